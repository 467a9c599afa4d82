// SPDX-License-Identifier: BSD-3-Clause
// The reference's gradient, Blinn-Phong shading, shadow rays and iso-surface crossings
// (the rules of amrsp/Shading.h).
#include "ReferenceRules.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace amrsp
{
namespace reference
{
namespace
{
/// Bisection steps locating an iso-surface crossing: the reference locates it to 2^-20 of the
/// sample spacing (the shader's 8 steps are an approximation of this root).
constexpr int CrossingBisections = 20;
/// The shadow ray's limits (amrsp/Shading.h): at most this many samples, and it stops once the
/// transmittance is below the floor.
constexpr int ShadowSamplesAtMost = 4096;
constexpr double ShadowTransmittanceFloor = 1e-3;

glm::dvec3 Clamp01(const glm::dvec3& c)
{
  return glm::dvec3(std::min(std::max(c.x, 0.0), 1.0), std::min(std::max(c.y, 0.0), 1.0),
    std::min(std::max(c.z, 0.0), 1.0));
}
} // namespace

glm::dvec3 Light::ToLight(const glm::dvec3& world) const
{
  if (!this->Positional)
  {
    return this->Direction;
  }
  const glm::dvec3 v = this->Position - world;
  const double n = std::sqrt(glm::dot(v, v));
  return n > 0.0 ? v / n : this->Direction;
}

Light ResolveLight(const Lighting& settings, const Camera& camera)
{
  Light l;
  l.Settings = &settings;
  l.Positional = settings.Positional && !settings.Headlight;
  l.Position = settings.Headlight ? camera.Position : settings.Position;
  const glm::dvec3 focal = settings.Headlight ? camera.FocalPoint : settings.FocalPoint;
  const glm::dvec3 v = l.Position - focal;
  const double n = std::sqrt(glm::dot(v, v));
  l.Direction = n > 0.0 ? v / n : glm::dvec3(0.0, 0.0, 1.0);
  return l;
}

Shader::Shader(const Field& field, const Light& light, const TransferFunction& tf)
  : F(field)
  , L(light)
  , Tf(tf)
{
}

glm::dvec3 Shader::Gradient(const glm::dvec3& p, double v, int level) const
{
  const Hierarchy& h = this->F.Data();
  const glm::dvec3 size = this->F.CellSizeOf(level);
  // nearest cells: the stencil around the centre of p's cell; a continuous field: around p
  glm::dvec3 centre = p;
  if (!h.VertexCentred && !this->F.Smooth())
  {
    centre = (glm::floor(p / size) + 0.5) * size;
  }
  glm::dvec3 gradient(0.0);
  for (int a = 0; a < 3; ++a)
  {
    glm::dvec3 step(0.0);
    step[a] = size[a];
    const double ahead = this->F.At(centre + step);
    const double behind = this->F.At(centre - step);
    const double world = size[a] * h.Spacing0[a];
    if (!std::isnan(ahead) && !std::isnan(behind))
    {
      gradient[a] = (ahead - behind) / (2.0 * world);
    }
    else if (!std::isnan(ahead))
    {
      gradient[a] = (ahead - v) / world;
    }
    else if (!std::isnan(behind))
    {
      gradient[a] = (v - behind) / world;
    }
  }
  return gradient;
}

double Shader::Transmittance(const glm::dvec3& p) const
{
  const Hierarchy& h = this->F.Data();
  const Lighting& s = *this->L.Settings;
  const glm::dvec3 x = h.Origin + p * h.Spacing0;
  double reach = std::numeric_limits<double>::infinity();
  if (this->L.Positional)
  {
    const glm::dvec3 v = this->L.Position - x;
    reach = std::sqrt(glm::dot(v, v));
    if (!(reach > 0.0))
    {
      return 1.0;
    }
  }
  const glm::dvec3 dir = this->L.ToLight(x) / h.Spacing0; // index units per world unit
  // where the ray leaves the root box
  const glm::dvec3 lo = this->F.RootLo(), hi = this->F.RootHi();
  for (int a = 0; a < 3; ++a)
  {
    if (dir[a] > 0.0)
    {
      reach = std::min(reach, (hi[a] - p[a]) / dir[a]);
    }
    else if (dir[a] < 0.0)
    {
      reach = std::min(reach, (lo[a] - p[a]) / dir[a]);
    }
  }
  // optical depth: sum over the samples of -ln(1 - opacity) x step / unit distance
  double depth = 0.0;
  const double floorDepth = -std::log(ShadowTransmittanceFloor);
  for (int k = 0; k < ShadowSamplesAtMost; ++k)
  {
    const double t = (k + 0.5) * s.ShadowStep;
    if (!(t < reach))
    {
      break;
    }
    const double v = this->F.At(p + t * dir);
    if (std::isnan(v))
    {
      continue;
    }
    const double opacity = std::min(1.0, OpacityOf(this->Tf, v));
    depth += -std::log1p(-opacity) * s.ShadowStep / this->Tf.UnitDistance;
    if (depth > floorDepth)
    {
      break;
    }
  }
  return std::exp(-depth);
}

glm::dvec3 Shader::Shade(const glm::dvec3& base, const glm::dvec3& p, double v, int level,
  const glm::dvec3& towardEye) const
{
  const Lighting& s = *this->L.Settings;
  const double shadow = s.Shadows ? this->Transmittance(p) : 1.0;
  if (!s.Shade)
  {
    // unshaded with shadows: as a sample facing the light
    return Clamp01(base * (s.Ambient + s.Diffuse * shadow * s.Colour));
  }
  const Hierarchy& h = this->F.Data();
  const glm::dvec3 lightDir = this->L.ToLight(h.Origin + p * h.Spacing0);
  const glm::dvec3 g = this->Gradient(p, v, level);
  const double norm = std::sqrt(glm::dot(g, g));
  glm::dvec3 colour = s.Ambient * base;
  if (norm > 0.0)
  {
    // two-sided: the normal facing the viewer
    const glm::dvec3 n = glm::dot(g, towardEye) < 0.0 ? -g / norm : g / norm;
    const double lambert = glm::dot(n, lightDir);
    if (lambert > 0.0)
    {
      const glm::dvec3 half = glm::normalize(lightDir + towardEye);
      const double highlight = std::pow(std::max(glm::dot(n, half), 0.0), s.SpecularPower);
      colour += shadow * s.Colour * (s.Diffuse * lambert * base + s.Specular * highlight);
    }
  }
  return Clamp01(colour);
}

std::vector<Crossing> FindCrossings(const Field& field, const std::vector<double>& isoValues,
  const glm::dvec3& pa, double va, const glm::dvec3& pb, double vb)
{
  std::vector<Crossing> crossings;
  for (double c : isoValues)
  {
    // crossed: the two samples lie on different sides of c (a value equal to c counts as above)
    const bool aBelow = va < c, bBelow = vb < c;
    if (aBelow == bBelow)
    {
      continue;
    }
    double t0 = 0.0, t1 = 1.0; // fractions of the way from pa to pb
    for (int k = 0; k < CrossingBisections; ++k)
    {
      const double tm = 0.5 * (t0 + t1);
      const double vm = field.At(pa + tm * (pb - pa));
      if (std::isnan(vm))
      {
        break; // no data to refine with: keep the interval found so far
      }
      if ((vm < c) == aBelow)
      {
        t0 = tm;
      }
      else
      {
        t1 = tm;
      }
    }
    const glm::dvec3 hit = pa + t1 * (pb - pa);
    crossings.push_back(Crossing{ glm::length(hit - pa), c, hit });
  }
  // in the order the ray meets them; crossings located at one point (a jump of nearest cells
  // between the samples) in the order the values pass from va to vb
  const bool rising = vb > va;
  std::sort(crossings.begin(), crossings.end(),
    [rising](const Crossing& x, const Crossing& y)
    {
      if (x.Distance != y.Distance)
      {
        return x.Distance < y.Distance;
      }
      return rising ? x.IsoValue < y.IsoValue : x.IsoValue > y.IsoValue;
    });
  return crossings;
}

} // namespace reference
} // namespace amrsp
