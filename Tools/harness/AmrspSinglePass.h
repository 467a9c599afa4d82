// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The single-pass methods of the amrsp tool (packing, bindless, linear, auto):
/// vtkSinglePassAMRVolumeMapper in an offscreen
/// vtkRenderWindow with the tool's camera, transfer-function and background conventions
/// (docs/design.md, "Rendering conventions"; the set-up is GpuRenderer's).

#include "AmrspGpuRenderer.h"

#include "amrsp/DataStorage.h"
#include "amrsp/RayCaster.h"
#include "amrsp/RayLoop.h"

#include <string>

class vtkSinglePassAMRVolumeMapper;

namespace amrsp
{
namespace harness
{

class SinglePassRenderer : public GpuRenderer
{
public:
  /// `h` holds the scalars as they are displayed (after --scale); `s` gives the image size, the
  /// transfer function, its unit distance, the sample factor and the LOD threshold. `storage` is
  /// the mapper's data storage (bindless falls back to the atlas where it cannot run), its name
  /// the renderer's; `access` the bindless access. Nothing is rendered yet.
  SinglePassRenderer(const Hierarchy& h, const RenderSettings& s, const ViewAngles& view,
    DataStorage storage = DataStorage::PackedAtlas, BindlessAccess access = BindlessAccess::Auto);

  vtkSinglePassAMRVolumeMapper* GetMapper() const;

  /// What rendered the last frame (None before the first successful one): the storage, its
  /// bindless access (None unless bindless), the ray loop and the caster.
  DataStorage StorageUsed() const;
  BindlessAccess AccessUsed() const;
  RayLoop LoopUsed() const;
  RayCaster CasterUsed() const;
  /// StorageUsed and AccessUsed in words ("bindless (direct)", amrsp::StorageInWords).
  std::string StorageUsedInWords() const;
  /// Bytes of the data textures each storage needs for the current data (tree included).
  /// Why bindless was asked for but the atlas rendered (empty when it did not fall back).
  std::string BindlessFallbackReason() const;
  long long PackedBytes() const;
  long long BindlessBytes() const;

  /// Renders the current camera's frame (RenderAsIs) with the mapper's LoopCountOutput set to
  /// `count` (vtkSinglePassAMRVolumeMapper::LoopCounts) and returns the sum of the counts over
  /// the image; the mapper draws colours again afterwards. Throws GpuError as RenderAsIs.
  long long RenderWorkCount(int count);

  /// Where the rays of one frame ran (vtkSinglePassAMRVolumeMapper::OccupancyProbe).
  struct Occupancy
  {
    bool Available = false;
    std::string Why;                        ///< why not (the mapper's error) when not Available
    RayCaster Caster = RayCaster::Fragment; ///< the caster that ran
    long long Rays = 0;                     ///< pixels whose ray met the volume
    int Multiprocessors = 0;                ///< distinct gl_SMIDNV among them
    int ChipMultiprocessors = 0;            ///< gl_SMCountNV
    int Warps = 0;                          ///< distinct (gl_SMIDNV, gl_WarpIDNV) pairs
    int MostWarpsOnOne = 0; ///< the most distinct warp slots one multiprocessor used
  };
  /// Renders the current camera's frame (RenderAsIs) with the occupancy probe and counts where
  /// its rays ran; the mapper draws colours again afterwards. Not Available (with the reason)
  /// where the context lacks GL_NV_shader_thread_group.
  Occupancy RenderOccupancy();

private:
  SinglePassRenderer(vtkSinglePassAMRVolumeMapper* mapper, const Hierarchy& h,
    const RenderSettings& s, const ViewAngles& view, DataStorage storage, BindlessAccess access);
  vtkSinglePassAMRVolumeMapper* Mapper; // held by the base (its volume's mapper)
};

} // namespace harness
} // namespace amrsp
