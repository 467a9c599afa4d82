// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What the amrsp subcommands share, internal to the tool: option lists and help texts, loading
/// the dataset the command line names, the atlas options, small output helpers.

// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspCommands.h"
#include "AmrspDataset.h"

#include "amrsp/BrickPacking.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include <glm/glm.hpp>

#include <chrono>
#include <initializer_list>
#include <exception>
#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

/// Seconds since `since`.
double Seconds(Clock::time_point since);
/// Prints "amrsp: error: MESSAGE" and returns the exit code 1.
int Fail(const std::string& message);
/// The same for an exception: its message, and the exit code of a reader that crashed (70) or
/// did not finish in time (75) (ReaderFailure, AmrspIsolatedRead.h), else 1.
int Fail(const std::exception& e);
/// Whether --help was given.
bool WantsHelp(const Arguments& a);

/// The options every command taking a dataset accepts, and the view and atlas options.
extern const std::vector<std::string> DatasetOptions;
extern const std::vector<std::string> DatasetFlags;
extern const std::vector<std::string> AtlasOptions;
std::vector<std::string> Concat(std::initializer_list<std::vector<std::string>> lists);
extern const char* const DatasetHelp;
extern const char* const AtlasHelp;
extern const char* const ViewHelp;

/// The dataset the command line names (DATASET and the dataset options).
LoadedDataset Load(const Arguments& a, bool needValues, bool needVTK);
/// The same for the dataset `spec` instead of DATASET (a step of a series).
LoadedDataset Load(const Arguments& a, const std::string& spec, bool needValues, bool needVTK);

/// Packing settings from the command line.
struct AtlasRequest
{
  Packer Algorithm = Packer::Best;
  glm::ivec3 MaxDims{ 2048 };
  std::size_t MaxBytes = 0;
};
AtlasRequest ParseAtlasRequest(const Arguments& a);
Json AtlasJson(const AtlasLayout& layout);

void WritePng(const Image& img, const std::string& path);
Json BoxJson(const glm::dvec3& lo, const glm::dvec3& hi);
Json TextureJson(const UIntTexture3D& t);

} // namespace tool
} // namespace amrsp
