// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspAmrResample.h"

#ifdef AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER
#include "vtkAMRVolumeMapper.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSmartVolumeMapper.h"
#include "vtkUniformGrid.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <fcntl.h>
#include <unistd.h>
#include <sstream>
#endif

namespace amrsp
{
namespace harness
{

#ifndef AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER

bool AmrResampleAvailable(std::string& why)
{
  why = "vtkAMRVolumeMapper is not in this VTK build (module VTK::RenderingVolumeAMR missing; "
        "Debian's plain VTK 9.1 does not build it, ParaView's VTK does)";
  return false;
}

#else

bool AmrResampleAvailable(std::string&)
{
  return true;
}

/// vtkAMRVolumeMapper with its resampling timed: the grid update the base class would do inside
/// Render() is done first, under a clock; the base then finds the grid up to date.
class vtkAmrspTimedAMRVolumeMapper : public vtkAMRVolumeMapper
{
public:
  static vtkAmrspTimedAMRVolumeMapper* New();
  vtkTypeMacro(vtkAmrspTimedAMRVolumeMapper, vtkAMRVolumeMapper);

  void Render(vtkRenderer* ren, vtkVolume* vol) override
  {
    if (!this->HasMetaData)
    {
      this->UpdateResampler(ren, nullptr);
    }
    if (this->GridNeedsToBeUpdated)
    {
      const auto t0 = std::chrono::steady_clock::now();
      // vtkAMRResampleFilter prints its statistics on the standard error: kept off the
      // terminal by pointing file descriptor 2 at /dev/null meanwhile (a failed resampling
      // shows as a missing grid, GetLastError)
      std::cerr.flush();
      std::fflush(stderr);
      const int saved = ::dup(2);
      const int null = ::open("/dev/null", O_WRONLY);
      if (saved >= 0 && null >= 0)
      {
        ::dup2(null, 2);
      }
      this->UpdateGrid();
      std::cerr.flush();
      std::fflush(stderr);
      if (saved >= 0 && null >= 0)
      {
        ::dup2(saved, 2);
      }
      if (saved >= 0)
      {
        ::close(saved);
      }
      if (null >= 0)
      {
        ::close(null);
      }
      this->ResampleSeconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      ++this->Resamplings;
    }
    this->Superclass::Render(ren, vol);
  }

  double ResampleSeconds = 0.0;
  int Resamplings = 0;
  /// The ray caster vtkSmartVolumeMapper chose for the last frame.
  std::string RenderMode()
  {
    switch (this->InternalMapper->GetLastUsedRenderMode())
    {
      case vtkSmartVolumeMapper::GPURenderMode:
        return "gpu (vtkGPUVolumeRayCastMapper)";
      case vtkSmartVolumeMapper::RayCastRenderMode:
        return "cpu (vtkFixedPointVolumeRayCastMapper)";
      default:
        return "other (" + std::to_string(this->InternalMapper->GetLastUsedRenderMode()) + ")";
    }
  }
  /// Points of the resampled grid (0 before the first frame).
  void GetGridDimensions(int dims[3]) const
  {
    dims[0] = dims[1] = dims[2] = 0;
    if (this->Grid)
    {
      this->Grid->GetDimensions(dims);
    }
  }
  long long GridBytes() const
  {
    if (!this->Grid)
    {
      return 0;
    }
    long long bytes = 0;
    vtkDataSetAttributes* pd = this->Grid->GetPointData();
    for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* a = pd->GetArray(i);
      const char* selected = const_cast<vtkAmrspTimedAMRVolumeMapper*>(this)->GetArrayName();
      if (a && a->GetName() && selected && std::string(a->GetName()) == selected)
      {
        bytes += static_cast<long long>(a->GetNumberOfValues()) * a->GetDataTypeSize();
      }
    }
    return bytes;
  }

protected:
  vtkAmrspTimedAMRVolumeMapper() = default;
  ~vtkAmrspTimedAMRVolumeMapper() override = default;

private:
  vtkAmrspTimedAMRVolumeMapper(const vtkAmrspTimedAMRVolumeMapper&) = delete;
  void operator=(const vtkAmrspTimedAMRVolumeMapper&) = delete;
};
vtkStandardNewMacro(vtkAmrspTimedAMRVolumeMapper);

namespace
{
/// vtkAMRResampleFilter copies every array of each block into its grid and asserts (aborting
/// the process) when two blocks hold different numbers of arrays; vtkAMRVolumeMapper blanks the
/// blocks that lack vtkGhostType itself, only some of them: every block gets it here first.
GpuScene ResampleScene()
{
  GpuScene scene;
  scene.Blanking = true;
  return scene;
}

/// Throws GpuError naming the first block whose number of cell or point arrays differs from the
/// first block's: vtkAMRResampleFilter would assert on it and abort the process.
void RequireSameArrays(vtkDataObject* input)
{
  vtkCompositeDataSet* amr = vtkCompositeDataSet::SafeDownCast(input);
  if (!amr)
  {
    return;
  }
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(amr->NewIterator());
  int cells = -1, points = -1, block = 0;
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem(), ++block)
  {
    vtkDataSet* ds = vtkDataSet::SafeDownCast(it->GetCurrentDataObject());
    if (!ds)
    {
      continue;
    }
    const int c = ds->GetCellData()->GetNumberOfArrays();
    const int p = ds->GetPointData()->GetNumberOfArrays();
    if (cells < 0)
    {
      cells = c;
      points = p;
    }
    else if (c != cells || p != points)
    {
      throw GpuError("vtkAMRResampleFilter needs the same arrays in every block: block " +
        std::to_string(block) + " has " + std::to_string(c) + " cell and " + std::to_string(p) +
        " point arrays, the first " + std::to_string(cells) + " and " + std::to_string(points));
    }
  }
}
} // namespace

