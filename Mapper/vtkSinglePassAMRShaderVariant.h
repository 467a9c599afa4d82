// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRShaderVariant.h
 * @brief   the single-pass shader variant of a frame, and its source (private)
 *
 * Everything that selects a variant of Shaders/SinglePassAMRRay.glsl, as plain values: the mapper
 * fills one per frame (vtkSinglePassAMRVolumeMapperFrame.cxx) and composes the source from it;
 * Mapper.ShaderVariants composes every variant the same way without an OpenGL context and has
 * glslangValidator check each. The #defines are listed at the top of SinglePassAMRRay.glsl.
 */
#ifndef vtkSinglePassAMRShaderVariant_h
#define vtkSinglePassAMRShaderVariant_h

#include "amrsp/BlendMode.h"
#include "amrsp/DataStorage.h"
#include "amrsp/RayCaster.h"

#include <string>

class vtkVolume;

struct vtkSinglePassAMRShaderVariant
{
  amrsp::RayCaster Caster = amrsp::RayCaster::Fragment; ///< Fragment or Compute
  /// PackedAtlas, BindlessTextures or LinearBricks (as uploaded)
  amrsp::DataStorage Storage = amrsp::DataStorage::PackedAtlas;
  int AtlasPages = 1;       ///< packing: 1 to 4
  int LinearPages = 1;      ///< linear: 1 to 4
  int LinearWidthLog2 = 12; ///< linear: 2^this texels per row
  bool Waterfall = false;   ///< bindless: one distinct handle at a time (GL_ARB_shader_ballot)
  int LevelCount = 1;
  bool VertexCentred = false;
  bool LogTransfer = false;
  bool UseDepth = false;
  bool ReducedImage = false; ///< with UseDepth: the rays' image is smaller than the viewport
  bool PowerOfTwoRefinement = false;
  int UniformRefinementLog2 = 0; ///< > 0: every level refines the one above by 2^this
  amrsp::BlendMode Blend = amrsp::BlendMode::Composite; ///< AMRSP_BLEND_MODE is its value
  bool SkipEmpty = false;
  bool SmoothCells = false;
  bool Ropes = false;
  bool FlatLoop = false;
  int Ablation = 0; ///< 0 none, 1 traversal only, 2 sampling only
  bool Shade = false;
  bool Shadows = false;
  bool AccelerationCounts =
    false;                     ///< AMRSP_ACCELERATION_COUNTS (ignored with LoopCount or the probe)
  int LoopCount = 0;           ///< AMRSP_LOOP_COUNT 1..3 (ignored with the probe)
  bool OccupancyProbe = false; ///< GL_NV_shader_thread_group
  int GroupWidth = 8;          ///< compute: work group size
  int GroupHeight = 4;

  /// The #define lines of this variant.
  std::string Defines() const;
};

/// The shader sources a variant is composed from (the files of Shaders/).
struct vtkSinglePassAMRShaderSources
{
  const char* Fragment;     ///< SinglePassAMR.frag.glsl
  const char* Compute;      ///< SinglePassAMR.comp.glsl
  const char* Ray;          ///< SinglePassAMRRay.glsl
  const char* KdTreeLayout; ///< KdTreeLayout.glsl
  const char* RayCommon;    ///< RayCommon.glsl
  const char* BrickSample;  ///< BrickSample.glsl
  /// The storages' pieces (amrspBrickRef, amrspReadStorage), one spliced per variant.
  const char* PackedAtlasStorage;  ///< StoragePackedAtlas.glsl
  const char* BindlessStorage;     ///< StorageBindless.glsl
  const char* LinearBricksStorage; ///< StorageLinearBricks.glsl
  const char* SmoothCells;         ///< SmoothCells.glsl
  const char* Shading;             ///< Shading.glsl
  const char* RaySteps;            ///< RaySteps.glsl
};

/**
 * The source of `variant`'s fragment shader (VTK's shader cache then replaces its //VTK::
 * markers) or compute shader (`computeVersion` as its first lines: #version, and the extension
 * on OpenGL 4.2), with the volume's vtkShaderProperty fragment replacements (`vol` may be null).
 */
std::string vtkSinglePassAMRComposeShader(const vtkSinglePassAMRShaderVariant& variant,
  const vtkSinglePassAMRShaderSources& sources, const std::string& computeVersion, vtkVolume* vol);

#endif
