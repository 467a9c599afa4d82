// SPDX-License-Identifier: BSD-3-Clause
// vtkOverlappingAMR -> amrsp::Hierarchy: ghost layers, ratios, bad input.
#include "vtkAMRMapperConversion.h"
#include "vtkSinglePassAMRDataModel.h"

#include "vtkAMRBox.h"
#include "vtkAMRUtilities.h"
#include "vtkDataSetAttributes.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkUniformGrid.h"

#include <gtest/gtest.h>

namespace
{

/// One level-0 block with box [0,3]^3 and `ghost` layers of ghost cells around it, plus a level-1
/// block with spacing `fineSpacing`. Cell values: 1000 * level + linear cell index of the block.
vtkNew<vtkOverlappingAMR> MakeAMR(int ghost, double fineSpacing, int components = 1)
{
  vtkNew<vtkOverlappingAMR> amr;
  vtkSinglePassAMRDataModel::Initialize(amr, { 1, 1 });
  const double origin[3] = { 0, 0, 0 };
  amr->SetOrigin(origin);
  amr->SetGridDescription(vtkSinglePassAMRDataModel::XYZGrid);
  const double s0[3] = { 1, 1, 1 }, s1[3] = { fineSpacing, fineSpacing, fineSpacing };
  amr->SetSpacing(0, s0);
  amr->SetSpacing(1, s1);
  amr->SetRefinementRatio(0, 2);
  amr->SetRefinementRatio(1, 2);
  const int lo0[3] = { 0, 0, 0 }, hi0[3] = { 3, 3, 3 }, lo1[3] = { 2, 2, 2 }, hi1[3] = { 5, 5, 5 };
  amr->SetAMRBox(0, 0, vtkAMRBox(lo0, hi0));
  amr->SetAMRBox(1, 0, vtkAMRBox(lo1, hi1));
  for (int level = 0; level < 2; ++level)
  {
    const int n = 4 + (level == 0 ? 2 * ghost : 0);
    vtkNew<vtkUniformGrid> g;
    g->SetDimensions(n + 1, n + 1, n + 1);
    const double h = level == 0 ? 1.0 : fineSpacing;
    const double corner = level == 0 ? -ghost * h : 2 * h; // the boxes' lower corners
    g->SetOrigin(corner, corner, corner);
    g->SetSpacing(h, h, h);
    vtkNew<vtkDoubleArray> a;
    a->SetName("phi");
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(n * n * n);
    for (vtkIdType i = 0; i < n * n * n; ++i)
    {
      for (int c = 0; c < components; ++c)
      {
        a->SetComponent(i, c, 1000.0 * level + static_cast<double>(i) + c);
      }
    }
    g->GetCellData()->AddArray(a);
    amr->SetDataSet(level, 0, g);
  }
  return amr;
}

TEST(Conversion, StripsGhostLayers)
{
  auto amr = MakeAMR(1, 0.5);
  vtkAMRMapperConversion::ArraySelection sel;
  amrsp::Hierarchy h;
  std::string error;
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  ASSERT_EQ(h.Grids.size(), 2u);
  EXPECT_EQ(h.ArrayName, "phi");
  EXPECT_EQ(h.RefinementRatio[1], glm::ivec3(2));
  EXPECT_EQ(h.Grids[0].Cells.Hi, glm::i64vec3(4));
  ASSERT_EQ(h.Values[0].size(), 64u);
  // inner cell (0,0,0) of the box is ghosted cell (1,1,1) of the 6^3 block
  EXPECT_EQ(h.Values[0][0], static_cast<float>((1 * 6 + 1) * 6 + 1));
  EXPECT_EQ(h.Values[0][63], static_cast<float>((4 * 6 + 4) * 6 + 4));
  EXPECT_EQ(h.Values[1][5], 1005.0f);
}

TEST(Conversion, VectorMagnitudeAndComponent)
{
  auto amr = MakeAMR(0, 0.5, 2);
  vtkAMRMapperConversion::ArraySelection sel;
  amrsp::Hierarchy h;
  std::string error;
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  EXPECT_FLOAT_EQ(h.Values[0][3], std::sqrt(3.0f * 3.0f + 4.0f * 4.0f));
  sel.Component = 1;
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  EXPECT_EQ(h.Values[0][3], 4.0f);
}

TEST(Conversion, PointDataIsVertexCentred)
{
  auto amr = MakeAMR(0, 0.5);
  for (int level = 0; level < 2; ++level)
  {
    vtkImageData* g = vtkSinglePassAMRDataModel::ImageBlock(amr, level, 0);
    vtkNew<vtkDoubleArray> p;
    p->SetName("pressure");
    p->SetNumberOfTuples(g->GetNumberOfPoints());
    for (vtkIdType i = 0; i < g->GetNumberOfPoints(); ++i)
    {
      double x[3];
      g->GetPoint(i, x);
      p->SetValue(i, 2.0 * x[0] + x[1] - x[2]); // linear: the interface fix keeps it exact
    }
    g->GetPointData()->AddArray(p);
  }
  vtkAMRMapperConversion::ArraySelection sel;
  sel.Name = "pressure";
  amrsp::Hierarchy h;
  std::string error;
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  EXPECT_TRUE(h.VertexCentred);
  ASSERT_EQ(h.Values[0].size(), 125u);
  ASSERT_EQ(h.Values[1].size(), 125u);
  // level-1 vertex (1,1,1) of the box [2,5]^3 sits at world (1.5, 1.5, 1.5)
  EXPECT_FLOAT_EQ(h.Values[1][(1 * 5 + 1) * 5 + 1], 3.0f);
  EXPECT_FLOAT_EQ(h.Values[1][0], 2.0f); // a dangling corner keeps the linear field's value
}

TEST(Conversion, IntegerAndDoubleArraysBecomeFloat)
{
  auto amr = MakeAMR(0, 0.5);
  for (int level = 0; level < 2; ++level)
  {
    vtkImageData* g = vtkSinglePassAMRDataModel::ImageBlock(amr, level, 0);
    vtkNew<vtkIntArray> ints;
    ints->SetName("count");
    vtkNew<vtkUnsignedCharArray> bytes;
    bytes->SetName("flag");
    for (vtkIdType i = 0; i < g->GetNumberOfCells(); ++i)
    {
      ints->InsertNextValue(static_cast<int>(-7 * i));
      bytes->InsertNextValue(static_cast<unsigned char>(i % 256));
    }
    g->GetCellData()->AddArray(ints);
    g->GetCellData()->AddArray(bytes);
  }
  vtkAMRMapperConversion::ArraySelection sel;
  amrsp::Hierarchy h;
  std::string error;
  sel.Name = "count";
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  EXPECT_EQ(h.Values[0][9], -63.0f);
  sel.Name = "flag";
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  EXPECT_EQ(h.Values[1][63], 63.0f);
  sel.Name = "phi"; // vtkDoubleArray
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  EXPECT_EQ(h.Values[1][5], 1005.0f);
}

TEST(Conversion, BadInputGivesOneClearError)
{
  amrsp::Hierarchy h;
  std::string error;
  vtkAMRMapperConversion::ArraySelection sel;
  EXPECT_FALSE(vtkAMRMapperConversion::FromOverlappingAMR(MakeAMR(0, 0.3), sel, h, error));
  EXPECT_NE(error.find("unsupported refinement"), std::string::npos) << error;
  sel.Name = "rho";
  EXPECT_FALSE(vtkAMRMapperConversion::FromOverlappingAMR(MakeAMR(0, 0.5), sel, h, error));
  EXPECT_NE(error.find("no cell array named 'rho' (available: phi)"), std::string::npos) << error;
  vtkNew<vtkOverlappingAMR> empty;
  EXPECT_FALSE(vtkAMRMapperConversion::FromOverlappingAMR(empty, sel, h, error));
  EXPECT_NE(error.find("no blocks"), std::string::npos) << error;
}

} // namespace

