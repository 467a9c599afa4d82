// SPDX-License-Identifier: BSD-3-Clause
// Uses the installed AMRSP::SinglePassAMR module: generates a small synthetic hierarchy.
#include "vtkSinglePassAMRCosmoSource.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"

#include <iostream>

int main()
{
  vtkNew<vtkSinglePassAMRCosmoSource> source;
  source->SetNumberOfGrids(40);
  source->SetNumberOfLevels(3);
  source->SetNumberOfCells(100000);
  source->Update();
  vtkOverlappingAMR* amr = vtkOverlappingAMR::SafeDownCast(source->GetOutputDataObject(0));
  if (!amr || amr->GetNumberOfLevels() != 3 || amr->GetTotalNumberOfBlocks() < 35)
  {
    std::cerr << "consumer: unexpected output\n";
    return 1;
  }
  std::cout << "consumer: " << amr->GetNumberOfLevels() << " levels, "
            << amr->GetTotalNumberOfBlocks() << " blocks from the installed SinglePassAMR\n";
  return 0;
}
