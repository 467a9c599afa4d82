// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The subcommands of the amrsp tool. Each returns the process exit code; errors are printed as
/// one line "amrsp: error: ..." on stderr.

#include "AmrspRenderOptions.h"
#include "AmrspSinglePass.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"

#include <glm/glm.hpp>

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the options, datasets, renderers and checks the commands use

int RunInspect(int argc, char** argv);
int RunReference(int argc, char** argv);
int RunRender(int argc, char** argv);
int RunBench(int argc, char** argv);

/// The dataset used when none is given: small enough to render in a second on two CPU cores.
extern const char* const DefaultDataset;

} // namespace tool
} // namespace amrsp
