// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Gradient shading, iso-surfaces and shadow rays of the CPU integrators, written against a point
/// lookup so that the reference (finest grid found from the hierarchy's boxes) and the kD-tree
/// integrator (descent of the encoded tree, as the shader's amrspSampleAtPoint) share the rules.
/// The GLSL raycaster (Shaders/SinglePassAMRRay.glsl, in both casters) implements the same rules:
///
/// - Lookup: the scalar at a point p (level-0 index units) and the cell size (level-0 index units)
///   of the level it comes from; absent (NaN) outside every grid and outside the root box.
/// - Gradient at a sample p of value v whose level has cell size h (index units): per axis a
///   central difference (f(b + h_a e_a) - f(b - h_a e_a)) / (2 h_a s_a), s = level-0 spacing
///   (world units per index unit). b is p for a continuous field (vertex data, smooth cells); for
///   nearest cells (ShadingContext::CellStencil) b is the centre of p's cell, (floor(p / h) +
///   1/2) h, so the stencil is that cell's neighbours: the sampling rule puts samples exactly on
///   cell faces (the middle sample of a segment between two faces of one axis), where p's last
///   bit, which a compiler's contraction or order of operations decides, would otherwise pick the
///   stencil, and a neighbour one cell inside the domain or outside it. An absent neighbour is
///   replaced by v and the difference becomes
///   one-sided (denominator h_a s_a); both absent gives 0. The neighbours may lie in other grids
///   and other levels: the lookup finds them. The neighbour values come from
///   ShadingContext::Neighbours when set (the integrators set it to the smooth reconstruction
///   under RenderSettings::SmoothCellData, so that the gradient is the one of the sampled field),
///   else from the point lookup.
/// - Shading (Blinn-Phong, two-sided; vtkVolumeProperty's Ambient Ka, Diffuse Kd, Specular Ks,
///   SpecularPower n): N = gradient / |gradient| turned toward the viewer V (unit vector to the
///   eye), L = unit vector to the light (positional: from the sample to the light position;
///   directional: from the light's focal point to its position), H = normalize(L + V);
///   rgb = Ka c + T Lc (Kd max(N.L, 0) c + Ks max(N.H, 0)^n [N.L > 0]), clamped to [0, 1]; a zero
///   gradient has no diffuse or specular part. Lc: the light colour (diffuse colour x intensity);
///   T: the shadow transmittance (1 without shadows).
/// - Unshaded with shadows: rgb = clamp(c (Ka + Kd T Lc)), as a sample facing the light.
/// - Shadow ray from a sample at world point x toward the light (positional: up to the light;
///   directional: along L), clipped to the root box: steps of ShadowStep (world units), samples at
///   the step midpoints t_k = (k + 1/2) ShadowStep, T = product of (1 - opacity(f))^(ShadowStep /
///   UnitDistance) over the present samples; it stops when T < ShadowMinTransmittance or after
///   ShadowMaxSteps samples.
/// - Iso-surfaces: between two consecutive present samples a (value va) and b (vb) along the ray,
///   an iso-value c is crossed when (va < c) != (vb < c); the crossings of one pair are taken in
///   the order the ray meets them (ascending values when vb > va). Each is refined by
///   IsoRefineSteps bisections on the segment [a, b] with the lookup (absent midpoint: refinement
///   stops); the hit is the far end of the final interval. Its colour is the transfer function's
///   colour at c, shaded at the hit (with the level found there), and its opacity the transfer
///   function's opacity at c (no unit-distance correction, as VTK's iso-surface blend). Missing
///   data between two samples (absent sample or empty space) breaks the pairing.

#include "amrsp/Lighting.h"
#include "amrsp/PointLookup.h"

#include <glm/glm.hpp>

#include <functional>
#include <vector>

namespace amrsp
{

struct TransferFunction;

constexpr int ShadowMaxSteps = 4096;
constexpr double ShadowMinTransmittance = 1e-3;
constexpr int IsoRefineSteps = 8;
constexpr int MaxIsoValues = 8;

/// Per-render constants of the shading rules.
struct ShadingContext
{
  const Lighting* Light = nullptr;
  const TransferFunction* Transfer = nullptr;
  glm::dvec3 Origin{ 0.0 };   ///< world position of index (0, 0, 0)
  glm::dvec3 Spacing0{ 1.0 }; ///< world size of a level-0 cell
  glm::dvec3 RootLo{ 0.0 };   ///< root box, level-0 index units
  glm::dvec3 RootHi{ 0.0 };
  glm::dvec3 LightPosition{ 0.0 }; ///< resolved for the camera (headlight) in world units
  glm::dvec3 LightDirection{ 0.0, 0.0, 1.0 }; ///< unit, toward the light (directional lights)
  bool Positional = false;
  /// The lookup of the gradient's neighbours; empty: the point lookup passed to the rules (which
  /// shadow rays and iso-surface refinement always use).
  PointLookup Neighbours;
  /// Nearest-cell data: the gradient's stencil is the neighbours of the sample's cell, at their
  /// centres (see the gradient rule above); false for a continuous field (vertex data, smooth
  /// cells), where it is p's.
  bool CellStencil = false;
};

/// Resolves the light for a camera (position and focal point in world units).
ShadingContext MakeShadingContext(const Lighting& light, const TransferFunction& tf,
  const glm::dvec3& origin, const glm::dvec3& spacing0, const glm::dvec3& rootLo,
  const glm::dvec3& rootHi, const glm::dvec3& cameraPosition, const glm::dvec3& cameraFocalPoint);

/// World-space gradient at p (index units) with value v and neighbour distance cellSize.
glm::dvec3 Gradient(const ShadingContext& c, const PointLookup& f, const glm::dvec3& p, double v,
  const glm::dvec3& cellSize);

/// Shadow transmittance from p (index units) toward the light.
double ShadowTransmittance(const ShadingContext& c, const PointLookup& f, const glm::dvec3& p);

/// The lit colour of base colour `rgb` at p (index units) of value v; `towardEye` is the unit
/// world vector from the sample to the eye (minus the ray direction).
glm::dvec3 ShadeSample(const ShadingContext& c, const PointLookup& f, const glm::dvec3& rgb,
  const glm::dvec3& p, double v, const glm::dvec3& cellSize, const glm::dvec3& towardEye);

/// Iso-surface crossings of one ray, composited front to back into (colour, alpha) as they are
/// found. Feed every sample in ray order; Break() where data is missing.
class IsoSurfaceTracker
{
public:
  IsoSurfaceTracker(const ShadingContext& c, const PointLookup& f,
    const std::vector<double>& sortedValues, const glm::dvec3& towardEye)
    : C(c)
    , F(f)
    , Values(sortedValues)
    , TowardEye(towardEye)
  {
  }
  void Sample(const glm::dvec3& p, double v, glm::dvec3& colour, double& alpha);
  void Break() { HavePrevious = false; }

private:
  const ShadingContext& C;
  const PointLookup& F;
  const std::vector<double>& Values;
  glm::dvec3 TowardEye;
  bool HavePrevious = false;
  glm::dvec3 PreviousP{ 0.0 };
  double PreviousV = 0.0;
};

} // namespace amrsp
