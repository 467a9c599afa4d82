// SPDX-License-Identifier: BSD-3-Clause
#include "SinglePassAMRBaselineTest.h"

#include "AmrspCommands.h"
#include "AmrspDataset.h"
#include "AmrspPacking.h"

#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkTesting.h"

#include <cstdio>
#include <iostream>

namespace amrsp
{
namespace test
{

int RunBaselineTest(int argc, char* argv[], const BaselineCase& c)
{
  using namespace amrsp::tool;
  std::string why;
  if (!PackingRenderer::Available(why))
  {
    std::cout << "SKIPPED: " << why << "\n";
    return VTK_SKIP_RETURN_CODE;
  }
  std::string spec = c.Dataset;
  if (spec.rfind("data:", 0) == 0)
  {
    spec = std::string(AMRSP_DATA_DIR) + "/" + spec.substr(5);
    if (std::FILE* f = std::fopen(spec.c_str(), "r"))
    {
      std::fclose(f);
    }
    else
    {
      std::cout << "SKIPPED: " << spec << " not found (set AMRSP_DATA_DIR)\n";
      return VTK_SKIP_RETURN_CODE;
    }
  }

  std::vector<std::string> words = { "render", spec };
  words.insert(words.end(), c.Options.begin(), c.Options.end());
  std::vector<char*> args;
  for (std::string& w : words)
  {
    args.push_back(&w[0]);
  }
  try
  {
    const Arguments a = ParseArguments(static_cast<int>(args.size()), args.data(), 1,
      { "array", "centering", "size", "azimuth", "elevation", "zoom", "tf", "scale",
        "unit-distance", "sample-factor", "reference-sample-factor", "lod", "blend" },
      {});
    DatasetRequest request;
    request.Spec = spec;
    request.Array = a.Get("array", "");
    request.Centering = a.Get("centering", "auto");
    request.NeedVTK = false;
    LoadedDataset d = LoadDataset(request);
    RenderSettings s = MakeSettings(d.Data, a);
    ViewAngles view;
    view.Azimuth = a.GetNumber("azimuth", 30.0);
    view.Elevation = a.GetNumber("elevation", 20.0);
    view.Zoom = a.GetNumber("zoom", 1.0);

    PackingRenderer gpu(d.Data, s, view);
    double ms = 0.0;
    gpu.Render(0.0, ms);
    if (c.Adjust)
    {
      c.Adjust(gpu.GetRenderer());
      gpu.GetRenderer()->ResetCameraClippingRange();
    }
    const Image image = gpu.RenderAsIs(ms);

    // the independent check: the CPU reference of the very same view (no kD-tree), and the CPU
    // mirror of the shader (same segments, same level of detail)
    RenderSettings ref = s;
    ref.View = gpu.LastCamera();
    const double rmse = Rmse(image, RenderReference(d.Data, ref));
    const double mirror =
      Rmse(image, RenderKdTree(d.Data, EncodeKdTree(d.Data, BuildKdTree(d.Data)), ref));
    const bool agrees = rmse < c.ReferenceBound && mirror < 1.0;
    std::cout << (rmse < c.ReferenceBound ? "ok" : "FAILED")
              << ": GPU image vs CPU reference RMSE " << rmse << " (bound " << c.ReferenceBound
              << ")\n"
              << (mirror < 1.0 ? "ok" : "FAILED") << ": GPU image vs CPU kD-tree integrator RMSE "
              << mirror << " (bound 1)\n";

    vtkRenderWindow* window = gpu.GetRenderer()->GetRenderWindow();
    // vtkImageDifference ignores per-pixel differences below its own threshold and averages
    // the rest; 0.15 is under one badly wrong pixel (a wrong transfer function scores > 1)
    const int baseline = vtkRegressionTestImageThreshold(window, 0.15);
    return (agrees && baseline == vtkTesting::PASSED) ? 0 : 1;
  }
  catch (const std::exception& e)
  {
    std::cout << "FAILED: " << e.what() << "\n";
    return 1;
  }
}

} // namespace test
} // namespace amrsp
