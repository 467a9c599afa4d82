// SPDX-License-Identifier: BSD-3-Clause
// amrsp: command-line front end of the single-pass AMR volume renderer.
#include "AmrspCommands.h"
#include "AmrspMethods.h"

#include <cstring>
#include <iostream>
#include <string>

namespace
{
const char* const Usage =
  "usage: amrsp <command> [DATASET] [options]\n"
  "commands:\n"
  "  render      render a dataset to a PNG with the single-pass kD-tree raycaster\n"
  "  reference   render the independent CPU reference image (no kD-tree)\n"
  "  inspect     hierarchy, kD-tree and texture statistics (--json for machine use)\n"
  "  bench       timing, memory and image error of each rendering method\n"
  "`amrsp <command> --help` describes each command and the DATASET forms.\n";

/// The methods of each command, from the registry (AmrspMethods.h), wrapped at 100 columns.
void PrintMethods()
{
  using namespace amrsp::tool;
  std::cout << "methods (* renders through an OpenGL context):\n";
  const std::string indent(21, ' ');
  for (const unsigned command : { unsigned(RenderCommand), unsigned(BenchCommand) })
  {
    std::string line = command == RenderCommand ? "  render --method    " : "  bench --methods    ";
    bool first = true;
    for (const Method& m : Methods())
    {
      if (!(m.Commands & command))
      {
        continue;
      }
      const std::string item = m.Syntax() + (m.NeedsGpu ? "*" : "");
      if (!first && line.size() + 2 + item.size() > 100)
      {
        std::cout << line << ",\n";
        line = indent;
        first = true;
      }
      line += (first ? "" : ", ") + item;
      first = false;
    }
    std::cout << line << "\n";
  }
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
    !std::strcmp(argv[1], "help"))
  {
    std::cout << Usage;
    PrintMethods();
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  if (command == "render")
  {
    return amrsp::tool::RunRender(argc, argv);
  }
  if (command == "reference")
  {
    return amrsp::tool::RunReference(argc, argv);
  }
  if (command == "inspect")
  {
    return amrsp::tool::RunInspect(argc, argv);
  }
  if (command == "bench")
  {
    return amrsp::tool::RunBench(argc, argv);
  }
  std::cerr << "amrsp: error: unknown command '" << command << "' (see amrsp --help)\n";
  return 2;
}
