// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkSinglePassAMRDataModel.h
 * @brief The one place where the project sees which AMR data model its VTK has.
 *
 * VTK 9.6 reworked vtkOverlappingAMR (Documentation/release/9.6: vtkAMRDataObject, a
 * vtkPartitionedDataSetCollection with one partitioned data set per level;
 * vtkOverlappingAMRMetaData instead of vtkAMRInformation; blocks that are vtkCartesianGrid, i.e.
 * image data or rectilinear grids) and deprecated the earlier calls, which VTK's main branch has
 * since removed. These functions call the current API where the VTK has it (`vtkAMRDataObject.h`
 * exists) and the earlier one on VTK 9.1-9.5, so that the rest of the project is written once and
 * builds on both without deprecated calls.
 */
#ifndef vtkSinglePassAMRDataModel_h
#define vtkSinglePassAMRDataModel_h

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkRectilinearGrid.h"
#include "vtkSmartPointer.h"
#include "vtkStructuredData.h"
#include "vtkUniformGrid.h"

#if defined(__has_include)
#if __has_include("vtkAMRDataObject.h")
#define AMRSP_VTK_AMR_DATA_OBJECT 1 // VTK 9.6's AMR data model
#include "vtkCartesianGrid.h"
#include "vtkOverlappingAMRMetaData.h"
#endif
#endif
#ifndef AMRSP_VTK_AMR_DATA_OBJECT
#include "vtkAMRInformation.h"
#endif

#include <vector>

namespace vtkSinglePassAMRDataModel
{

/// The blocks of every level.
inline unsigned int NumberOfBlocks(vtkOverlappingAMR* amr)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  return amr->GetNumberOfBlocks();
#else
  return amr->GetTotalNumberOfBlocks();
#endif
}

/// The blocks of `level`.
inline unsigned int NumberOfBlocks(vtkOverlappingAMR* amr, unsigned int level)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  return amr->GetNumberOfBlocks(level);
#else
  return amr->GetNumberOfDataSets(level);
#endif
}

/// Block `index` of `level` (nullptr where it is not loaded): image data (vtkUniformGrid), or on
/// VTK 9.6 possibly a vtkRectilinearGrid.
inline vtkDataSet* Block(vtkOverlappingAMR* amr, unsigned int level, unsigned int index)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  return amr->GetDataSetAsCartesianGrid(level, index);
#else
  return amr->GetDataSet(level, index);
#endif
}

/// Sets block `index` of `level`: before VTK 9.6 it must be a vtkUniformGrid (others are left
/// out), from 9.6 on image data or a rectilinear grid.
inline void SetBlock(
  vtkOverlappingAMR* amr, unsigned int level, unsigned int index, vtkDataSet* block)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  amr->SetDataSet(level, index, block);
#else
  amr->SetDataSet(level, index, vtkUniformGrid::SafeDownCast(block));
#endif
}

/// Block `index` of `level` when it is image data (nullptr otherwise).
inline vtkImageData* ImageBlock(vtkOverlappingAMR* amr, unsigned int level, unsigned int index)
{
  return vtkImageData::SafeDownCast(Block(amr, level, index));
}

/// A block's points per axis: image data and rectilinear grids; false for any other data set.
inline bool BlockDimensions(vtkDataSet* block, int dims[3])
{
  if (vtkImageData* image = vtkImageData::SafeDownCast(block))
  {
    image->GetDimensions(dims);
    return true;
  }
  if (vtkRectilinearGrid* grid = vtkRectilinearGrid::SafeDownCast(block))
  {
    grid->GetDimensions(dims);
    return true;
  }
  return false;
}

