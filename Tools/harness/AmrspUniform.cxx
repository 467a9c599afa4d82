// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspUniform.h"

#include "amrsp/Resample.h"
#include "amrsp/SampleStep.h"

#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSmartPointer.h"

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>

namespace amrsp
{
namespace harness
{

namespace
{

GpuScene UniformScene()
{
  GpuScene scene;
  scene.AmrInput = false;
  scene.Modes = false;
  scene.Unavailable = "uniform-gpu cannot render here: ";
  return scene;
}
} // namespace

UniformGpuRenderer::UniformGpuRenderer(
  const Hierarchy& h, const RenderSettings& s, const ViewAngles& view, int level)
  : UniformGpuRenderer(vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New(), h, s, view, level)
{
}

UniformGpuRenderer::UniformGpuRenderer(vtkGPUVolumeRayCastMapper* mapper, const Hierarchy& h,
  const RenderSettings& s, const ViewAngles& view, int level)
  : GpuRenderer("uniform-gpu", mapper, h, s, view, UniformScene())
  , Mapper(mapper)
  , ResampledLevel(level)
{
  const auto t0 = std::chrono::steady_clock::now();
  // 2^29 float voxels are 2 GiB, as much as one 3D texture is sensibly given here
  const UniformGrid u = ResampleToLevel(h, level, int64_t(1) << 29, 2048);
  this->Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  this->Dims = u.Dims;

  // cell data (the mapper's cell-data path: the volume spans the cells' whole extent), nearest
  // interpolation: every sample shows the finest cell the resampling found there; outside every
  // grid, transparent
  const double below = s.Transfer.Opacity.empty() ? 0.0 : s.Transfer.Opacity.front().X - 1.0;
  vtkNew<vtkImageData> image;
  image->SetDimensions(u.Dims.x + 1, u.Dims.y + 1, u.Dims.z + 1);
  image->SetSpacing(u.Spacing.x, u.Spacing.y, u.Spacing.z);
  image->SetOrigin(u.Origin.x, u.Origin.y, u.Origin.z);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  values->SetNumberOfTuples(static_cast<vtkIdType>(u.Values.size()));
  for (std::size_t i = 0; i < u.Values.size(); ++i)
  {
    values->SetValue(
      static_cast<vtkIdType>(i), std::isnan(u.Values[i]) ? static_cast<float>(below) : u.Values[i]);
  }
  image->GetCellData()->SetScalars(values);
  this->Mapper->SetInputData(image);
  this->Mapper->AutoAdjustSampleDistancesOff();
  // the voxels are the level's cells: its sampling distance
  this->Mapper->SetSampleDistance(
    static_cast<float>(LevelSampleStep(h, level, s.SampleDistanceFactor)));
}

int UniformGpuRenderer::Level() const
{
  return this->ResampledLevel;
}

double UniformGpuRenderer::ResampleSeconds() const
{
  return this->Seconds;
}

std::string UniformGpuRenderer::Dimensions() const
{
  std::ostringstream s;
  s << this->Dims.x << "x" << this->Dims.y << "x" << this->Dims.z;
  return s.str();
}

double UniformGpuRenderer::BuildSeconds() const
{
  return this->Seconds;
}

double UniformGpuRenderer::UploadSeconds() const
{
  return -1.0; // not separable from the first frame
}

int UniformGpuRenderer::NumberOfBuilds() const
{
  return 1;
}

long long UniformGpuRenderer::TextureBytes() const
{
  return static_cast<long long>(this->Dims.x) * this->Dims.y * this->Dims.z * 4;
}

std::string UniformGpuRenderer::LastError() const
{
  return std::string();
}

void UniformGpuRenderer::GetAtlasDimensions(int dims[3]) const
{
  dims[0] = this->Dims.x;
  dims[1] = this->Dims.y;
  dims[2] = this->Dims.z;
}

} // namespace harness
} // namespace amrsp
