// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRRegionSplit.h"

#include "vtkSinglePassAMRDataModel.h"

#include "vtkAMRBox.h"
#include "vtkAMRMapperConversion.h"
#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkUniformGrid.h"

#include "amrsp/RankPartition.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

namespace model = vtkSinglePassAMRDataModel;

namespace
{

/// FNV-1a over the metadata that must agree between ranks: levels, blocks per level, their boxes,
/// the origin and the spacings (bit patterns).
long long MetadataDigest(vtkOverlappingAMR* amr)
{
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t bytes)
  {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i)
    {
      h = (h ^ p[i]) * 1099511628211ull;
    }
  };
  const unsigned int levels = amr->GetNumberOfLevels();
  mix(&levels, sizeof(levels));
  mix(amr->GetOrigin(), 3 * sizeof(double));
  for (unsigned int l = 0; l < levels; ++l)
  {
    double spacing[3];
    amr->GetSpacing(l, spacing);
    mix(spacing, sizeof(spacing));
    const unsigned int blocks = model::NumberOfBlocks(amr, l);
    mix(&blocks, sizeof(blocks));
    for (unsigned int i = 0; i < blocks; ++i)
    {
      const vtkAMRBox& box = amr->GetAMRBox(l, i);
      mix(box.GetLoCorner(), 3 * sizeof(int));
      mix(box.GetHiCorner(), 3 * sizeof(int));
    }
  }
  return static_cast<long long>(h & 0x7fffffffffffffffull);
}

/// The cells of a block's box, half-open, in its level's index space.
amrsp::Box CellsOf(const vtkAMRBox& box)
{
  amrsp::Box cells;
  for (int a = 0; a < 3; ++a)
  {
    cells.Lo[a] = box.GetLoCorner()[a];
    cells.Hi[a] = static_cast<int64_t>(box.GetHiCorner()[a]) + 1;
  }
  return cells;
}

/// Copies the elements of `source` in index range [lo, hi) of a grid of `sourceDims` elements
/// starting at `sourceLo` (x fastest) into a new array of (hi - lo) elements.
vtkSmartPointer<vtkAbstractArray> CopyRange(vtkAbstractArray* source, const int64_t sourceDims[3],
  const int64_t sourceLo[3], const int64_t lo[3], const int64_t hi[3])
{
  vtkSmartPointer<vtkAbstractArray> out;
  out.TakeReference(source->NewInstance());
  out->SetName(source->GetName());
  out->SetNumberOfComponents(source->GetNumberOfComponents());
  const int64_t nx = hi[0] - lo[0], ny = hi[1] - lo[1], nz = hi[2] - lo[2];
  out->SetNumberOfTuples(static_cast<vtkIdType>(nx * ny * nz));
  vtkIdType dst = 0;
  for (int64_t z = lo[2]; z < hi[2]; ++z)
  {
    for (int64_t y = lo[1]; y < hi[1]; ++y, dst += nx)
    {
      const int64_t src = ((z - sourceLo[2]) * sourceDims[1] + (y - sourceLo[1])) * sourceDims[0] +
        (lo[0] - sourceLo[0]);
      out->InsertTuples(dst, static_cast<vtkIdType>(nx), static_cast<vtkIdType>(src), source);
    }
  }
  return out;
}

/// The part `piece` (cells of the block's level, inside `cells`) of `block`, whose box is
/// `cells`, as a vtkImageData with every cell and point array; the block may carry ghost layers
/// around its box (equal on both sides of an axis).
/// `block` itself as image data sharing its arrays when `piece` is all of its cells and it has
/// no ghost layers; nullptr otherwise (then ExtractPiece copies the piece).
vtkSmartPointer<vtkImageData> WholeBlock(
  vtkDataSet* block, const amrsp::Box& cells, const amrsp::Box& piece)
{
  int dims[3];
  if (!(piece.Lo == cells.Lo && piece.Hi == cells.Hi) || !model::BlockDimensions(block, dims))
  {
    return nullptr;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (std::max(1, dims[a] - 1) != cells.Extent()[a])
    {
      return nullptr; // ghost layers: the piece leaves them out
    }
  }
  return model::AsImageData(block);
}

