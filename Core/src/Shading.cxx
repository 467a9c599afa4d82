// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/Shading.h"

#include "amrsp/TransferFunction.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace amrsp
{

ShadingContext MakeShadingContext(const Lighting& light, const TransferFunction& tf,
  const glm::dvec3& origin, const glm::dvec3& spacing0, const glm::dvec3& rootLo,
  const glm::dvec3& rootHi, const glm::dvec3& cameraPosition, const glm::dvec3& cameraFocalPoint)
{
  ShadingContext c;
  c.Light = &light;
  c.Transfer = &tf;
  c.Origin = origin;
  c.Spacing0 = spacing0;
  c.RootLo = rootLo;
  c.RootHi = rootHi;
  const glm::dvec3 position = light.Headlight ? cameraPosition : light.Position;
  const glm::dvec3 focal = light.Headlight ? cameraFocalPoint : light.FocalPoint;
  c.Positional = !light.Headlight && light.Positional;
  c.LightPosition = position;
  const glm::dvec3 toLight = position - focal;
  c.LightDirection =
    glm::length(toLight) > 0.0 ? glm::normalize(toLight) : glm::dvec3(0.0, 0.0, 1.0);
  return c;
}

glm::dvec3 Gradient(const ShadingContext& c, const PointLookup& f, const glm::dvec3& p, double v,
  const glm::dvec3& cellSize)
{
  glm::dvec3 g(0.0);
  // nearest cells: the stencil of p's cell, from its centre (a sample on a face takes one cell's)
  const glm::dvec3 b = c.CellStencil ? (glm::floor(p / cellSize) + 0.5) * cellSize : p;
  for (int a = 0; a < 3; ++a)
  {
    glm::dvec3 e(0.0);
    e[a] = cellSize[a];
    glm::dvec3 ignored;
    double plus = f(b + e, ignored);
    double minus = f(b - e, ignored);
    int n = 2;
    if (std::isnan(plus))
    {
      plus = v;
      --n;
    }
    if (std::isnan(minus))
    {
      minus = v;
      --n;
    }
    g[a] = n > 0 ? (plus - minus) / (n * cellSize[a] * c.Spacing0[a]) : 0.0;
  }
  return g;
}

double ShadowTransmittance(const ShadingContext& c, const PointLookup& f, const glm::dvec3& p)
{
  const Lighting& light = *c.Light;
  const glm::dvec3 x = c.Origin + p * c.Spacing0;
  glm::dvec3 toLight = c.Positional ? c.LightPosition - x : c.LightDirection;
  double tLight = std::numeric_limits<double>::infinity();
  if (c.Positional)
  {
    tLight = glm::length(toLight);
    if (!(tLight > 0.0))
    {
      return 1.0;
    }
    toLight /= tLight;
  }
  const glm::dvec3 d = toLight / c.Spacing0; // t stays the world distance
  double tExit = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] != 0.0)
    {
      tExit = std::min(tExit, ((d[a] > 0.0 ? c.RootHi[a] : c.RootLo[a]) - p[a]) / d[a]);
    }
  }
  const double tEnd = std::min(tExit, tLight);
  const double exponent = light.ShadowStep / c.Transfer->UnitDistance;
  double transmittance = 1.0;
  for (int k = 0; k < ShadowMaxSteps; ++k)
  {
    const double t = (k + 0.5) * light.ShadowStep;
    if (t >= tEnd)
    {
      break;
    }
    glm::dvec3 ignored;
    const double v = f(p + t * d, ignored);
    if (std::isnan(v))
    {
      continue;
    }
    const double opacity = std::min(1.0, c.Transfer->EvaluateOpacity(v));
    transmittance *= std::pow(1.0 - opacity, exponent);
    if (transmittance < ShadowMinTransmittance)
    {
      break;
    }
  }
  return transmittance;
}

glm::dvec3 ShadeSample(const ShadingContext& c, const PointLookup& f, const glm::dvec3& rgb,
  const glm::dvec3& p, double v, const glm::dvec3& cellSize, const glm::dvec3& towardEye)
{
  const Lighting& light = *c.Light;
  const double transmittance = light.Shadows ? ShadowTransmittance(c, f, p) : 1.0;
  if (!light.Shade)
  {
    return glm::clamp(rgb * (light.Ambient + light.Diffuse * transmittance * light.Colour),
      glm::dvec3(0.0), glm::dvec3(1.0));
  }
  const glm::dvec3 x = c.Origin + p * c.Spacing0;
  const glm::dvec3 l = c.Positional ? glm::normalize(c.LightPosition - x) : c.LightDirection;
  const glm::dvec3 g = Gradient(c, c.Neighbours ? c.Neighbours : f, p, v, cellSize);
  const double length = glm::length(g);
  double diffuse = 0.0, specular = 0.0;
  if (length > 0.0)
  {
    glm::dvec3 n = g / length;
    if (glm::dot(n, towardEye) < 0.0)
    {
      n = -n;
    }
    diffuse = std::max(0.0, glm::dot(n, l));
    if (diffuse > 0.0)
    {
      const glm::dvec3 h = glm::normalize(l + towardEye);
      specular = std::pow(std::max(0.0, glm::dot(n, h)), light.SpecularPower);
    }
  }
  const glm::dvec3 lit = light.Ambient * rgb +
    transmittance * light.Colour * (light.Diffuse * diffuse * rgb + light.Specular * specular);
  return glm::clamp(lit, glm::dvec3(0.0), glm::dvec3(1.0));
}

void IsoSurfaceTracker::Sample(const glm::dvec3& p, double v, glm::dvec3& colour, double& alpha)
{
  if (HavePrevious)
  {
    const int count = static_cast<int>(Values.size());
    const bool rising = v > PreviousV;
    for (int i = 0; i < count; ++i)
    {
      const double iso = Values[rising ? i : count - 1 - i];
      const bool belowA = PreviousV < iso;
      if (belowA == (v < iso))
      {
        continue;
      }
      glm::dvec3 a = PreviousP, b = p;
      for (int k = 0; k < IsoRefineSteps; ++k)
      {
        const glm::dvec3 m = 0.5 * (a + b);
        glm::dvec3 ignored;
        const double vm = F(m, ignored);
        if (std::isnan(vm))
        {
          break;
        }
        if ((vm < iso) == belowA)
        {
          a = m;
        }
        else
        {
          b = m;
        }
      }
      glm::dvec3 cellSize;
      double vh = F(b, cellSize);
      if (std::isnan(vh))
      {
        vh = iso;
        cellSize = glm::dvec3(1.0);
      }
      glm::dvec3 rgb = C.Transfer->EvaluateColor(iso);
      if (C.Light->Shade || C.Light->Shadows)
      {
        rgb = ShadeSample(C, F, rgb, b, vh, cellSize, TowardEye);
      }
      const double opacity = std::min(1.0, std::max(0.0, C.Transfer->EvaluateOpacity(iso)));
      colour += (1.0 - alpha) * opacity * rgb;
      alpha += (1.0 - alpha) * opacity;
    }
  }
  HavePrevious = true;
  PreviousP = p;
  PreviousV = v;
}

} // namespace amrsp
