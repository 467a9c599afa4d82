// SPDX-License-Identifier: BSD-3-Clause
/**
 * Gathering the blocks of a distributed vtkOverlappingAMR on one rank (private to the
 * representation module).
 *
 * ParaView's parallel AMR readers give every rank the whole hierarchy's metadata
 * (vtkAMRInformation: every block's level, box and spacing) but the cell data of only some
 * blocks; the other blocks are null on that rank. vtkSinglePassAMRVolumeMapper needs the data of
 * every block it decodes, so the representation gathers all blocks on one rank, which renders
 * the whole volume, while the other ranks render nothing.
 */
#ifndef vtkSinglePassAMRGather_h
#define vtkSinglePassAMRGather_h

#include "vtkSmartPointer.h" // for the return value

#include <string> // for the error message

class vtkMultiProcessController;
class vtkOverlappingAMR;

namespace vtkSinglePassAMRGather
{
/**
 * Collective over all ranks of `controller` (every rank must call it, in the same order with
 * respect to other collective calls). Returns, on rank `root`, a new hierarchy with `local`'s
 * metadata and blocks (shared, not copied) in which every block that is null on `root` but loaded
 * on another rank is filled in with that rank's block (the lowest such rank wins); on the other
 * ranks it returns `local` unchanged. Blocks loaded nowhere stay null. Only blocks `root` lacks
 * travel: rank `root` first broadcasts which blocks it has, then every other rank sends just the
 * blocks that are missing there (its hierarchy must have the root's level and block counts, else
 * its blocks are left out).
 *
 * `local` may be null on ranks without data (they send no block). On a mismatch between
 * the hierarchies (different level or block counts) `error` is set to one line naming it and the
 * mismatching rank's blocks are left out. Memory: rank `root` ends up holding the whole
 * hierarchy's cell data (all arrays the reader loaded).
 */
vtkSmartPointer<vtkOverlappingAMR> GatherBlocks(
  vtkMultiProcessController* controller, vtkOverlappingAMR* local, int root, std::string* error);
}

#endif