AmrResampleRenderer::AmrResampleRenderer(
  const Hierarchy& h, const RenderSettings& s, const ViewAngles& view, const glm::ivec3& samples)
  : AmrResampleRenderer(vtkSmartPointer<vtkAmrspTimedAMRVolumeMapper>::New(), h, s, view, samples)
{
}

AmrResampleRenderer::AmrResampleRenderer(vtkAmrspTimedAMRVolumeMapper* mapper, const Hierarchy& h,
  const RenderSettings& s, const ViewAngles& view, const glm::ivec3& samples)
  : GpuRenderer(samples.x < 0 ? "vtk-amr-resample:finest" : "vtk-amr-resample", mapper, h, s, view,
      ResampleScene())
  , Mapper(mapper)
{
  // the resampler turns cell data into point data at its sample points: the mapper expects the
  // array as field data of either kind
  if (h.VertexCentred)
  {
    this->Mapper->SetScalarModeToUsePointFieldData();
  }
  else
  {
    this->Mapper->SetScalarModeToUseCellFieldData();
  }
  this->Mapper->SelectScalarArray(h.ArrayName.empty() ? "values" : h.ArrayName.c_str());
  // (the render mode stays the default: vtkAMRVolumeMapper's GPURenderMode constant is not
  // vtkSmartVolumeMapper's, whose default mode picks the GPU ray caster where it can)

  // The frustum box the mapper resamples on the first frame (its default frustum mode) and the
  // finest level's cell size give the sample count that resolves the finest level.
  vtkRenderer* ren = this->GetRenderer();
  const glm::dvec3 lo = h.WorldLo(h.RootCells(), 0), hi = h.WorldHi(h.RootCells(), 0);
  double bounds[6] = { lo.x, hi.x, lo.y, hi.y, lo.z, hi.z }, box[6];
  ren->ResetCameraClippingRange(bounds);
  glm::dvec3 extent = hi - lo;
  if (vtkAMRVolumeMapper::ComputeResamplerBoundsFrustumMethod(
        ren->GetActiveCamera(), ren, bounds, box))
  {
    extent = glm::dvec3(box[1] - box[0], box[3] - box[2], box[5] - box[4]);
  }
  const glm::dvec3 finest = h.CellSize(h.NumberOfLevels() - 1) * h.Spacing0;
  glm::ivec3 n = samples;
  if (samples.x < 0)
  {
    // two samples per finest cell edge: the resampled points do not line up with the cells, and
    // with one sample per cell nearest-point reconstruction shifts cell values by up to a cell
    // (measured on AMReX plt1_Y: RMSE 28.5 with one sample per cell, against 9.2 at the default)
    const glm::dvec3 need = glm::ceil(2.0 * extent / finest) + 1.0;
    const double points = need.x * need.y * need.z;
    if (need.x > 2048 || need.y > 2048 || need.z > 2048 || points > double(int64_t(1) << 29))
    {
      std::ostringstream why;
      why << "does not fit: resolving the finest level takes " << need.x << " x " << need.y << " x "
          << need.z << " samples (limits 2048 per axis, 2^29 in total)";
      throw GpuError(why.str());
    }
    n = glm::ivec3(need);
  }
  if (n.x > 0)
  {
    this->Mapper->SetNumberOfSamples(n.x, n.y, n.z);
  }
  int used[3];
  this->Mapper->GetNumberOfSamples(used);
  this->CellsPerSample = extent / (glm::dvec3(used[0], used[1], used[2]) - 1.0) / finest;
  RequireSameArrays(this->Mapper->GetInputDataObject(0, 0));
}

double AmrResampleRenderer::BuildSeconds() const
{
  return this->Mapper->ResampleSeconds;
}

double AmrResampleRenderer::UploadSeconds() const
{
  return -1.0; // not separable from the internal mapper's first frame
}

int AmrResampleRenderer::NumberOfBuilds() const
{
  return this->Mapper->Resamplings;
}

long long AmrResampleRenderer::TextureBytes() const
{
  return this->Mapper->GridBytes();
}

std::string AmrResampleRenderer::RenderMode() const
{
  return this->Mapper->RenderMode();
}

glm::ivec3 AmrResampleRenderer::Samples() const
{
  int n[3];
  this->Mapper->GetNumberOfSamples(n);
  return glm::ivec3(n[0], n[1], n[2]);
}

glm::dvec3 AmrResampleRenderer::FinestCellsPerSample() const
{
  return this->CellsPerSample;
}

std::string AmrResampleRenderer::LastError() const
{
  int dims[3];
  this->Mapper->GetGridDimensions(dims);
  if (dims[0] * dims[1] * dims[2] == 0)
  {
    return "vtkAMRResampleFilter produced no grid";
  }
  return std::string();
}

void AmrResampleRenderer::GetAtlasDimensions(int dims[3]) const
{
  this->Mapper->GetGridDimensions(dims);
}

#endif

} // namespace harness
} // namespace amrsp
