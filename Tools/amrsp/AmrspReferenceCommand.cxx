// SPDX-License-Identifier: BSD-3-Clause
// `amrsp reference`: the independent CPU reference image.
// first: see AmrspJson.h
#include "AmrspImageCommand.h"
#include "AmrspProgress.h"

#include "amrsp/Render.h"

#include <iostream>
#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

int RunReference(int argc, char** argv)
{
  const std::string name = "reference";
  try
  {
    const Arguments a =
      ParseArguments(argc, argv, 1, ImageValueOptions(), Concat({ DatasetFlags, { "stats" } }));
    if (WantsHelp(a))
    {
      std::cout << "usage: amrsp reference [DATASET] [-o FILE.png] [view options] [dataset "
                   "options]\n"
                   "Renders the independent CPU reference image: no kD-tree; each sample finds "
                   "the finest\n"
                   "cell containing it directly from the hierarchy's boxes.\n"
                << ImageOptionsHelp(name) << ViewHelp << DatasetHelp;
      return 0;
    }
    if (a.Positional.size() > 2)
    {
      throw UsageError{ "unexpected argument '" + a.Positional[2] + "'" };
    }
    ParseAtlasRequest(a); // the atlas options are accepted (and checked) as render's
    const std::string output = a.Get("output", name + ".png");
    LoadedDataset d = Load(a, true, false);
    glm::dvec2 range;
    RenderSettings s = MakeSettings(d.Data, a, &range);
    const int repeat = RepeatCount(a);
    RenderStats stats;
    s.Stats = &stats;
    ImageRun run;
    s.Progress = ProgressOf("reference");
    for (int k = 0; k < repeat; ++k)
    {
      const auto t0 = Clock::now();
      run.Img = RenderReference(d.Data, s);
      run.FrameMs.push_back(1000.0 * Seconds(t0));
    }
    run.StatsReport = CpuStatsReport(stats);
    WriteImageReport("cpu-reference", d, a, s, range, output, repeat, run);
    WarnIfNearlyEmpty(run.Img);
    return 0;
  }
  catch (const UsageError& e)
  {
    return Fail(e.Message + " (see amrsp " + name + " --help)");
  }
  catch (const std::exception& e)
  {
    return Fail(e);
  }
}

} // namespace tool
} // namespace amrsp
