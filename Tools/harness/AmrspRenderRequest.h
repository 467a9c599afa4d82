// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The render options as values: what `amrsp render --size --tf --scale ...` asks for
/// (docs/command-line.md), before any hierarchy is known. ParseRenderRequest reads them from the
/// option words; a test fills one directly. MakeSettings (AmrspRenderOptions.h) turns a request
/// and a hierarchy into RenderSettings with the conventions of docs/design.md.

#include "AmrspArguments.h"

#include "amrsp/BlendMode.h"
#include "amrsp/RayCaster.h"
#include "amrsp/RayLoop.h"

#include <glm/glm.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace amrsp
{
namespace harness
{

struct RenderRequest
{
  int Width = 512; ///< --size WxH
  int Height = 512;
  std::string
    ViewJson; ///< --view-json: a file with the camera, transfer function, light (empty: none)
  /// --azimuth, --elevation (degrees, after ResetCamera) and --zoom; unset: 30, 20, 1 (and no
  /// change of a --view-json camera)
  std::optional<double> Azimuth;
  std::optional<double> Elevation;
  std::optional<double> Zoom;
  std::optional<std::string> Tf; ///< --tf preset; unset: "default"
  std::optional<std::string>
    Scale;                    ///< --scale auto|linear|log; unset: auto (linear for a file's TF)
  std::string Range = "step"; ///< --range all|step|LO:HI
  std::optional<double> UnitDistance;     ///< --unit-distance; unset: the file's, or diagonal / 100
  double SampleFactor = 1.0;              ///< --sample-factor
  double ReferenceSampleFactor = 0.5;     ///< --reference-sample-factor
  double Lod = 0.0;                       ///< --lod (pixels)
  double AtlasPageMiB = 0.0;              ///< --atlas-page-mib (0: the mapper's default)
  BlendMode Blend = BlendMode::Composite; ///< --blend
  bool Shade = false;                     ///< --shade on|off
  double ShadowStep = 0.0;                ///< --shadows (world units; 0: off)
  std::optional<glm::dvec3> Light;        ///< --light X,Y,Z (a positional light)
  /// --iso: iso-values as fractions of the transfer function's range (1 to 8); unset: 0.5
  std::optional<std::vector<double>> Iso;
  int Threads = 0;                    ///< --threads (0: hardware concurrency)
  double OpacityThreshold = 0.999;    ///< --opacity-threshold
  bool SkipEmptySpace = true;         ///< --empty-space-skipping on|off
  bool Ropes = true;                  ///< --ropes on|off
  RayLoop Loop = RayLoop::Nested;     ///< --loop
  RayCaster Caster = RayCaster::Auto; ///< --caster
  int Ablation = 0;                   ///< --ablation: 0 none, 1 traversal-only, 2 sampling-only
  int AblationSamples = 256;          ///< --ablation sampling-only:N
  bool SmoothCells = false;           ///< --interpolation smooth
  std::optional<std::array<double, 6>> Crop; ///< --crop X0,X1,Y0,Y1,Z0,Z1 (world units)
};

/// The request the option words of `a` make. Throws UsageError for a malformed or out-of-range
/// value (the checks that need the data or a --view-json file are MakeSettings').
RenderRequest ParseRenderRequest(const Arguments& a);

} // namespace harness
} // namespace amrsp
