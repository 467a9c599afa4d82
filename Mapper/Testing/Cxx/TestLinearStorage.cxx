// SPDX-License-Identifier: BSD-3-Clause
//
// The linear storage of vtkSinglePassAMRVolumeMapper (LINEAR_BRICKS: the bricks back to back in
// 2D R32F pages, found through a brick table) against the packed atlas and the CPU integrators,
// on any OpenGL 3.2 context.
//
// Bounds (RMSE over RGB, 0-255): linear vs packing 0 for cell data (the same float texels through
// the same traversal, nearest fetches: measured 0), < 0.05 for vertex data (the shader's own
// trilinear mix against the texture unit's filtering, as the bindless path); vs the CPU kD-tree
// integrator < 1.0 and vs the tree-free CPU reference < 2.0 (the bounds of
// TestSinglePassAMRMapper). The mapper is asked which storage rendered, so a silent fall back to
// the atlas cannot pass as linear, and a broken layer stride (a shader replacement) is shown to
// fail the bound.

#include "AmrspDataset.h"
#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/BrickPacking.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkSinglePassAMRLinearBricks.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"

#include <algorithm>
#include <iostream>
#include <string>

namespace
{
using namespace amrsp;
using namespace amrsp::harness;
using mappertest::BoundVsKdTree;
using mappertest::Check;
using mappertest::CoveredRmse;
using mappertest::Failures;
using mappertest::Fixed;
using mappertest::LoadHierarchy;
using mappertest::Settings;
using mappertest::ShaderProperty;
using Mapper = vtkSinglePassAMRVolumeMapper;

constexpr double BoundVsPackingVertices = 0.05;

std::string StorageName(Mapper* m)
{
  return Mapper::GetDataStorageName(m->GetLastDataStorage());
}

/// Renders `h` with packing and with the linear storage (one page, then several) and compares.
void TestDataset(const std::string& name, Hierarchy h, double referenceBound, bool smooth = false)
{
  std::cout << "dataset " << name << " (" << h.Grids.size() << " grids)\n";
  RenderSettings s = Settings(h, mappertest::Request(96, 96));
  s.SmoothCellData = smooth;
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  const Image kd = RenderKdTree(h, enc, s);
  const Image ref = RenderReference(h, s);
  const double vsPackingBound = h.VertexCentred ? BoundVsPackingVertices : 0.0;
  double ms = 0.0;

  SinglePassRenderer gpu(h, s, ViewAngles(), DataStorage::PackedAtlas);
  Mapper* m = gpu.GetMapper();
  const Image packed = gpu.Render(0.0, ms);
  Check(m->GetLastDataStorage() == Mapper::PACKED_ATLAS, "packing rendered: " + StorageName(m));

  m->SetDataStorageToLinearBricks();
  const int builds = m->GetNumberOfBuilds();
  const Image linear = gpu.Render(0.0, ms);
  Check(m->GetLastDataStorage() == Mapper::LINEAR_BRICKS && m->GetNumberOfLinearPages() == 1,
    "the linear storage rendered, one page: " + StorageName(m) + ", " +
      std::to_string(m->GetNumberOfLinearPages()) + " pages");
  const double lVsP = Rmse(linear, packed), lVsKd = CoveredRmse(linear, kd),
               lVsRef = CoveredRmse(linear, ref);
  Check(lVsP <= vsPackingBound,
    "linear vs packing RMSE " + Fixed(lVsP) + " <= " + Fixed(vsPackingBound));
  Check(lVsKd < BoundVsKdTree,
    "linear vs CPU kD-tree RMSE " + Fixed(lVsKd) + " < " + Fixed(BoundVsKdTree));
  const double refBound = referenceBound;
  Check(
    lVsRef < refBound, "linear vs CPU reference RMSE " + Fixed(lVsRef) + " < " + Fixed(refBound));
  // the other ray loop (the flat loop; the nested loops are the default)
  const mappertest::RayLoopComparison otherLoop = mappertest::CompareOtherRayLoop(gpu, linear);
  Check(
    otherLoop.Same(), "linear: the other ray loop renders the same image: " + otherLoop.Describe());
  const mappertest::RayCasterComparison otherCaster =
    mappertest::CompareOtherRayCaster(gpu, linear, &kd);
  Check(otherCaster.Same(), "linear: the " + otherCaster.Describe() + " renders the same image");

  // memory: the tree textures, the empty-space flags, the ropes, every cell once (whole rows of
  // the page) and the brick table (RG32UI, laid out like the tree)
  const glm::ivec3 tableDims = TextureDimsFor(h.Grids.size());
  const long long floor = static_cast<long long>(enc.Tree.Bytes() + enc.Ropes.Bytes() +
    9 * enc.DataNodes.Texels.size() + SeparateBrickBytes(h) +
    static_cast<std::size_t>(tableDims.x) * tableDims.y * tableDims.z * 8);
  const long long bytes = m->GetTextureBytes();
  Check(bytes >= floor && bytes < floor + (16384LL * 4),
    "texture bytes " + std::to_string(bytes) + ": tree + flags + ropes + cells + table = " +
      std::to_string(floor) + ", plus less than one row");

  // several pages (a third of the data each, at least the largest brick, in whole rows of
  // 16384 texels): the same image
  if (h.Grids.size() >= 3)
  {
    std::size_t largest = 0;
    for (const glm::ivec3& e : BrickExtents(h, h.VertexCentred))
    {
      largest = std::max(largest, static_cast<std::size_t>(e.x) * e.y * e.z * sizeof(float));
    }
    const std::size_t row = 16384 * sizeof(float);
    const std::size_t page = std::max(largest, SeparateBrickBytes(h) / 3 + 1);
    const vtkIdType pageBytes = static_cast<vtkIdType>((page + row - 1) / row * row);
    m->SetMaximumAtlasPageBytes(pageBytes);
    const Image paged = gpu.Render(0.0, ms);
    const int pages = m->GetNumberOfLinearPages();
    Check(m->GetLastDataStorage() == Mapper::LINEAR_BRICKS && pages >= 2 && pages <= 4 &&
        Rmse(paged, linear) == 0.0,
      "linear pages of " + std::to_string(pageBytes) + " bytes: " + std::to_string(pages) +
        " pages, RMSE to one page " + Fixed(Rmse(paged, linear)));
    m->SetMaximumAtlasPageBytes((vtkIdType(2048) - 64) << 20);
  }

  // the orbit: another view
  {
    RenderSettings fs = s;
    fs.View.Azimuth(120.0);
    const double e = Rmse(gpu.Render(120.0, ms), RenderKdTree(h, enc, fs));
    Check(e < BoundVsKdTree, "linear, orbit 120 deg: vs CPU kD-tree RMSE " + Fixed(e));
  }

  // the linear build skipped the packing: asking for packing again builds it and renders the
  // packed image
  m->SetDataStorageToPackedAtlas();
  const Image back = gpu.Render(0.0, ms);
  Check(m->GetLastDataStorage() == Mapper::PACKED_ATLAS && Rmse(back, packed) == 0.0 &&
      m->GetNumberOfBuilds() > builds,
    "packing after linear renders the packed image again (builds " +
      std::to_string(m->GetNumberOfBuilds() - builds) + ")");
  m->SetDataStorageToLinearBricks();
  gpu.Render(0.0, ms);
  m->ReleaseGraphicsResources(gpu.GetRenderer()->GetRenderWindow());
  const Image again = gpu.Render(0.0, ms);
  Check(m->GetLastDataStorage() == Mapper::LINEAR_BRICKS && Rmse(again, linear) == 0.0,
    "linear after ReleaseGraphicsResources renders the same image");

  // the check can fail: a layer stride one row too long reads the wrong cells
  if (vtkOpenGLShaderProperty* shader = ShaderProperty(gpu))
  {
    shader->AddFragmentShaderReplacement("int nxy = nx * int(entry.y >> 16u);", false,
      "int nxy = nx * (int(entry.y >> 16u) + 1);", false);
    const Image broken = gpu.Render(0.0, ms);
    shader->ClearAllFragmentShaderReplacements();
    const double bVsP = Rmse(broken, packed);
    Check(bVsP > std::max(vsPackingBound, 0.5),
      "a wrong layer stride is rejected: RMSE to packing " + Fixed(bVsP));
  }
  else
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
  }
}

