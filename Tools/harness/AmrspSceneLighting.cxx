// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspSceneLighting.h"

#include "vtkContourValues.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkVolumeProperty.h"

namespace amrsp
{
namespace harness
{

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

} // namespace harness
} // namespace amrsp
