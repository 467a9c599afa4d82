// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// CPU ray integration with the conventions the mapper uses, so that images can be compared:
///
/// - Camera: VTK's. A pinhole at Position looking at FocalPoint, ViewAngle the full vertical
///   angle in degrees; or parallel projection with ParallelScale = half the view height (world).
///   Pixel (i, j) is sampled through its centre; row 0 is the bottom row (as vtkImageData).
/// - Transfer function: VTK's vtkColorTransferFunction / vtkPiecewiseFunction with clamping:
///   piecewise linear in the scalar, constant beyond the end points.
/// - Emission-absorption, front to back, premultiplied: C += (1 - A) a c; A += (1 - A) a, where a
///   sample that represents a ray length dt has a = 1 - (1 - opacity(s))^(dt / UnitDistance)
///   (vtkVolumeProperty's ScalarOpacityUnitDistance). The pixel is C + (1 - A) * Background.
/// - Sampling rule of the kD-tree integrator (and of the GPU shader): a segment of data level d,
///   [t0, t1], is cut into n = max(1, ceil((t1 - t0) / D)) equal steps, D = SampleDistanceFactor
///   times the smallest world-space edge of a level-d cell; samples sit at the step midpoints.
///   Cell-centred data is sampled nearest-cell.
/// - Reference integrator: no kD-tree. It marches the root box with steps of
///   ReferenceSampleFactor times the smallest edge of the finest cell at the current point, found
///   directly from the hierarchy (finest grid containing the point), and samples step midpoints.