vtkSmartPointer<vtkImageData> ExtractPiece(
  vtkDataSet* block, const amrsp::Box& cells, const amrsp::Box& piece)
{
  int dims[3];
  double origin[3], spacing[3];
  if (!model::BlockDimensions(block, dims) || !model::BlockOriginAndSpacing(block, origin, spacing))
  {
    return nullptr; // neither image data nor a rectilinear grid: nothing to send
  }
  int64_t cellDims[3], pointDims[3], cellLo[3], pointLo[3];
  int64_t pieceLo[3], pieceHi[3], piecePointHi[3];
  for (int a = 0; a < 3; ++a)
  {
    cellDims[a] = std::max(1, dims[a] - 1);
    pointDims[a] = dims[a];
    const int64_t ghost = (cellDims[a] - cells.Extent()[a]) / 2;
    cellLo[a] = cells.Lo[a] - ghost; // index of the block's first cell and point
    pointLo[a] = cellLo[a];
    pieceLo[a] = piece.Lo[a];
    pieceHi[a] = piece.Hi[a];
    piecePointHi[a] = piece.Hi[a] + 1;
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  for (int a = 0; a < 3; ++a)
  {
    origin[a] += static_cast<double>(piece.Lo[a] - cellLo[a]) * spacing[a];
  }
  image->SetOrigin(origin);
  image->SetSpacing(spacing);
  image->SetDimensions(static_cast<int>(piece.Extent().x + 1),
    static_cast<int>(piece.Extent().y + 1), static_cast<int>(piece.Extent().z + 1));
  vtkCellData* cd = block->GetCellData();
  for (int i = 0; i < cd->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = cd->GetAbstractArray(i);
    if (array && array->GetNumberOfTuples() == cellDims[0] * cellDims[1] * cellDims[2])
    {
      image->GetCellData()->AddArray(CopyRange(array, cellDims, cellLo, pieceLo, pieceHi));
    }
  }
  vtkPointData* pd = block->GetPointData();
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = pd->GetAbstractArray(i);
    if (array && array->GetNumberOfTuples() == pointDims[0] * pointDims[1] * pointDims[2])
    {
      image->GetPointData()->AddArray(CopyRange(array, pointDims, pointLo, pieceLo, piecePointHi));
    }
  }
  return image;
}

/// One piece in a rank's message: its level, block index, the piece's cells (half-open, level
/// index space) and the byte length of the marshalled vtkImageData that follows.
struct PieceHeader
{
  int32_t Level;
  int32_t Block;
  int64_t Lo[3];
  int64_t Hi[3];
  int64_t Bytes;
};

void Append(std::vector<char>& buffer, const void* data, std::size_t bytes)
{
  const char* p = static_cast<const char*>(data);
  buffer.insert(buffer.end(), p, p + bytes);
}

/// The flat index of each level's first block (levels + 1 entries, the last the block count).
std::vector<int> FirstBlockOfLevels(vtkOverlappingAMR* local)
{
  const unsigned int levels = local->GetNumberOfLevels();
  std::vector<int> firstBlock(levels + 1, 0);
  for (unsigned int l = 0; l < levels; ++l)
  {
    firstBlock[l + 1] = firstBlock[l] + static_cast<int>(model::NumberOfBlocks(local, l));
  }
  return firstBlock;
}

/// Which rank supplies each block (by flat index): the lowest rank that loaded it (collective).
std::vector<int> BlockSuppliers(vtkMultiProcessController* controller, vtkOverlappingAMR* local,
  const std::vector<int>& firstBlock)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const unsigned int levels = local->GetNumberOfLevels();
  const int total = firstBlock[levels];
  std::vector<int> loaded(static_cast<std::size_t>(total)),
    supplier(static_cast<std::size_t>(total));
  for (unsigned int l = 0; l < levels; ++l)
  {
    for (unsigned int i = 0; i < model::NumberOfBlocks(local, l); ++i)
    {
      loaded[static_cast<std::size_t>(firstBlock[l] + static_cast<int>(i))] =
        model::Block(local, l, i) ? rank : ranks;
    }
  }
  if (total > 0)
  {
    controller->AllReduce(loaded.data(), supplier.data(), total, vtkCommunicator::MIN_OP);
  }
  return supplier;
}

