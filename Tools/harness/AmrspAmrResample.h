// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The `vtk-amr-resample` method of the amrsp tool: VTK's vtkAMRVolumeMapper (module
/// VTK::RenderingVolumeAMR, shipped with ParaView's VTK) in the tool's offscreen window with the
/// tool's conventions. It resamples the visible part of the hierarchy (the view frustum's
/// bounding box, computed on the first frame) onto one uniform grid of NumberOfSamples points
/// (default 128 x 128 x 128) and renders it with vtkSmartVolumeMapper. The class exists only where
/// the module does (AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER); AmrResampleAvailable() says why not.

#include "AmrspGpuRenderer.h"

#include <glm/glm.hpp>

#include <string>

namespace amrsp
{
namespace harness
{

/// Whether this build has vtkAMRVolumeMapper; `why` names what is missing when not.
bool AmrResampleAvailable(std::string& why);

#ifdef AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER
class vtkAmrspTimedAMRVolumeMapper;

class AmrResampleRenderer : public GpuRenderer
{
public:
  /// `samples` becomes NumberOfSamples: 0 keeps the mapper's default (128 per axis), -1 asks for
  /// the count that resolves the finest level: two samples per finest cell edge over the frustum
  /// box the mapper resamples (computed here as the mapper does on its first frame). Throws
  /// GpuError when that grid would exceed 2048 points per axis or 2^29 points (as uniform-gpu). The
  /// volume property's interpolation is nearest, as for the other methods.
  AmrResampleRenderer(
    const Hierarchy& h, const RenderSettings& s, const ViewAngles& view, const glm::ivec3& samples);

  /// Seconds vtkAMRResampleFilter took (all resamplings so far) and how often it ran.
  double BuildSeconds() const override;
  double UploadSeconds() const override;
  int NumberOfBuilds() const override;
  /// The ray caster vtkSmartVolumeMapper used for the last frame.
  std::string RenderMode() const;
  /// NumberOfSamples as set.
  glm::ivec3 Samples() const;
  /// The finest level's cell edges that fit into one sample spacing, largest over the axes
  /// (0.5 or less: two samples per finest cell).
  glm::dvec3 FinestCellsPerSample() const;
  /// Bytes of the resampled grid's scalars (what the internal GPU mapper uploads).
  long long TextureBytes() const override;

protected:
  std::string LastError() const override;
  void GetAtlasDimensions(int dims[3]) const override;

private:
  AmrResampleRenderer(vtkAmrspTimedAMRVolumeMapper* mapper, const Hierarchy& h,
    const RenderSettings& s, const ViewAngles& view, const glm::ivec3& samples);
  vtkAmrspTimedAMRVolumeMapper* Mapper; // held by the base (its volume's mapper)
  glm::dvec3 CellsPerSample{ 0.0 };
};
#endif

} // namespace harness
} // namespace amrsp