#include "amrsp/BrickAtlas.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Shading.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace amrsp
{

struct Camera
{
  glm::dvec3 Position{ 0.0, 0.0, 1.0 };
  glm::dvec3 FocalPoint{ 0.0 };
  glm::dvec3 ViewUp{ 0.0, 1.0, 0.0 };
  double ViewAngle = 30.0; ///< degrees, full vertical angle
  bool Parallel = false;
  double ParallelScale = 1.0;

  /// World-space ray through the pixel position (px, py) in [0, width] x [0, height].
  void Ray(int width, int height, double px, double py, glm::dvec3& origin,
    glm::dvec3& direction) const;

  /// vtkRenderer::ResetCamera for the box [lo, hi] seen along -z with +y up: focal point at the
  /// centre, distance = half diagonal / sin(ViewAngle / 2), ParallelScale = half diagonal.
  static Camera ResetTo(const glm::dvec3& lo, const glm::dvec3& hi);
  /// vtkCamera::Azimuth: rotates the position about ViewUp through the focal point (degrees).
  void Azimuth(double degrees);
  /// vtkCamera::Elevation: rotates the position about the camera's left axis (degrees).
  void Elevation(double degrees);
  /// vtkCamera::OrthogonalizeViewUp.
  void OrthogonalizeViewUp();
  /// vtkCamera::Zoom: divides ViewAngle (perspective) or ParallelScale (parallel).
  void Zoom(double factor);
};

struct TransferFunction
{
  struct ColorPoint
  {
    double X;
    glm::dvec3 Rgb;
  };
  struct OpacityPoint
  {
    double X;
    double Opacity;
  };
  std::vector<ColorPoint> Color;     ///< sorted by X
  std::vector<OpacityPoint> Opacity; ///< sorted by X
  double UnitDistance = 1.0;         ///< world length over which Opacity applies unchanged

  glm::dvec3 EvaluateColor(double s) const;
  double EvaluateOpacity(double s) const;

  /// A named preset spanning [lo, hi]: "default" (blue-white-red, opacity ramp), "grey",
  /// "hot", "grey-opaque" (grey levels at opacity 1, for the intensity projections), "sparse"
  /// ("hot" colours, zero opacity below 60 % of the range: for empty-space skipping). Throws
  /// std::invalid_argument for an unknown name.
  static TransferFunction Preset(const std::string& name, double lo, double hi,
    double unitDistance);
  static std::vector<std::string> PresetNames();
};

/// vtkVolumeMapper's blend modes. Maximum/Minimum keep the extreme scalar along the ray,
/// Average its length-weighted mean; the pixel is then the transfer function's colour and
/// (uncorrected) opacity of that scalar over the background. IsoSurface composites the crossings
/// of RenderSettings::IsoValues (rules in amrsp/Shading.h).
enum class BlendMode
{
  Composite,
  Maximum,
  Minimum,
  Average,
  IsoSurface
};

/// Work counters of one render (summed over all rays), to show what the accelerations did.
struct RenderStats
{
  long long Rays = 0;             ///< rays that entered the root box
  long long Samples = 0;          ///< samples taken (transfer function evaluated or kept)
  long long DataSegments = 0;     ///< segments through data nodes reached by a ray
  long long SkippedSegments = 0;  ///< ... of which skipped as transparent (empty-space skipping)
  long long SkippedSamples = 0;   ///< samples those skipped segments would have taken
  long long TerminatedRays = 0;   ///< rays stopped early at the opacity threshold
  long long Segments = 0;         ///< kD-tree integrator: all traversal segments, empty included
  long long DescentLevels = 0;    ///< ... and the tree levels their descents went down in all
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
  std::function<bool(const glm::dvec3& origin, const glm::dvec3& direction, double& distance,
    glm::dvec3& colour)>
    Opaque;
  int Threads = 0;                 ///< 0 = hardware concurrency
  /// Early ray termination (composite blending): a ray stops once its accumulated opacity
  /// reaches this value. 1 (the default here) never stops a ray early; the GPU mapper's default
  /// is 0.999.
  double OpacityThreshold = 1.0;
  /// Empty-space skipping (kD-tree integrator, composite blending): a data segment whose node's
  /// value range (ComputeDataNodeRanges) has zero opacity under the transfer function
  /// (TransparentRange) is not sampled. The image is unchanged: every skipped sample would have
  /// had zero opacity. The reference ignores it (it is what skipping is checked against).
  bool SkipEmptySpace = false;
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
  /// boundaries where covered cells hold the field at their centres (README, "Smooth cell-centred
  /// data"). With shading, the gradient's central differences, iso-surface bisection and shadow
  /// rays read the same reconstruction (each at the level of the finest data there):
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
bool ClipInterval(const RenderSettings& s, const glm::dvec3& wo, const glm::dvec3& wd, double& t0,
  double& t1);

/// RGBA float image, row 0 at the bottom. Alpha is the accumulated opacity.
struct Image
{
  int Width = 0;
  int Height = 0;
  std::vector<glm::vec4> Pixels;

  /// 8-bit RGB, rows bottom to top (vtkImageData order).
  std::vector<std::uint8_t> Rgb8() const;
};

/// Root-mean-square difference of the RGB channels in 0-255 units.
double Rmse(const Image& a, const Image& b);
double Rmse8(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);

/// Finds the finest grid cell containing a point straight from the hierarchy's boxes (per-level
/// uniform buckets), with no kD-tree: the reference's independent lookup.
class FinestCellLocator
{
public:
  explicit FinestCellLocator(const Hierarchy& h);
  /// Point in level-0 index units. Returns the grid index (or -1 outside every grid) and the
  /// cell of that grid containing the point.
  int32_t Find(const glm::dvec3& p, glm::i64vec3& cell) const;

private:
  struct LevelBuckets
  {
    glm::dvec3 Lo{ 0.0 };
    glm::dvec3 BucketSize{ 1.0 };
    glm::ivec3 Count{ 0 };
    std::vector<std::vector<int32_t>> Grids;
  };
  const Hierarchy& H;
  std::vector<LevelBuckets> Levels;
  std::vector<glm::dvec3> CumRatio;
};

/// Value of grid `g` at cell `cell` (clamped into the grid). Requires cell-centred values.
float CellValue(const Hierarchy& h, int32_t g, glm::i64vec3 cell);

/// The kD-tree integrator's point lookup (mirrors the shader's amrspSampleAtPoint): descends the
/// encoded tree from the root to the leaf containing p (level-0 index units; the lower child when
/// p[axis] < the node's float split plane) and samples that leaf's grid as the integrator does.
/// Returns NaN outside the root box or in a leaf without data; cellSize is the leaf's data-level
/// cell size (level-0 index units).
double SampleKdTreeAtPoint(const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p,
  glm::vec3& cellSize);

/// The kD-tree integrator's point lookup for the shading rules (PointLookup): point location in
/// the encoded tree (as the shader's amrspLocateDataNode; outside the root box or in a leaf without
/// data: NaN), then the leaf's brick, read from the grid or, with `atlas`, through the data node's
/// atlas offset; cellSize: the leaf's data-level cell size. `smooth` (cell-centred data only):
/// the smooth reconstruction of RenderSettings::SmoothCellData at the leaf's level, as the
/// sample loop computes it (the gradient's neighbours under SmoothCellData); otherwise the same
/// value as SampleKdTreeAtPoint. The lookup refers to h, tree and atlas, which must outlive it.
PointLookup KdTreePointLookup(const Hierarchy& h, const EncodedKdTree& tree, bool smooth,
  const BrickAtlas* atlas = nullptr);

/// The reference's point lookup: the finest grid containing the point, found by `locator` (no
/// kD-tree); NaN outside the root box and every grid; cellSize: that grid's cell size. `smooth`
/// (cell-centred data only): the reference's smooth reconstruction at the finest level there.
/// Refers to h and locator, which must outlive it.
PointLookup ReferencePointLookup(const Hierarchy& h, const FinestCellLocator& locator, bool smooth);

/// Renders with the CPU kD-tree integrator over the encoded textures. Without `atlas`, samples
/// come from the grid named by each data node; with it, from the packed atlas through the data
/// nodes' atlas offsets, exactly as the packing shader addresses it (the tree must then have been
/// encoded with that atlas's origins). A NaN sample is transparent.
Image RenderKdTree(const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s,
  const BrickAtlas* atlas = nullptr);
/// The scalar the kD-tree integrator samples at p (level-0 index units; cell-centred data),
/// nearest-cell or smooth (RenderSettings::SmoothCellData), at the finest level there. NaN
/// outside every grid.
float SampleKdTreePoint(const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p,
  bool smooth);

/// Renders the independent reference (no kD-tree).
Image RenderReference(const Hierarchy& h, const RenderSettings& s);

/// The samples the kD-tree integrator takes along one world-space ray: position in level-0
/// index units (double, computed from the float segment bounds), the grid sampled and its cell.
struct TreeSample
{
  glm::dvec3 Position;
  int32_t Grid;
  glm::i64vec3 Cell;
};
void SampleRayKdTree(const Hierarchy& h, const EncodedKdTree& tree, const glm::dvec3& origin,
  const glm::dvec3& direction, double sampleDistanceFactor, std::vector<TreeSample>& samples);

} // namespace amrsp
