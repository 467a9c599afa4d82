// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperViewGeometry.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLCamera.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"

namespace vtkAMRMapperViewGeometry
{

//------------------------------------------------------------------------------
void ToColumnMajor(vtkMatrix4x4* m, float out[16])
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[c * 4 + r] = static_cast<float>(m->GetElement(r, c));
    }
  }
}

//------------------------------------------------------------------------------
bool ComputeViewGeometry(vtkRenderer* ren, vtkVolume* vol, ViewGeometry& view, std::string& error)
{
  ren->GetTiledSizeAndOrigin(&view.Width, &view.Height, &view.X0, &view.Y0);
  vtkOpenGLCamera* camera = vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera());
  if (!camera || view.Width < 1 || view.Height < 1)
  {
    error = "the renderer has no OpenGL camera or an empty viewport";
    return false;
  }
  vtkMatrix4x4* wcvc = nullptr;
  vtkMatrix3x3* normal = nullptr;
  vtkMatrix4x4* vcdc = nullptr;
  vtkMatrix4x4* wcdcGL = nullptr;
  camera->GetKeyMatrices(ren, wcvc, normal, vcdc, wcdcGL);
  vtkNew<vtkMatrix4x4> wcdc; // GetKeyMatrices returns OpenGL (transposed) order
  vtkMatrix4x4::Transpose(wcdcGL, wcdc);
  vtkNew<vtkMatrix4x4> mcdc;
  vtkMatrix4x4::Multiply4x4(wcdc, vol->GetMatrix(), mcdc);
  vtkNew<vtkMatrix4x4> dcmc;
  vtkMatrix4x4::Invert(mcdc, dcmc);
  ToColumnMajor(mcdc, view.MCDC);
  ToColumnMajor(dcmc, view.DCMC);

  view.Parallel = camera->GetParallelProjection() != 0;
  vtkNew<vtkMatrix4x4> wcmc;
  vtkMatrix4x4::Invert(vol->GetMatrix(), wcmc);
  double eyeWC[4] = { 0.0, 0.0, 0.0, 1.0 };
  camera->GetPosition(eyeWC);
  double eyeMC[4];
  wcmc->MultiplyPoint(eyeWC, eyeMC);
  double focalWC[4] = { 0.0, 0.0, 0.0, 1.0 };
  camera->GetFocalPoint(focalWC);
  double focalMC[4];
  wcmc->MultiplyPoint(focalWC, focalMC);
  for (int a = 0; a < 3; ++a)
  {
    view.Eye[a] = eyeMC[a] / eyeMC[3];
    view.Direction[a] = focalMC[a] / focalMC[3] - view.Eye[a];
    view.EyeMC[a] = static_cast<float>(view.Eye[a]);
  }
  view.EyeMC[3] = view.Parallel ? 0.0f : 1.0f;
  view.Mirrored = vol->GetMatrix()->Determinant() < 0.0;
  return true;
}

//------------------------------------------------------------------------------
ModelLight FirstLightInModel(vtkRenderer* ren, vtkVolume* vol)
{
  ModelLight light;
  vtkNew<vtkMatrix4x4> wcmc; // world -> model
  vtkMatrix4x4::Invert(vol->GetMatrix(), wcmc);
  vtkLightCollection* lights = ren->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* l = lights->GetNextLight(it))
  {
    if (!l->GetSwitch())
    {
      continue;
    }
    double position[4] = { 0.0, 0.0, 0.0, 1.0 }, focal[4] = { 0.0, 0.0, 0.0, 1.0 };
    l->GetTransformedPosition(position);
    l->GetTransformedFocalPoint(focal);
    double positionMC[4], focalMC[4];
    wcmc->MultiplyPoint(position, positionMC);
    wcmc->MultiplyPoint(focal, focalMC);
    double toLight[3];
    for (int a = 0; a < 3; ++a)
    {
      light.Position[a] = static_cast<float>(positionMC[a] / positionMC[3]);
      toLight[a] = positionMC[a] / positionMC[3] - focalMC[a] / focalMC[3];
    }
    if (vtkMath::Normalize(toLight) > 0.0)
    {
      for (int a = 0; a < 3; ++a)
      {
        light.Direction[a] = static_cast<float>(toLight[a]);
      }
    }
    const double* colour = l->GetDiffuseColor();
    for (int a = 0; a < 3; ++a)
    {
      light.Colour[a] = static_cast<float>(colour[a] * l->GetIntensity());
    }
    light.Positional = l->GetPositional() != 0;
    break;
  }
  return light;
}

} // namespace vtkAMRMapperViewGeometry
