// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspLighting.h"

#include "AmrspCommands.h"

#include "vtkContourValues.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <sstream>

namespace amrsp
{
namespace tool
{

const std::vector<std::string> LightingOptions = { "shade", "iso", "shadows", "light" };

void ApplyLightingOptions(RenderSettings& s, const Arguments& a, double lo, double hi)
{
  const std::string shade = a.Get("shade", "off");
  if (shade != "on" && shade != "off")
  {
    throw UsageError{ "--shade must be on or off" };
  }
  s.Light.Shade = shade == "on";
  s.Light.ShadowStep = a.GetNumber("shadows", 0.0);
  if (s.Light.ShadowStep < 0.0)
  {
    throw UsageError{ "--shadows expects a positive step (0 = off)" };
  }
  s.Light.Shadows = s.Light.ShadowStep > 0.0;
  if (a.Has("light"))
  {
    const std::vector<double> p = a.GetNumbers("light", "");
    if (p.size() != 3)
    {
      throw UsageError{ "--light expects X,Y,Z" };
    }
    s.Light.Headlight = false;
    s.Light.Positional = true;
    s.Light.Position = glm::dvec3(p[0], p[1], p[2]);
    s.Light.FocalPoint = s.View.FocalPoint;
  }
  if (a.Has("iso") && s.Blend != BlendMode::IsoSurface)
  {
    throw UsageError{ "--iso needs --blend iso" };
  }
  if (s.Blend == BlendMode::IsoSurface)
  {
    const std::vector<double> f = a.GetNumbers("iso", "0.5");
    if (f.empty() || f.size() > static_cast<std::size_t>(MaxIsoValues))
    {
      throw UsageError{ "--iso takes 1 to 8 values" };
    }
    s.IsoValues.clear();
    for (double x : f)
    {
      s.IsoValues.push_back(lo + x * (hi - lo));
    }
  }
}

void ApplyLighting(const RenderSettings& s, vtkVolumeProperty* property, vtkVolumeMapper* mapper,
  vtkRenderer* renderer)
{
  property->SetShade(s.Light.Shade ? 1 : 0);
  property->SetAmbient(s.Light.Ambient);
  property->SetDiffuse(s.Light.Diffuse);
  property->SetSpecular(s.Light.Specular);
  property->SetSpecularPower(s.Light.SpecularPower);
  property->GetIsoSurfaceValues()->SetNumberOfContours(static_cast<int>(s.IsoValues.size()));
  for (std::size_t i = 0; i < s.IsoValues.size(); ++i)
  {
    property->GetIsoSurfaceValues()->SetValue(static_cast<int>(i), s.IsoValues[i]);
  }
  if (s.Blend == BlendMode::IsoSurface)
  {
    mapper->SetBlendModeToIsoSurface();
  }
  if (auto* single = vtkSinglePassAMRVolumeMapper::SafeDownCast(mapper))
  {
    single->SetShadows(s.Light.Shadows);
    single->SetShadowSampleDistance(s.Light.ShadowStep);
  }
  if (!s.Light.Headlight)
  {
    // a scene light replaces the renderer's automatic headlight
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPosition(s.Light.Position.x, s.Light.Position.y, s.Light.Position.z);
    light->SetFocalPoint(s.Light.FocalPoint.x, s.Light.FocalPoint.y, s.Light.FocalPoint.z);
    light->SetPositional(s.Light.Positional);
    light->SetConeAngle(180.0);
    light->SetColor(s.Light.Colour.r, s.Light.Colour.g, s.Light.Colour.b);
    light->SetIntensity(1.0);
    renderer->AddLight(light);
  }
}

} // namespace tool
} // namespace amrsp