/// The pieces this rank supplies, one message per destination rank; each destination gathers its
/// messages from all ranks (GatherV, one destination after the other). Collective; what reached
/// this rank is appended to `received` and `receivedImages`.
void ExchangePieces(vtkMultiProcessController* controller, vtkOverlappingAMR* local,
  const amrsp::Hierarchy& boxes, const std::vector<amrsp::Box>& regions,
  const std::vector<int>& firstBlock, const std::vector<int>& supplier,
  std::vector<PieceHeader>& received, std::vector<vtkSmartPointer<vtkImageData>>& receivedImages)
{
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const unsigned int levels = local->GetNumberOfLevels();
  for (int destination = 0; destination < ranks; ++destination)
  {
    const amrsp::Box& region = regions[static_cast<std::size_t>(destination)];
    std::vector<char> message;
    for (unsigned int l = 0; l < levels && !region.Empty(); ++l)
    {
      for (unsigned int i = 0; i < model::NumberOfBlocks(local, l); ++i)
      {
        if (supplier[static_cast<std::size_t>(firstBlock[l] + static_cast<int>(i))] != rank)
        {
          continue;
        }
        const amrsp::Box cells = CellsOf(local->GetAMRBox(l, i));
        const amrsp::Box piece = amrsp::GhostedPiece(boxes, cells, static_cast<int>(l), region);
        if (piece.Empty())
        {
          continue;
        }
        vtkDataSet* block = model::Block(local, l, i);
        PieceHeader header{ static_cast<int32_t>(l), static_cast<int32_t>(i),
          { piece.Lo.x, piece.Lo.y, piece.Lo.z }, { piece.Hi.x, piece.Hi.y, piece.Hi.z }, 0 };
        if (destination == rank)
        {
          // this rank's own piece stays here; a whole block without ghost layers is not copied
          // (its image shares the block's arrays: in situ, the simulation's memory)
          vtkSmartPointer<vtkImageData> own = WholeBlock(block, cells, piece);
          if (!own)
          {
            own = ExtractPiece(block, cells, piece);
          }
          if (own)
          {
            received.push_back(header);
            receivedImages.push_back(own);
          }
          continue;
        }
        vtkSmartPointer<vtkImageData> extracted = ExtractPiece(block, cells, piece);
        if (!extracted)
        {
          continue;
        }
        vtkNew<vtkCharArray> bytes;
        vtkCommunicator::MarshalDataObject(extracted, bytes);
        header.Bytes = static_cast<int64_t>(bytes->GetNumberOfValues());
        Append(message, &header, sizeof(header));
        Append(message, bytes->GetPointer(0), static_cast<std::size_t>(header.Bytes));
      }
    }
    vtkNew<vtkCharArray> send;
    send->SetArray(message.data(), static_cast<vtkIdType>(message.size()), 1);
    vtkNew<vtkCharArray> all;
    controller->GatherV(send, all, destination);
    if (destination != rank)
    {
      continue;
    }
    const char* p = all->GetPointer(0);
    const char* end = p + all->GetNumberOfValues();
    while (p + sizeof(PieceHeader) <= end)
    {
      PieceHeader header;
      std::memcpy(&header, p, sizeof(header));
      p += sizeof(header);
      vtkNew<vtkCharArray> bytes;
      bytes->SetArray(const_cast<char*>(p), static_cast<vtkIdType>(header.Bytes), 1);
      p += header.Bytes;
      auto image = vtkSmartPointer<vtkImageData>::New();
      vtkCommunicator::UnMarshalDataObject(bytes, image);
      received.push_back(header);
      receivedImages.push_back(image);
    }
  }
}

/// This rank's hierarchy: the received pieces level by level, in (block, piece) order, with the
/// levels' origin, spacings and refinement ratios of `local`.
vtkSmartPointer<vtkOverlappingAMR> AssembleRegion(vtkOverlappingAMR* local,
  const std::vector<PieceHeader>& received,
  const std::vector<vtkSmartPointer<vtkImageData>>& receivedImages)
{
  const unsigned int levels = local->GetNumberOfLevels();
  std::vector<std::size_t> order(received.size());
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    order[k] = k;
  }
  std::sort(order.begin(), order.end(),
    [&received](std::size_t a, std::size_t b)
    {
      return std::tie(received[a].Level, received[a].Block) <
        std::tie(received[b].Level, received[b].Block);
    });
  std::vector<int> blocksPerLevel(levels, 0);
  for (const PieceHeader& header : received)
  {
    ++blocksPerLevel[static_cast<std::size_t>(header.Level)];
  }
  auto split = vtkSmartPointer<vtkOverlappingAMR>::New();
  model::Initialize(split, blocksPerLevel);
  split->SetOrigin(local->GetOrigin());
  split->SetGridDescription(local->GetGridDescription());
  for (unsigned int l = 0; l < levels; ++l)
  {
    double spacing[3];
    local->GetSpacing(l, spacing);
    split->SetSpacing(l, spacing);
  }
  if (model::HasRefinementRatio(local))
  {
    for (unsigned int l = 0; l < levels; ++l)
    {
      split->SetRefinementRatio(l, local->GetRefinementRatio(l));
    }
  }
  std::vector<unsigned int> next(levels, 0);
  for (std::size_t k : order)
  {
    const PieceHeader& header = received[k];
    const unsigned int level = static_cast<unsigned int>(header.Level);
    const unsigned int index = next[level]++;
    const int lo[3] = { static_cast<int>(header.Lo[0]), static_cast<int>(header.Lo[1]),
      static_cast<int>(header.Lo[2]) };
    const int hi[3] = { static_cast<int>(header.Hi[0]) - 1, static_cast<int>(header.Hi[1]) - 1,
      static_cast<int>(header.Hi[2]) - 1 };
    split->SetAMRBox(level, index, vtkAMRBox(lo, hi));
    vtkNew<vtkUniformGrid> grid;
    grid->ShallowCopy(receivedImages[k]);
    split->SetDataSet(level, index, grid);
  }
  return split;
}
} // namespace