namespace
{
/// Two levels of float cell data, 4^3 cells each, values 100 * grid + cell index.
amrsp::Hierarchy FloatHierarchy()
{
  amrsp::Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(2) };
  h.ArrayName = "density";
  h.Grids = { { 0, amrsp::Box{ glm::i64vec3(0), glm::i64vec3(4) } },
    { 1, amrsp::Box{ glm::i64vec3(2), glm::i64vec3(6) } } };
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    std::vector<float> v(64);
    for (std::size_t i = 0; i < v.size(); ++i)
    {
      v[i] = static_cast<float>(100 * g + i);
    }
    h.Values.emplace_back(std::move(v));
  }
  return h;
}

vtkFloatArray* BlockArray(vtkOverlappingAMR* amr, unsigned int level)
{
  return vtkFloatArray::SafeDownCast(
    vtkSinglePassAMRDataModel::Block(amr, level, 0)->GetCellData()->GetArray("density"));
}
} // namespace

TEST(Conversion, ToOverlappingAMRSharesTheValuesAndKeepsThemAlive)
{
  vtkNew<vtkOverlappingAMR> amr;
  const float* level1 = nullptr;
  {
    amrsp::Hierarchy h = FloatHierarchy();
    level1 = static_cast<const amrsp::Hierarchy&>(h).Values[1].data();
    vtkAMRMapperConversion::ToOverlappingAMR(h, amr, false);
    ASSERT_NE(BlockArray(amr, 1), nullptr);
    EXPECT_EQ(BlockArray(amr, 1)->GetPointer(0), level1); // no copy
    EXPECT_EQ(vtkSinglePassAMRDataModel::Block(amr, 1, 0)->GetCellData()->GetArray(
                vtkDataSetAttributes::GhostArrayName()),
      nullptr); // blanking left out on request
    // writing the hierarchy afterwards copies its values first: VTK's array is unchanged
    h.Values[1][0] = -1.0f;
    EXPECT_EQ(BlockArray(amr, 1)->GetValue(0), 100.0f);
  } // h is gone: the arrays still hold the values
  // a shallow copy shares the lent buffer and outlives the original array
  vtkNew<vtkFloatArray> copy;
  copy->ShallowCopy(BlockArray(amr, 1));
  amr->Initialize();
  EXPECT_EQ(copy->GetPointer(0), level1);
  EXPECT_EQ(copy->GetValue(63), 163.0f);
}

