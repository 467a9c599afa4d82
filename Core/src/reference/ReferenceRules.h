// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The independent reference's own rules: transfer-function evaluation, opacity correction,
/// compositing and the blend modes, sampling (nearest, vertex trilinear, smooth cells), the
/// gradient, Blinn-Phong shading, shadow rays and iso-surface crossings. Written from the
/// specifications (amrsp/Render.h, amrsp/RenderSettings.h, amrsp/Shading.h,
/// amrsp/TransferFunction.h), not from the kD-tree integrator's code, in double precision and
/// textbook form: a rule that the shader and its CPU mirror get wrong alike differs here.
///
/// What the reference shares with the mirror is limited to data loading, the hierarchy (with the
/// tree-free FinestCellLocator), the camera and the row scheduler; Core.ReferenceIndependence
/// checks the includes of these files and the symbols of their objects.
///
/// Units: p, positions in level-0 index units; t, world distance along a unit world direction;
/// cell sizes in level-0 index units.

#include "amrsp/FinestCellLocator.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/RenderSettings.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{
namespace reference
{

/// Transfer-function evaluation (piecewise linear, clamped at the end points; log10-linear
/// between two positive control points under log scale, where a scalar <= 0 takes the first
/// point). Empty colour list: white; empty opacity list: 0.
glm::dvec3 ColourOf(const TransferFunction& tf, double scalar);
double OpacityOf(const TransferFunction& tf, double scalar);

/// The opacity of a ray length `length` (world units) through constant opacity `opacity` per
/// unit distance `unitDistance`: 1 - exp(ln(1 - opacity) length / unitDistance).
double CorrectedOpacity(double opacity, double length, double unitDistance);

/// Front-to-back emission-absorption in transmittance form: radiance L = sum_i T_i a_i c_i with
/// T_{i+1} = T_i (1 - a_i); the pixel is L + T * background, alpha 1 - T.
struct Compositor
{
  glm::dvec3 Radiance{ 0.0 };
  double Transmittance = 1.0;
  void Add(const glm::dvec3& colour, double alpha);
  double Alpha() const { return 1.0 - this->Transmittance; }
};

/// The data field as the reference samples it.
class Field
{
public:
  /// `smooth`: the smooth reconstruction of cell-centred data (ignored for vertex data).
  Field(const Hierarchy& h, const FinestCellLocator& locator, bool smooth);
  /// The value at p, NaN outside the root box and every grid; `level` (when given) receives the
  /// level of the finest grid there, -1 where there is none.
  double At(const glm::dvec3& p, int* level = nullptr) const;
  /// The nearest-cell (cell data) or trilinear (vertex data) value at p, NaN where absent.
  double Plain(const glm::dvec3& p, int* level = nullptr) const;
  /// The finest level containing p, -1 outside every grid and the root box.
  int LevelAt(const glm::dvec3& p) const;
  glm::dvec3 CellSizeOf(int level) const;
  const Hierarchy& Data() const { return this->H; }
  glm::dvec3 RootLo() const { return this->Lo; }
  glm::dvec3 RootHi() const { return this->Hi; }
  bool Smooth() const { return this->SmoothCells; }

private:
  int32_t FindGrid(const glm::dvec3& p, glm::i64vec3& cell) const;
  double VertexValue(int32_t grid, const glm::dvec3& p) const;
  double SmoothValue(int32_t grid, const glm::dvec3& p, double nearest) const;
  double CornerValue(int32_t grid, const glm::i64vec3& corner, int level, double nearest) const;

  const Hierarchy& H;
  const FinestCellLocator& Locator;
  bool SmoothCells;
  glm::dvec3 Lo{ 0.0 };
  glm::dvec3 Hi{ 0.0 };
};

/// The resolved light of a render (world units).
struct Light
{
  const Lighting* Settings = nullptr;
  bool Positional = false;
  glm::dvec3 Position{ 0.0 };
  glm::dvec3 Direction{ 0.0, 0.0, 1.0 }; ///< unit, toward the light (directional)
  glm::dvec3 ToLight(const glm::dvec3& world) const;
};
Light ResolveLight(const Lighting& settings, const Camera& camera);

/// Shading of samples and iso-surface hits.
class Shader
{
public:
  Shader(const Field& field, const Light& light, const TransferFunction& tf);
  /// The lit colour of `base` at p (value v, the level of the data there), seen along
  /// `towardEye` (unit world vector from the sample to the eye).
  glm::dvec3 Shade(const glm::dvec3& base, const glm::dvec3& p, double v, int level,
    const glm::dvec3& towardEye) const;
  /// The world-space gradient at p by central differences (amrsp/Shading.h's stencil).
  glm::dvec3 Gradient(const glm::dvec3& p, double v, int level) const;
  /// Transmittance of the shadow ray from p toward the light.
  double Transmittance(const glm::dvec3& p) const;

private:
  const Field& F;
  const Light& L;
  const TransferFunction& Tf;
};

/// One iso-surface crossing found between two samples.
struct Crossing
{
  double Distance; ///< from the first sample, index units
  double IsoValue;
  glm::dvec3 Hit;
};

/// The crossings of the iso-values between samples (pa, va) and (pb, vb), each located by
/// bisection with the field, in the order the ray meets them.
std::vector<Crossing> FindCrossings(const Field& field, const std::vector<double>& isoValues,
  const glm::dvec3& pa, double va, const glm::dvec3& pb, double vb);

} // namespace reference
} // namespace amrsp
