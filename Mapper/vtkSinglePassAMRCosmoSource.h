// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRCosmoSource
 * @brief   synthetic cosmology-like vtkOverlappingAMR for tests and benchmarks
 *
 * Produces a properly nested hierarchy with refinement ratio 2 and several root grids that
 * refines a procedural, clustered density field (halos around cluster centres): deep levels
 * concentrate around density peaks as in a cosmological simulation. The statistics requested
 * (grids, levels, cells) are reproduced closely enough to rebuild the hierarchies of Kaehler &
 * Abel (2013), Table 1. The output is deterministic for a seed. The cell array is "Density".
 *
 * The domain is the unit cube; level-0 spacing is 1 / (root cells per axis).
 */
#ifndef vtkSinglePassAMRCosmoSource_h
#define vtkSinglePassAMRCosmoSource_h

#include "vtkOverlappingAMRAlgorithm.h"
#include "vtkSinglePassAMRModule.h" // for export macro

class VTKSINGLEPASSAMR_EXPORT vtkSinglePassAMRCosmoSource : public vtkOverlappingAMRAlgorithm
{
public:
  static vtkSinglePassAMRCosmoSource* New();
  vtkTypeMacro(vtkSinglePassAMRCosmoSource, vtkOverlappingAMRAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Requested number of grids over all levels (default 2666, the paper's dataset 1).
  vtkSetClampMacro(NumberOfGrids, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(NumberOfGrids, vtkIdType);
  ///@}

  ///@{
  /// Number of levels (default 4).
  vtkSetClampMacro(NumberOfLevels, int, 1, 30);
  vtkGetMacro(NumberOfLevels, int);
  ///@}

  ///@{
  /// Requested number of cells over all grids, covered cells included (default 19e6).
  vtkSetClampMacro(NumberOfCells, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(NumberOfCells, vtkIdType);
  ///@}

  ///@{
  /// Seed of the procedural field (default 1).
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /**
   * A time series (amrsp::GenerateCosmoStep): NumberOfTimeSteps steps at times 0, 1, ...
   * (default 1: no time), the halos drifting from step to step; the grids are rebuilt every
   * RegridEvery steps (default 0: never, the boxes of step 0 throughout), as AMR codes regrid
   * every few steps. The step rendered is the one the pipeline asks for (UPDATE_TIME_STEP,
   * rounded to the nearest step).
   */
  vtkSetClampMacro(NumberOfTimeSteps, int, 1, 1000000);
  vtkGetMacro(NumberOfTimeSteps, int);
  vtkSetClampMacro(RegridEvery, int, 0, 1000000);
  vtkGetMacro(RegridEvery, int);
  ///@}

protected:
  vtkSinglePassAMRCosmoSource();
  ~vtkSinglePassAMRCosmoSource() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkIdType NumberOfGrids = 2666;
  int NumberOfLevels = 4;
  vtkIdType NumberOfCells = 19000000;
  int Seed = 1;
  int NumberOfTimeSteps = 1;
  int RegridEvery = 0;

private:
  vtkSinglePassAMRCosmoSource(const vtkSinglePassAMRCosmoSource&) = delete;
  void operator=(const vtkSinglePassAMRCosmoSource&) = delete;
};

#endif
