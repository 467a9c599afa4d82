// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRShaderVariant.h"

#include "vtkAMRMapperShaderComposer.h"

#include "amrsp/LinearBricks.h"

//------------------------------------------------------------------------------
std::string vtkSinglePassAMRShaderVariant::Defines() const
{
  std::string defines;
  const auto define = [&defines](bool on, const std::string& line)
  {
    if (on)
    {
      defines += "#define " + line + "\n";
    }
  };
  define(true, "AMRSP_LEVEL_COUNT " + std::to_string(this->LevelCount));
  switch (this->Storage)
  {
    case amrsp::DataStorage::BindlessTextures:
      define(true, "AMRSP_BINDLESS 1");
      define(this->Waterfall, "AMRSP_WATERFALL 1");
      break;
    case amrsp::DataStorage::LinearBricks:
      // the table's layout comes from the core, which writes it (amrsp::LinearBrickTable)
      define(true, "AMRSP_LINEAR 1");
      define(true, "AMRSP_LINEAR_WIDTH_LOG2 " + std::to_string(this->LinearWidthLog2));
      define(true, "AMRSP_LINEAR_BASE_BITS " + std::to_string(amrsp::LinearBaseBits));
      define(this->LinearPages > 1, "AMRSP_LINEAR_PAGES " + std::to_string(this->LinearPages));
      break;
    default: // PackedAtlas
      define(true, "AMRSP_PACKING 1");
      define(this->AtlasPages > 1, "AMRSP_ATLAS_PAGES " + std::to_string(this->AtlasPages));
      break;
  }
  define(true, this->VertexCentred ? "AMRSP_VERTEX_CENTRED 1" : "AMRSP_CELL_CENTRED 1");
  define(this->LogTransfer, "AMRSP_LOG_TRANSFER 1");
  define(this->UseDepth, "AMRSP_USE_DEPTH 1");
  define(this->UseDepth && this->ReducedImage, "AMRSP_REDUCED_IMAGE 1");
  define(this->PowerOfTwoRefinement, "AMRSP_POWER_OF_TWO_REFINEMENT 1");
  define(this->UniformRefinementLog2 > 0,
    "AMRSP_UNIFORM_REFINEMENT_LOG2 " + std::to_string(this->UniformRefinementLog2));
  define(true, "AMRSP_BLEND_MODE " + std::to_string(static_cast<int>(this->Blend)));
  define(this->SkipEmpty, "AMRSP_SKIP_EMPTY 1");
  define(this->SmoothCells, "AMRSP_SMOOTH_CELLS 1");
  define(this->Ropes, "AMRSP_ROPES 1");
  define(this->FlatLoop, "AMRSP_FLAT_LOOP 1");
  define(this->Ablation != 0, "AMRSP_ABLATION " + std::to_string(this->Ablation));
  define(this->Shade, "AMRSP_SHADE 1");
  define(this->Shadows, "AMRSP_SHADOWS 1");
  const bool probe = this->OccupancyProbe;
  define(!probe && this->AccelerationCounts && this->LoopCount == 0, "AMRSP_ACCELERATION_COUNTS 1");
  define(!probe && this->LoopCount != 0, "AMRSP_LOOP_COUNT " + std::to_string(this->LoopCount));
  define(probe, "AMRSP_OCCUPANCY_PROBE 1");
  const bool compute = this->Caster == amrsp::RayCaster::Compute;
  define(compute, "AMRSP_GROUP_WIDTH " + std::to_string(this->GroupWidth));
  define(compute, "AMRSP_GROUP_HEIGHT " + std::to_string(this->GroupHeight));
  return defines;
}

//------------------------------------------------------------------------------
std::string vtkSinglePassAMRComposeShader(const vtkSinglePassAMRShaderVariant& variant,
  const vtkSinglePassAMRShaderSources& sources, const std::string& computeVersion, vtkVolume* vol)
{
  const bool compute = variant.Caster == amrsp::RayCaster::Compute;
  const char* storage = variant.Storage == amrsp::DataStorage::BindlessTextures
    ? sources.BindlessStorage
    : variant.Storage == amrsp::DataStorage::LinearBricks ? sources.LinearBricksStorage
                                                          : sources.PackedAtlasStorage;
  // CastRay first: the ray's source holds the other pieces' markers
  return vtkAMRMapperShaderComposer::ComposeFragmentShader(
    compute ? sources.Compute : sources.Fragment, variant.Defines(),
    { { "CastRay", sources.Ray }, { "KdTreeLayout", sources.KdTreeLayout },
      { "RayCommon", sources.RayCommon }, { "GridStorage", storage },
      { "BrickSample", sources.BrickSample }, { "SmoothCells", sources.SmoothCells },
      { "Shading", sources.Shading }, { "RaySteps", sources.RaySteps },
      { "Version", compute ? computeVersion.c_str() : "" } },
    vol);
}
