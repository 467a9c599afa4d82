// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRGather.h"

#include "vtkSinglePassAMRDataModel.h"

#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkUniformGrid.h"

#include <map>
#include <sstream>
#include <utility>
#include <vector>

namespace
{
/// Message tag of the gathered hierarchies (any value unused by ParaView's own messages).
constexpr int GatherTag = 472931;

/// Blocks per level; empty for a null hierarchy.
std::vector<int> BlockCounts(vtkOverlappingAMR* amr)
{
  std::vector<int> counts;
  if (amr)
  {
    for (unsigned int level = 0; level < amr->GetNumberOfLevels(); ++level)
    {
      counts.push_back(static_cast<int>(vtkSinglePassAMRDataModel::NumberOfBlocks(amr, level)));
    }
  }
  return counts;
}
} // namespace

vtkSmartPointer<vtkOverlappingAMR> vtkSinglePassAMRGather::GatherBlocks(
  vtkMultiProcessController* controller, vtkOverlappingAMR* local, int root, std::string* error)
{
  if (!controller || controller->GetNumberOfProcesses() < 2)
  {
    return local;
  }
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();

  // 1. the root's block counts and which blocks it holds (1) or lacks (0), level by level
  std::vector<int> counts = BlockCounts(rank == root ? local : nullptr);
  int levels = static_cast<int>(counts.size());
  controller->Broadcast(&levels, 1, root);
  counts.resize(levels);
  if (levels > 0)
  {
    controller->Broadcast(counts.data(), levels, root);
  }
  int total = 0;
  for (int count : counts)
  {
    total += count;
  }
  std::vector<int> held(total, 0);
  if (rank == root && local)
  {
    int flat = 0;
    for (int level = 0; level < levels; ++level)
    {
      for (int index = 0; index < counts[level]; ++index, ++flat)
      {
        held[flat] = vtkSinglePassAMRDataModel::Block(local, level, index) != nullptr ? 1 : 0;
      }
    }
  }
  if (total > 0)
  {
    controller->Broadcast(held.data(), total, root);
  }

  if (rank != root)
  {
    // 2. every other rank sends the blocks the root lacks: a count, then per block its
    // (level, index) and its grid as vtkImageData (vtkCommunicator cannot marshal a
    // vtkUniformGrid, and marshalling a whole vtkOverlappingAMR fails for ranks without blocks)
    std::vector<int> outgoing; // level, index pairs
    if (local && BlockCounts(local) == counts)
    {
      int flat = 0;
      for (int level = 0; level < levels; ++level)
      {
        for (int index = 0; index < counts[level]; ++index, ++flat)
        {
          // blocks travel as vtkImageData: a rectilinear block (VTK 9.6) as its image-data twin
          if (!held[flat] && vtkSinglePassAMRDataModel::Block(local, level, index))
          {
            outgoing.push_back(level);
            outgoing.push_back(index);
          }
        }
      }
    }
    else if (local && vtkSinglePassAMRDataModel::NumberOfBlocks(local) > 0 && error)
    {
      std::ostringstream message;
      message << "rank " << rank << " holds a different AMR hierarchy ("
              << local->GetNumberOfLevels() << " levels) than rank " << root << " (" << levels
              << " levels): its blocks are left out";
      *error = message.str();
    }
    int count = static_cast<int>(outgoing.size() / 2);
    controller->Send(&count, 1, root, GatherTag);
    for (int k = 0; k < count; ++k)
    {
      controller->Send(&outgoing[2 * k], 2, root, GatherTag);
      vtkSmartPointer<vtkImageData> grid = vtkSinglePassAMRDataModel::AsImageData(
        vtkSinglePassAMRDataModel::Block(local, outgoing[2 * k], outgoing[2 * k + 1]));
      if (!grid)
      {
        grid = vtkSmartPointer<vtkImageData>::New(); // neither image nor rectilinear: empty
      }
      controller->Send(grid, root, GatherTag);
    }
    return local;
  }

  // 3. the root receives every other rank's blocks, then builds a new hierarchy with its own
  // metadata and inserts each block in increasing (level, index) order: its own block where it
  // has one, else the first one received. (Inserting into a shallow copy of a hierarchy after it
  // has been read leaves vtkUniformGridAMR's block index stale.)
  std::map<std::pair<int, int>, vtkSmartPointer<vtkUniformGrid>> received;
  for (int source = 0; source < ranks; ++source)
  {
    if (source == root)
    {
      continue;
    }
    int count = 0;
    controller->Receive(&count, 1, source, GatherTag);
    for (int k = 0; k < count; ++k)
    {
      int block[2] = { 0, 0 };
      controller->Receive(block, 2, source, GatherTag);
      vtkNew<vtkImageData> image;
      controller->Receive(image, source, GatherTag);
      auto grid = vtkSmartPointer<vtkUniformGrid>::New();
      grid->ShallowCopy(image);
      received.emplace(std::make_pair(block[0], block[1]), grid);
    }
  }
  if (!local)
  {
    return nullptr;
  }
  auto gathered = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkSinglePassAMRDataModel::CopyStructure(local, gathered);
  for (int level = 0; level < levels; ++level)
  {
    for (int index = 0; index < counts[level]; ++index)
    {
      vtkDataSet* grid = vtkSinglePassAMRDataModel::Block(local, level, index);
      if (!grid)
      {
        auto found = received.find(std::make_pair(level, index));
        grid = found != received.end() ? found->second.Get() : nullptr;
      }
      if (grid)
      {
        vtkSinglePassAMRDataModel::SetBlock(gathered, level, index, grid);
      }
    }
  }
  return gathered;
}
