// SPDX-License-Identifier: BSD-3-Clause
#include "ReferenceHierarchy.h"

#include "BlobSimulation.h"

#include "vtkAMRBox.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkStructuredData.h"
#include "vtkUniformGrid.h"
#include "vtkXMLUniformGridAMRWriter.h"

#include <map>
#include <stdexcept>
#include <vector>

#if defined(__has_include)
#if __has_include("vtkAMRDataObject.h")
#define INSITU_REFERENCE_AMR_DATA_OBJECT 1 // VTK 9.6's AMR data model
#endif
#endif

namespace insitu
{

void WriteReferenceHierarchy(const BlobSimulation& simulation, const std::string& path)
{
  // the blocks of each level, in the simulation's order
  std::map<int, std::vector<const Block*>> byLevel;
  for (const Block& b : simulation.Blocks())
  {
    byLevel[b.Level].push_back(&b);
  }
  const int levels = byLevel.empty() ? 0 : byLevel.rbegin()->first + 1;
  std::vector<unsigned int> counts(static_cast<std::size_t>(levels), 0);
  for (const auto& level : byLevel)
  {
    counts[static_cast<std::size_t>(level.first)] = static_cast<unsigned int>(level.second.size());
  }
  vtkNew<vtkOverlappingAMR> amr;
#ifdef INSITU_REFERENCE_AMR_DATA_OBJECT
  amr->Initialize(counts);
  amr->SetGridDescription(vtkStructuredData::VTK_STRUCTURED_XYZ_GRID);
#else
  const std::vector<int> signedCounts(counts.begin(), counts.end());
  amr->Initialize(levels, signedCounts.data());
  amr->SetGridDescription(VTK_XYZ_GRID);
#endif
  const double zero[3] = { 0.0, 0.0, 0.0 };
  amr->SetOrigin(zero);
  for (const auto& level : byLevel)
  {
    const int l = level.first;
    // the cell size of level l from level 0's and the ratio 2 between levels
    double h = simulation.CellSize(0);
    for (int k = 0; k < l; ++k)
    {
      h *= 0.5;
    }
    const double spacing[3] = { h, h, h };
    amr->SetSpacing(static_cast<unsigned int>(l), spacing);
    if (l + 1 < levels)
    {
      amr->SetRefinementRatio(static_cast<unsigned int>(l), 2);
    }
    unsigned int index = 0;
    for (const Block* b : level.second)
    {
      if (b->Values.empty())
      {
        throw std::runtime_error("the reference hierarchy needs every block on this rank");
      }
      int lo[3], hi[3];
      double corner[3];
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = b->Lo[a];
        hi[a] = b->Lo[a] + b->Cells[a] - 1;
        corner[a] = lo[a] * h;
      }
      amr->SetAMRBox(static_cast<unsigned int>(l), index, vtkAMRBox(lo, hi));
      vtkNew<vtkUniformGrid> grid;
      grid->SetOrigin(corner);
      grid->SetSpacing(spacing);
      grid->SetDimensions(b->Cells[0] + 1, b->Cells[1] + 1, b->Cells[2] + 1);
      // the analytic field at the cell centres, in an array of its own
      vtkNew<vtkFloatArray> density;
      density->SetName("density");
      density->SetNumberOfTuples(static_cast<vtkIdType>(b->Cells[0]) * b->Cells[1] * b->Cells[2]);
      vtkIdType n = 0;
      for (int k = 0; k < b->Cells[2]; ++k)
      {
        for (int j = 0; j < b->Cells[1]; ++j)
        {
          for (int i = 0; i < b->Cells[0]; ++i)
          {
            density->SetValue(n++,
              static_cast<float>(simulation.Field(
                corner[0] + (i + 0.5) * h, corner[1] + (j + 0.5) * h, corner[2] + (k + 0.5) * h)));
          }
        }
      }
      grid->GetCellData()->AddArray(density);
      amr->SetDataSet(static_cast<unsigned int>(l), index, grid);
      ++index;
    }
  }
  vtkNew<vtkXMLUniformGridAMRWriter> writer;
  writer->SetInputData(amr);
  writer->SetFileName(path.c_str());
  if (!writer->Write())
  {
    throw std::runtime_error("could not write " + path);
  }
}

} // namespace insitu
