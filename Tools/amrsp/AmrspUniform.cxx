// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspUniform.h"

#include "amrsp/Resample.h"
#include "amrsp/SampleStep.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkCellData.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <chrono>
#include <cmath>
#include <sstream>

namespace amrsp
{
namespace tool
{

struct UniformGpuRenderer::Internals
{
  vtkNew<vtkImageData> Image;
  vtkNew<vtkGPUVolumeRayCastMapper> Mapper;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkColorTransferFunction> Colour;
  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCamera> Start;
  int Width = 0;
  int Height = 0;
  double ResampleSeconds = 0.0;
  glm::ivec3 Dims{ 0 };
};

UniformGpuRenderer::UniformGpuRenderer(
  const Hierarchy& h, const RenderSettings& s, const ViewAngles& view, int level)
  : I(new Internals)
{
  std::string why;
  if (!PackingRenderer::Available(why))
  {
    throw GpuError("uniform-gpu cannot render here: " + why);
  }
  I->Width = s.Width;
  I->Height = s.Height;
  const auto t0 = std::chrono::steady_clock::now();
  // 2^29 float voxels are 2 GiB, as much as one 3D texture is sensibly given here
  const UniformGrid u = ResampleToLevel(h, level, int64_t(1) << 29, 2048);
  I->ResampleSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  I->Dims = u.Dims;

  // cell data (the mapper's cell-data path: the volume spans the cells' whole extent), nearest
  // interpolation: every sample shows the finest cell the resampling found there; outside every
  // grid, transparent
  const double below = s.Transfer.Opacity.empty() ? 0.0 : s.Transfer.Opacity.front().X - 1.0;
  I->Image->SetDimensions(u.Dims.x + 1, u.Dims.y + 1, u.Dims.z + 1);
  I->Image->SetSpacing(u.Spacing.x, u.Spacing.y, u.Spacing.z);
  I->Image->SetOrigin(u.Origin.x, u.Origin.y, u.Origin.z);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(static_cast<vtkIdType>(u.Values.size()));
  for (std::size_t i = 0; i < u.Values.size(); ++i)
  {
    values->SetValue(static_cast<vtkIdType>(i),
      std::isnan(u.Values[i]) ? static_cast<float>(below) : u.Values[i]);
  }
  I->Image->GetCellData()->SetScalars(values);

  for (const TransferFunction::ColorPoint& p : s.Transfer.Color)
  {
    I->Colour->AddRGBPoint(p.X, p.Rgb.r, p.Rgb.g, p.Rgb.b);
  }
  for (const TransferFunction::OpacityPoint& p : s.Transfer.Opacity)
  {
    I->Opacity->AddPoint(p.X, p.Opacity);
  }
  I->Colour->SetColorSpaceToRGB();
  I->Property->SetColor(I->Colour);
  I->Property->SetScalarOpacity(I->Opacity);
  I->Property->SetScalarOpacityUnitDistance(s.Transfer.UnitDistance);
  I->Property->ShadeOff();
  I->Property->SetInterpolationTypeToNearest();
  I->Mapper->SetInputData(I->Image);
  I->Mapper->AutoAdjustSampleDistancesOff();
  // the voxels are the level's cells: its sampling distance
  I->Mapper->SetSampleDistance(
    static_cast<float>(LevelSampleStep(h, level, s.SampleDistanceFactor)));
  I->Volume->SetMapper(I->Mapper);
  I->Volume->SetProperty(I->Property);
  I->Renderer->SetBackground(s.Background.r, s.Background.g, s.Background.b);
  I->Renderer->AddVolume(I->Volume);
  I->Window->SetOffScreenRendering(1);
  I->Window->SetMultiSamples(0);
  I->Window->SetSize(s.Width, s.Height);
  I->Window->AddRenderer(I->Renderer);

  // the README camera on the level-0 bounds, as the other methods
  const glm::dvec3 lo = h.WorldLo(h.RootCells(), 0), hi = h.WorldHi(h.RootCells(), 0);
  double bounds[6] = { lo.x, hi.x, lo.y, hi.y, lo.z, hi.z };
  I->Renderer->ResetCamera(bounds);
  vtkCamera* camera = I->Renderer->GetActiveCamera();
  camera->Azimuth(view.Azimuth);
  camera->Elevation(view.Elevation);
  camera->OrthogonalizeViewUp();
  camera->Zoom(view.Zoom);
  I->Start->DeepCopy(camera);
}

UniformGpuRenderer::~UniformGpuRenderer()
{
  if (I)
  {
    I->Window->Finalize();
  }
}

Image UniformGpuRenderer::Render(double orbitDegrees, double& milliseconds)
{
  vtkCamera* camera = I->Renderer->GetActiveCamera();
  camera->DeepCopy(I->Start);
  camera->Azimuth(orbitDegrees);
  I->Renderer->ResetCameraClippingRange();
  const auto t0 = std::chrono::steady_clock::now();
  I->Window->Render();
  I->Window->WaitForCompletion();
  milliseconds =
    1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(I->Window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkUnsignedCharArray* rgb =
    vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  if (!rgb)
  {
    throw GpuError("reading the uniform-gpu image back failed");
  }
  Image img;
  img.Width = I->Width;
  img.Height = I->Height;
  img.Pixels.resize(static_cast<std::size_t>(img.Width) * img.Height);
  const unsigned char* p = rgb->GetPointer(0);
  for (std::size_t i = 0; i < img.Pixels.size(); ++i)
  {
    img.Pixels[i] = glm::vec4(p[3 * i] / 255.0f, p[3 * i + 1] / 255.0f, p[3 * i + 2] / 255.0f, 1.0f);
  }
  return img;
}

double UniformGpuRenderer::ResampleSeconds() const
{
  return I->ResampleSeconds;
}

long long UniformGpuRenderer::TextureBytes() const
{
  return static_cast<long long>(I->Dims.x) * I->Dims.y * I->Dims.z * 4;
}

std::string UniformGpuRenderer::Dimensions() const
{
  std::ostringstream s;
  s << I->Dims.x << "x" << I->Dims.y << "x" << I->Dims.z;
  return s.str();
}

} // namespace tool
} // namespace amrsp
