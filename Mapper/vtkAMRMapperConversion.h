// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAMRMapperConversion
 * @brief   converts between vtkOverlappingAMR and the core's amrsp::Hierarchy
 *
 * Not installed (the header exposes core types), but exported: the amrsp tool and the ParaView
 * representation, which link the core themselves, convert through it. vtkOverlappingAMR boxes are
 * inclusive cell ranges in each level's index space relative to the global origin; the core uses
 * half-open boxes in the same index spaces. Refinement ratios are recovered per axis from the level
 * spacings, so anisotropic and per-level ratios survive; a non-integer ratio is an error.
 */
#ifndef vtkAMRMapperConversion_h
#define vtkAMRMapperConversion_h

#include "amrsp/Hierarchy.h"
#include "vtkSinglePassAMRModule.h" // for export macro

#include <string>
#include <vector>

class vtkOverlappingAMR;

class VTKSINGLEPASSAMR_EXPORT vtkAMRMapperConversion
{
public:
  struct ArraySelection
  {
    /// Name of a cell array, or of a point array (vertex-centred data, made continuous across
    /// interfaces); empty selects the first cell array, or the first point array if none.
    std::string Name;
    /// Component of a multi-component array; -1 takes the magnitude (VTK's vector mode
    /// convention). Ignored for one-component arrays.
    int Component = -1;
    /// false: structure only, no values copied (statistics of large hierarchies).
    bool CopyValues = true;
  };

  /// Fills `out` from `amr`. Returns false and a one-line `error` naming the problem (no blocks,
  /// missing array, non-integer refinement, 2D data, missing block data, bad ghost layers).
  /// One-component vtkFloatArray blocks without ghost layers are borrowed, not copied: `out`
  /// holds those arrays until its values are released; other arrays are copied to floats.
  static bool FromOverlappingAMR(vtkOverlappingAMR* amr, const ArraySelection& selection,
    amrsp::Hierarchy& out, std::string& error);

  /// Writes `h` into `out` as vtkUniformGrid blocks sharing `h`'s values (no copy; the arrays
  /// keep them alive after `h` is gone): cell-centred values as a cell array,
  /// vertex-centred values as a point array, and blanking as a vtkGhostType cell array (REFINEDCELL
  /// where the next level refines a cell), as vtkAMRUtilities::BlankCells writes it. Parent-child
  /// information is not generated (VTK code that needs it generates it).
  /// `blanking` false leaves the vtkGhostType array out (1 byte per cell): for consumers that do
  /// not read it, such as this module's mappers.
  static void ToOverlappingAMR(
    const amrsp::Hierarchy& h, vtkOverlappingAMR* out, bool blanking = true);

  /// Names of the cell arrays of the first non-empty block.
  static std::vector<std::string> CellArrayNames(vtkOverlappingAMR* amr);
  /// The array a vtkAbstractVolumeMapper selection asks for: a name, an index into the cell
  /// arrays, or "" (the first cell array, or the first point array if there is none).
  static std::string RequestedArray(
    vtkOverlappingAMR* amr, int accessMode, const char* name, int id);
  /// Names of the cell (points = false) or point arrays of the first non-empty block.
  static std::vector<std::string> ArrayNames(vtkOverlappingAMR* amr, bool points);
};

#endif