/// AUTO_STORAGE: the atlas below AutoLinearBytes, the linear bricks above it on a CPU driver, and
/// the linear bricks rather than an error where no atlas fits and bindless cannot run.
void TestAutomaticChoice()
{
  std::cout << "automatic storage choice\n";
  Hierarchy h = LoadHierarchy("synthetic:cosmo:grids=30,levels=3,cells=60k,seed=5");
  const RenderSettings s = Settings(h, mappertest::Request(64, 64));
  SinglePassRenderer gpu(h, s, ViewAngles(), DataStorage::PackedAtlas);
  Mapper* m = gpu.GetMapper();
  double ms = 0.0;
  const Image packed = gpu.Render(0.0, ms);
  vtkRenderWindow* window = gpu.GetRenderer()->GetRenderWindow();
  const bool cpu = mappertest::IsCpuDriver(window);
  const bool bindless = Mapper::IsBindlessSupported(window);
  std::cout << "  info    " << (cpu ? "a CPU driver" : "not a CPU driver") << ", "
            << (bindless ? "bindless textures" : "no bindless textures") << "\n";
  m->SetDataStorageToAuto();
  m->SetAutoBindlessWaste(1.0);
  const Image small = gpu.Render(0.0, ms);
  Check(m->GetLastDataStorage() == Mapper::PACKED_ATLAS && Rmse(small, packed) == 0.0,
    "auto with 0.24 MB of grid data, under AutoLinearBytes = " +
      std::to_string(m->GetAutoLinearBytes()) + ": " + StorageName(m));
  m->SetAutoLinearBytes(0);
  const Image large = gpu.Render(0.0, ms);
  Check(m->GetLastDataStorage() == (cpu ? Mapper::LINEAR_BRICKS : Mapper::PACKED_ATLAS) &&
      Rmse(large, packed) == 0.0,
    "auto with AutoLinearBytes = 0: " + StorageName(m) + (cpu ? " (CPU driver)" : ""));
  m->SetAutoLinearBytes(vtkIdType(64) << 20);

  // linear bricks that cannot fit four pages of one row (16,384 texels): the feasibility test
  // AUTO_STORAGE relies on says so, and asking for them is an error naming the pages
  {
    Hierarchy big = LoadHierarchy("synthetic:cosmo:grids=60,levels=3,cells=100k,seed=4");
    Settings(big, mappertest::Request(64, 64));
    auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
    Check(vtkSinglePassAMRLinearBricks::Fits(gl, big, false, 0) &&
        !vtkSinglePassAMRLinearBricks::Fits(gl, big, false, 4),
      "100k cells fit linear pages of 1 GiB, not pages of one row");
    SinglePassRenderer tight(big, s, ViewAngles(), DataStorage::LinearBricks);
    tight.GetMapper()->SetMaximumAtlasPageBytes(4);
    std::string error;
    try
    {
      tight.Render(0.0, ms);
    }
    catch (const GpuError& e)
    {
      error = e.what();
    }
    Check(error.find("linear pages") != std::string::npos,
      "linear bricks over four pages of one row: an error, not a black image: " + error);
  }

  m->SetMaximumAtlasSize(8); // no atlas can be packed
  const Image noAtlas = gpu.Render(0.0, ms);
  Check(m->GetLastDataStorage() == (bindless ? Mapper::BINDLESS_TEXTURES : Mapper::LINEAR_BRICKS) &&
      Rmse(noAtlas, packed) < BoundVsPackingVertices,
    "auto when no atlas fits MaximumAtlasSize = 8 renders, no error: " + StorageName(m));
}

} // namespace

int main()
{
  return mappertest::RunChecks(
    []
    {
      using namespace mappertest;
      TestDataset(
        "one grid", LoadHierarchy("synthetic:cosmo:grids=1,levels=1,cells=20k,seed=2"), RefOneGrid);
      TestDataset("enzo_moving7", LoadHierarchy(EnzoPath()), RefEnzo);
      TestDataset(
        "amrex_plt1_Y", LoadHierarchy(std::string(AMRSP_DATA_DIR) + "/amrex_plt1_Y"), RefAmrex);
      TestDataset("synthetic, vertex-centred",
        LoadHierarchy("synthetic:cosmo:grids=60,levels=3,cells=100k,seed=4", "vertex"), RefVertex);
      TestDataset("synthetic, smooth cells",
        LoadHierarchy("synthetic:cosmo:grids=60,levels=3,cells=100k,seed=4"), RefSmooth, true);
      TestAutomaticChoice();
    });
}
