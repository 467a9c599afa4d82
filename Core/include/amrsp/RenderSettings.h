// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What one render of the CPU integrators is asked to do (image size, camera, transfer
/// function, blending, sampling factors, shading, clipping) and the work counters it reports.
/// The integrators that read them are declared in amrsp/Render.h.

#include "amrsp/BlendMode.h"
#include "amrsp/Camera.h"
#include "amrsp/Lighting.h"
#include "amrsp/Progress.h"
#include "amrsp/RayCaster.h"
#include "amrsp/RayLoop.h"
#include "amrsp/TransferFunction.h"

#include <glm/glm.hpp>

#include <functional>
#include <vector>

namespace amrsp
{

/// Work counters of one render (summed over all rays), to show what the accelerations did.
struct RenderStats
{
  long long Rays = 0;            ///< rays that entered the root box
  long long Samples = 0;         ///< samples taken (transfer function evaluated or kept)
  long long DataSegments = 0;    ///< segments through data nodes reached by a ray
  long long SkippedSegments = 0; ///< ... of which skipped as transparent (empty-space skipping)
  long long SkippedSamples = 0;  ///< samples those skipped segments would have taken
  long long TerminatedRays = 0;  ///< rays stopped early at the opacity threshold
  long long Segments = 0;        ///< kD-tree integrator: all traversal segments, empty included
  long long DescentLevels = 0;   ///< ... and the tree levels their descents went down in all
};

struct RenderSettings
{
  int Width = 256;
  int Height = 256;
  Camera View;
  TransferFunction Transfer;
  glm::dvec3 Background{ 0.0 };
  double SampleDistanceFactor = 1.0;
  double ReferenceSampleFactor = 0.5;
  float LodThresholdPixels = 0.0f; ///< kD-tree integrator only; 0 = always the finest level
  BlendMode Blend = BlendMode::Composite;
  /// Optional opaque geometry in the scene (as the depth buffer the GPU mapper reads): for a
  /// world ray (origin, unit direction) it returns true with the distance and the colour of the
  /// nearest opaque hit; the ray then ends there and that colour replaces the background.
  std::function<bool(
    const glm::dvec3& origin, const glm::dvec3& direction, double& distance, glm::dvec3& colour)>
    Opaque;
  int Threads = 0; ///< 0 = hardware concurrency
  /// When set, the CPU integrators report the fraction of image rows done (amrsp/Progress.h).
  ProgressCallback Progress;
  /// The single-pass mapper's DiagnosticAblation (0 none, 1 traversal only, 2 sampling only)
  /// and DiagnosticAblationSamples; not used by the CPU integrators.
  int GpuAblation = 0;
  /// The single-pass mapper's RayLoop (the image is the same); not used by the CPU integrators.
  RayLoop GpuRayLoop = RayLoop::Nested;
  /// The single-pass mapper's RayCaster (the image is the same); not used by the CPU integrators.
  RayCaster GpuRayCaster = RayCaster::Auto;
  int GpuAblationSamples = 256;
  /// GPU mappers' MaximumAtlasPageBytes (the largest atlas texture; larger atlases are split
  /// into pages); 0 keeps the mapper's default. Not used by the CPU integrators.
  long long AtlasPageBytes = 0;
  /// Early ray termination (composite blending): a ray stops once its accumulated opacity
  /// reaches this value. 1 (the default here) never stops a ray early; the GPU mapper's default
  /// is 0.999.
  double OpacityThreshold = 1.0;
  /// Empty-space skipping (kD-tree integrator, composite blending): a data segment whose node's
  /// value range (ComputeDataNodeRanges) has zero opacity under the transfer function
  /// (TransparentRange) is not sampled. The image is unchanged: every skipped sample would have
  /// had zero opacity. The reference ignores it (it is what skipping is checked against).
  bool SkipEmptySpace = false;
  /// Neighbour links (kD-tree integrator, as the GPU mapper's Ropes): a ray leaving a leaf
  /// through one face continues from that face's rope (amrsp/KdTreeRopes.h) instead of a
  /// descent from the restart node. The segments, and so the image, are the same either way;
  /// only the work differs (amrsp/WorkCounters.h).
  bool Ropes = true;
  /// Precomputed ComputeDataNodeRanges of the tree being rendered; computed when null.
  const std::vector<glm::vec2>* DataNodeRanges = nullptr;
  /// When set, receives the work counters of the render.
  RenderStats* Stats = nullptr;
  /// Smooth reconstruction of cell-centred data (all three integrators; vertex-centred data is
  /// trilinear anyway). A sample at p whose level is d (the segment's data level; the reference:
  /// the finest grid at p) is the trilinear interpolation, in the dual cell of level d that
  /// contains p, of its 8 corners: the level-d cell centres x around p. A corner that is a cell
  /// of the sample's grid (covered by finer grids or not) takes that cell; any other the leaf at
  /// x (kD integrators: point location in the tree; reference: straight from the grids): its
  /// nearest cell when the leaf's level m >= d, else the trilinear value of level m at x from
  /// the leaf's grid's cells (or, where that grid has none, the nearest cell of the leaf there).
  /// A corner outside every grid takes the nearest-cell value at p. Linear-exact across level
  /// boundaries where covered cells hold the field at their centres (docs/design.md, "Smooth
  /// cell-centred data"). With shading, the gradient's central differences, iso-surface bisection
  /// and shadow rays read the same reconstruction (each at the level of the finest data there):
  /// ShadingContext::Neighbours and the integrators' point lookup.
  bool SmoothCellData = false;
  /// Gradient shading and shadow rays (composite and iso-surface blending; amrsp/Shading.h).
  Lighting Light;
  /// Iso-values of BlendMode::IsoSurface (at most MaxIsoValues), in the scalar's units.
  std::vector<double> IsoValues;
  /// Clip box, world units (vtkVolumeMapper's cropping of the central sub-volume,
  /// VTK_CROP_SUBVOLUME): with Clip on, every ray is integrated only where it lies inside
  /// [ClipLo, ClipHi]; samples are placed as if the data ended at the box (a segment starts at
  /// the box face). Point lookups (smooth corners, gradient neighbours, shadow rays, iso-surface
  /// refinement) still read data outside it.
  bool Clip = false;
  glm::dvec3 ClipLo{ 0.0 };
  glm::dvec3 ClipHi{ 0.0 };
};

/// The ray parameter interval [t0, t1] (world distance along the unit direction `wd` from `wo`)
/// inside the settings' clip box: false when the ray misses it; (-inf, inf) without Clip.
bool ClipInterval(
  const RenderSettings& s, const glm::dvec3& wo, const glm::dvec3& wd, double& t0, double& t1);

} // namespace amrsp