/// A block's first point and its spacing: image data's own, or a rectilinear grid's first
/// coordinates and first steps (callers check its spacing is uniform); false otherwise.
inline bool BlockOriginAndSpacing(vtkDataSet* block, double origin[3], double spacing[3])
{
  if (vtkImageData* image = vtkImageData::SafeDownCast(block))
  {
    image->GetOrigin(origin);
    image->GetSpacing(spacing);
    return true;
  }
  vtkRectilinearGrid* grid = vtkRectilinearGrid::SafeDownCast(block);
  if (!grid)
  {
    return false;
  }
  vtkDataArray* coordinates[3] = { grid->GetXCoordinates(), grid->GetYCoordinates(),
    grid->GetZCoordinates() };
  for (int a = 0; a < 3; ++a)
  {
    vtkDataArray* c = coordinates[a];
    if (!c || c->GetNumberOfTuples() < 1)
    {
      return false;
    }
    origin[a] = c->GetComponent(0, 0);
    spacing[a] = c->GetNumberOfTuples() > 1 ? c->GetComponent(1, 0) - origin[a] : 1.0;
  }
  return true;
}

/// `block` as image data sharing its arrays: image data itself, or an evenly spaced rectilinear
/// grid's first point, first steps and dimensions (nullptr for any other data set).
inline vtkSmartPointer<vtkImageData> AsImageData(vtkDataSet* block)
{
  int dims[3];
  double origin[3], spacing[3];
  if (!BlockDimensions(block, dims) || !BlockOriginAndSpacing(block, origin, spacing))
  {
    return nullptr;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  if (vtkImageData* given = vtkImageData::SafeDownCast(block))
  {
    image->ShallowCopy(given);
    return image;
  }
  image->SetDimensions(dims);
  image->SetOrigin(origin);
  image->SetSpacing(spacing);
  image->GetPointData()->ShallowCopy(block->GetPointData());
  image->GetCellData()->ShallowCopy(block->GetCellData());
  image->GetFieldData()->ShallowCopy(block->GetFieldData());
  return image;
}

/// Sets up `amr` for `blocksPerLevel[l]` blocks on each level l.
inline void Initialize(vtkOverlappingAMR* amr, const std::vector<int>& blocksPerLevel)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  amr->Initialize(std::vector<unsigned int>(blocksPerLevel.begin(), blocksPerLevel.end()));
#else
  amr->Initialize(static_cast<int>(blocksPerLevel.size()), blocksPerLevel.data());
#endif
}

/// The index of block `index` of `level` among all blocks, level by level.
inline int AbsoluteBlockIndex(vtkOverlappingAMR* amr, unsigned int level, unsigned int index)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  return amr->GetAbsoluteBlockIndex(level, index);
#else
  return amr->GetCompositeIndex(level, index);
#endif
}

/// Whether `amr` has its structure (levels, boxes, spacing) described: an AMR VTK initialised.
inline bool HasMetaData(vtkOverlappingAMR* amr)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  return amr->GetOverlappingAMRMetaData() != nullptr;
#else
  return amr->GetAMRInfo() != nullptr;
#endif
}

/// Whether `amr`'s refinement ratios are set (then GetRefinementRatio answers).
inline bool HasRefinementRatio(vtkOverlappingAMR* amr)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  vtkOverlappingAMRMetaData* meta = amr->GetOverlappingAMRMetaData();
#else
  vtkAMRInformation* meta = amr->GetAMRInfo();
#endif
  return meta && meta->HasRefinementRatio();
}

/// `to` gets a copy of `from`'s structure (levels, boxes, spacing, ratios), none of its blocks.
inline void CopyStructure(vtkOverlappingAMR* from, vtkOverlappingAMR* to)
{
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  vtkNew<vtkOverlappingAMRMetaData> meta;
  meta->DeepCopy(from->GetOverlappingAMRMetaData());
  to->Initialize(meta);
#else
  vtkNew<vtkAMRInformation> info;
  info->DeepCopy(from->GetAMRInfo());
  to->SetAMRInfo(info);
#endif
}

/// vtkOverlappingAMR's grid description of 3D blocks.
constexpr int XYZGrid =
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  vtkStructuredData::VTK_STRUCTURED_XYZ_GRID;
#else
  VTK_XYZ_GRID;
#endif

} // namespace vtkSinglePassAMRDataModel

#endif