vtkSmartPointer<vtkOverlappingAMR> vtkSinglePassAMRRegionSplit::SplitByRegion(
  vtkMultiProcessController* controller, vtkOverlappingAMR* local, double regionBounds[6],
  std::string* error)
{
  vtkMath::UninitializeBounds(regionBounds);
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();

  // 1. the metadata must be the same on every rank; then every rank computes the same regions
  amrsp::Hierarchy boxes;
  std::string conversionError;
  vtkAMRMapperConversion::ArraySelection structureOnly;
  structureOnly.CopyValues = false;
  const bool usable = local && local->GetNumberOfLevels() > 0 &&
    vtkAMRMapperConversion::FromOverlappingAMR(local, structureOnly, boxes, conversionError) &&
    !boxes.RootCells().Empty();
  const long long mine[2] = { usable ? 1 : 0, usable ? MetadataDigest(local) : 0 };
  long long lowest[2] = { 0, 0 };
  long long highest[2] = { 0, 0 };
  controller->AllReduce(mine, lowest, 2, vtkCommunicator::MIN_OP);
  controller->AllReduce(mine, highest, 2, vtkCommunicator::MAX_OP);
  if (lowest[0] != 1 || lowest[1] != highest[1])
  {
    if (error)
    {
      std::ostringstream message;
      if (lowest[0] != 1)
      {
        message << "a rank has no usable AMR metadata"
                << (conversionError.empty() ? std::string() : " (" + conversionError + ")");
      }
      else
      {
        message << "the ranks hold different AMR metadata (levels, boxes or spacings)";
      }
      *error = message.str();
    }
    return nullptr;
  }
  const std::vector<amrsp::Box> regions = amrsp::PartitionRootBox(boxes, ranks);
  if (std::any_of(regions.begin(), regions.end(), [](const amrsp::Box& b) { return b.Empty(); }))
  {
    if (error)
    {
      const glm::i64vec3 e = boxes.RootCells().Extent();
      std::ostringstream message;
      message << "more ranks (" << ranks << ") than the root box of " << e.x << " x " << e.y
              << " x " << e.z << " level-0 cells can be split into";
      *error = message.str();
    }
    return nullptr;
  }
  const amrsp::Box& own = regions[static_cast<std::size_t>(rank)];
  if (!own.Empty())
  {
    const glm::dvec3 lo = boxes.WorldLo(own, 0);
    const glm::dvec3 hi = boxes.WorldHi(own, 0);
    const double bounds[6] = { lo.x, hi.x, lo.y, hi.y, lo.z, hi.z };
    std::copy(bounds, bounds + 6, regionBounds);
  }

  // 2. which rank supplies each block; 3. the pieces of the blocks it supplies to every rank;
  // 4. this rank's hierarchy from the pieces it received
  const std::vector<int> firstBlock = FirstBlockOfLevels(local);
  const std::vector<int> supplier = BlockSuppliers(controller, local, firstBlock);
  std::vector<PieceHeader> received;
  std::vector<vtkSmartPointer<vtkImageData>> receivedImages;
  ExchangePieces(controller, local, boxes, regions, firstBlock, supplier, received, receivedImages);
  return AssembleRegion(local, received, receivedImages);
}
