// SPDX-License-Identifier: BSD-3-Clause
// amrsp: command-line front end of the single-pass AMR volume renderer.
#include "AmrspCommands.h"

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
}

int main(int argc, char** argv)
{
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
    !std::strcmp(argv[1], "help"))
  {
    std::cout << Usage;
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