TEST(Conversion, FromOverlappingAMRBorrowsFloatArraysWithoutGhosts)
{
  vtkNew<vtkOverlappingAMR> amr;
  vtkAMRMapperConversion::ToOverlappingAMR(FloatHierarchy(), amr);
  vtkAMRMapperConversion::ArraySelection sel;
  sel.Name = "density";
  amrsp::Hierarchy h;
  std::string error;
  ASSERT_TRUE(vtkAMRMapperConversion::FromOverlappingAMR(amr, sel, h, error)) << error;
  const amrsp::Hierarchy& read = h;
  EXPECT_TRUE(read.Values[0].IsBorrowed());
  EXPECT_EQ(read.Values[0].data(), BlockArray(amr, 0)->GetPointer(0));
  EXPECT_EQ(read.Values[1][63], 163.0f);
  // the borrowed values hold their arrays: the hierarchy outlives the AMR dataset
  vtkFloatArray* array = BlockArray(amr, 1);
  const int references = array->GetReferenceCount();
  amr->Initialize();
  EXPECT_EQ(array->GetReferenceCount(), references - 1);
  EXPECT_EQ(read.Values[1][62], 162.0f);
  h = amrsp::Hierarchy();
}

TEST(Conversion, BlankingMatchesVtkBlankCells)
{
  // ToOverlappingAMR writes REFINEDCELL itself; VTK's BlankCells on a second conversion with the
  // ghost arrays removed must mark exactly the same cells (refinement 2, three levels,
  // children not aligned to their parents' cells).
  amrsp::Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(2), glm::ivec3(2) };
  auto box = [](int x0, int y0, int z0, int x1, int y1, int z1) {
    return amrsp::Box{ glm::i64vec3(x0, y0, z0), glm::i64vec3(x1, y1, z1) };
  };
  h.Grids = { { 0, box(0, 0, 0, 8, 8, 4) }, { 1, box(2, 2, 0, 8, 10, 8) },
    { 1, box(9, 3, 1, 15, 9, 7) }, { 2, box(5, 5, 1, 14, 12, 9) } };
  for (const amrsp::Grid& g : h.Grids)
  {
    h.Values.emplace_back(static_cast<std::size_t>(g.Cells.Cells()), 1.0f);
  }
  vtkNew<vtkOverlappingAMR> ours;
  vtkAMRMapperConversion::ToOverlappingAMR(h, ours);
  vtkNew<vtkOverlappingAMR> vtks;
  vtkAMRMapperConversion::ToOverlappingAMR(h, vtks);
  for (unsigned int l = 0; l < vtks->GetNumberOfLevels(); ++l)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(vtks, l); ++i)
    {
      vtkSinglePassAMRDataModel::Block(vtks, l, i)
        ->GetCellData()
        ->RemoveArray(vtkDataSetAttributes::GhostArrayName());
      ASSERT_EQ(vtkSinglePassAMRDataModel::Block(vtks, l, i)
                  ->GetCellData()
                  ->GetArray(vtkDataSetAttributes::GhostArrayName()),
        nullptr);
    }
  }
  vtkAMRUtilities::BlankCells(vtks);
  int refined = 0;
  for (unsigned int l = 0; l < ours->GetNumberOfLevels(); ++l)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(ours, l); ++i)
    {
      vtkDataArray* a = vtkSinglePassAMRDataModel::Block(ours, l, i)
                          ->GetCellData()
                          ->GetArray(vtkDataSetAttributes::GhostArrayName());
      vtkDataArray* b = vtkSinglePassAMRDataModel::Block(vtks, l, i)
                          ->GetCellData()
                          ->GetArray(vtkDataSetAttributes::GhostArrayName());
      ASSERT_NE(a, nullptr);
      ASSERT_NE(b, nullptr);
      ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
      for (vtkIdType c = 0; c < a->GetNumberOfTuples(); ++c)
      {
        EXPECT_EQ(a->GetTuple1(c), b->GetTuple1(c))
          << "level " << l << " block " << i << " cell " << c;
        refined += a->GetTuple1(c) == vtkDataSetAttributes::REFINEDCELL ? 1 : 0;
      }
    }
  }
  // level 0: 3*4*4 + 4*4*4 cells under the two level-1 grids; level 1: 5*4*5 under the level-2
  // grid (boxes coarsened outward), so the comparison is not vacuous
  EXPECT_EQ(refined, 48 + 64 + 100);
}
