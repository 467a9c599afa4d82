// SPDX-License-Identifier: BSD-3-Clause
/**
 * Redistributing a distributed vtkOverlappingAMR into one convex region per rank (private to the
 * representation module), for sort-last parallel rendering.
 *
 * ParaView's parallel AMR readers give every rank the whole hierarchy's metadata but the cell
 * data of only some blocks. Here the root box is split into one box of level-0 cells per rank
 * (amrsp::PartitionRootBox: recursive bisection on level-0 cell planes, balancing the cells of all
 * levels), and every rank receives the part of every block inside its region, whichever rank
 * loaded that block. Each rank then renders its region alone; as the regions are disjoint
 * boxes, IceT's ordered compositing by the ranks' bounds gives the whole image.
 */
#ifndef vtkSinglePassAMRRegionSplit_h
#define vtkSinglePassAMRRegionSplit_h

#include "vtkSmartPointer.h" // for the return value

#include <string> // for the error message

class vtkMultiProcessController;
class vtkOverlappingAMR;

namespace vtkSinglePassAMRRegionSplit
{
/**
 * Collective over all ranks of `controller` (every rank calls it, in the same order with respect
 * to other collective calls). Returns a new hierarchy with the same levels, origin, spacings and
 * refinement ratios as `local`, holding every block cut to this rank's region grown by ghost
 * cells (amrsp::GhostedPiece: two cells of the next coarser level on each side; region faces
 * lie on level-0 cell planes, so no cell is split), with all of the block's cell and point
 * arrays; a block loaded on several ranks is taken from the lowest one. `regionBounds` receives
 * the region (without ghosts) in world coordinates; the ranks' regions tile the root box. The
 * rank renders its region only (cropping to `regionBounds`): the ghost cells serve smooth
 * interpolation and gradients at the region's faces, so that the ranks' images join without a
 * seam. A region may hold no block where the level-0 grids leave gaps. Memory: each rank holds
 * its region's part of the hierarchy and its ghost cells, plus, during the exchange, the pieces
 * it sends.
 *
 * Returns null on every rank (and sets `error` to one line naming the problem) when the ranks'
 * metadata differ, a rank has none (`local` null), or the hierarchy cannot be split (no blocks,
 * non-integer refinement, more ranks than level-0 cells to split); the caller then gathers
 * instead.
 */
vtkSmartPointer<vtkOverlappingAMR> SplitByRegion(vtkMultiProcessController* controller,
  vtkOverlappingAMR* local, double regionBounds[6], std::string* error);
}

#endif
