// SPDX-License-Identifier: BSD-3-Clause
//
// Bad and unusual input to vtkSinglePassAMRVolumeMapper, built as VTK data by hand: each case
// must end with one clear error from GetLastError() naming the problem (and draw nothing), or
// render what the data holds; never a crash, a hang or a silent black image. After each error
// the mapper must render the good input again.
//
//   - an input that is not vtkOverlappingAMR (vtkImageData);
//   - an array that is NaN everywhere, or +Inf everywhere; NaN and Inf in some cells;
//   - a level without blocks between two levels with blocks; a last level without blocks;
//   - a refinement ratio of 1 (a level as coarse as the one below it);
//   - a hierarchy over the encoding limits (32 levels of ratio 2);
//   - 1 to 8 iso-values (rendered) and 9 (an error);
//   - a fragment-shader replacement (vtkShaderProperty) that does not compile: one error, and
//     the image back once it is removed;
//   - a driver out of memory (RefuseLargeTextures.c, preloaded by CTest): one error, and the
//     image back once the driver accepts the allocation again.
//
// `TestMapperErrors linear` runs every case with the linear storage (LINEAR_BRICKS), whose pages
// are 2D textures: the driver then refuses them (AMRSP_REFUSE_TEXELS_2D) instead of the atlas.
//
// Exit code 125 (CTest SKIP) with "SKIPPED: ..." when no OpenGL context can be created, unless
// AMRSP_REQUIRE_GPU=1, which turns that into a failure.

#include "MapperTestHelpers.h"

#include "amrsp/Render.h"

#include "vtkSinglePassAMRDataModel.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include "vtkAMRBox.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLShaderProperty.h"
#include "vtkOverlappingAMR.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRectilinearGrid.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVersionMacros.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
using mappertest::Check;
using mappertest::Failures;

/// One block: level, lower corner and cell counts in that level's cells.
struct Block
{
  int Level;
  int Lo[3];
  int Cells[3];
};

using Field = std::function<double(double, double, double)>;

/// A vtkOverlappingAMR on the unit cube with `blocks` (cell array "Density": `value(level, x, y,
/// z)` at the cell centre) and level spacings 1/n0 * prod(ratios): `ratios[l]` refines level l - 1
/// into l.
vtkSmartPointer<vtkOverlappingAMR> MakeAMR(int n0, const std::vector<int>& ratios,
  const std::vector<Block>& blocks, const std::function<double(int, double, double, double)>& value)
{
  const int levels = static_cast<int>(ratios.size());
  std::vector<int> perLevel(levels, 0);
  for (const Block& b : blocks)
  {
    ++perLevel[b.Level];
  }
  auto amr = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkSinglePassAMRDataModel::Initialize(amr, perLevel);
  const double origin[3] = { 0.0, 0.0, 0.0 };
  amr->SetOrigin(origin);
  std::vector<double> h(levels);
  for (int l = 0; l < levels; ++l)
  {
    h[l] = (l == 0 ? 1.0 / n0 : h[l - 1] / ratios[l]);
    const double spacing[3] = { h[l], h[l], h[l] };
    amr->SetSpacing(l, spacing);
    if (l > 0)
    {
      amr->SetRefinementRatio(l - 1, ratios[l]);
    }
  }
  std::vector<int> next(levels, 0);
  for (const Block& b : blocks)
  {
    const double hl = h[b.Level];
    vtkNew<vtkUniformGrid> grid;
    grid->SetOrigin(b.Lo[0] * hl, b.Lo[1] * hl, b.Lo[2] * hl);
    grid->SetSpacing(hl, hl, hl);
    grid->SetDimensions(b.Cells[0] + 1, b.Cells[1] + 1, b.Cells[2] + 1);
    vtkNew<vtkDoubleArray> density;
    density->SetName("Density");
    density->SetNumberOfTuples(static_cast<vtkIdType>(b.Cells[0]) * b.Cells[1] * b.Cells[2]);
    vtkIdType id = 0;
    for (int k = 0; k < b.Cells[2]; ++k)
    {
      for (int j = 0; j < b.Cells[1]; ++j)
      {
        for (int i = 0; i < b.Cells[0]; ++i)
        {
          density->SetValue(id++,
            value(b.Level, (b.Lo[0] + i + 0.5) * hl, (b.Lo[1] + j + 0.5) * hl,
              (b.Lo[2] + k + 0.5) * hl));
        }
      }
    }
    grid->GetCellData()->AddArray(density);
    const int hi[3] = { b.Lo[0] + b.Cells[0] - 1, b.Lo[1] + b.Cells[1] - 1,
      b.Lo[2] + b.Cells[2] - 1 };
    vtkAMRBox box(b.Lo, hi);
    amr->SetAMRBox(b.Level, next[b.Level], box);
    amr->SetDataSet(b.Level, next[b.Level]++, grid);
  }
  // no GenerateParentChildInformation(): VTK 9.2's crashes on a level without blocks, and the
  // mapper does not use it
  return amr;
}

vtkSmartPointer<vtkOverlappingAMR> MakeAMR(
  int n0, const std::vector<int>& ratios, const std::vector<Block>& blocks, const Field& value)
{
  return MakeAMR(
    n0, ratios, blocks, [&value](int, double x, double y, double z) { return value(x, y, z); });
}

double Blob(double x, double y, double z)
{
  const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.45) * (y - 0.45) + (z - 0.5) * (z - 0.5);
  return std::exp(-8.0 * r2);
}

/// A level-0 grid of 8^3 cells and one ratio-2 block over its middle.
vtkSmartPointer<vtkOverlappingAMR> GoodAMR()
{
  return MakeAMR(
    8, { 1, 2 }, { { 0, { 0, 0, 0 }, { 8, 8, 8 } }, { 1, { 4, 4, 4 }, { 8, 8, 8 } } }, Blob);
}

/// The scene: an offscreen window, the mapper and a volume with a transfer function on [0, 1].
struct Scene
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkSinglePassAMRVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;

  Scene()
  {
    Window->SetOffScreenRendering(1);
    Window->SetSize(64, 64);
    Window->AddRenderer(Renderer);
    Renderer->SetBackground(0.0, 0.0, 0.0);
    vtkNew<vtkColorTransferFunction> colours;
    colours->AddRGBPoint(0.0, 0.2, 0.4, 1.0);
    colours->AddRGBPoint(1.0, 1.0, 0.8, 0.2);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(1.0, 0.8);
    vtkNew<vtkVolumeProperty> property;
    property->SetColor(colours);
    property->SetScalarOpacity(opacity);
    property->SetScalarOpacityUnitDistance(0.1);
    Volume->SetProperty(property);
    Volume->SetMapper(Mapper);
    Mapper->SelectScalarArray("Density");
    Mapper->SetScalarModeToUseCellFieldData();
    Renderer->AddVolume(Volume);
  }

  /// Renders `data` and returns the share of pixels that are not black.
  double Render(vtkDataObject* data)
  {
    Mapper->SetInputDataObject(0, data);
    Renderer->ResetCamera();
    Window->Render();
    vtkNew<vtkUnsignedCharArray> pixels;
    Window->GetPixelData(0, 0, 63, 63, 0, pixels);
    int lit = 0;
    for (vtkIdType i = 0; i < pixels->GetNumberOfTuples(); ++i)
    {
      lit += amrsp::IsCovered(pixels->GetPointer(3 * i)) ? 1 : 0;
    }
    return static_cast<double>(lit) / pixels->GetNumberOfTuples();
  }

  std::string Error() const { return Mapper->GetLastError(); }

  /// The last frame's RGB bytes.
  std::vector<unsigned char> Pixels()
  {
    vtkNew<vtkUnsignedCharArray> pixels;
    Window->GetPixelData(0, 0, 63, 63, 0, pixels);
    const unsigned char* p = pixels->GetPointer(0);
    return std::vector<unsigned char>(p, p + pixels->GetNumberOfValues());
  }
};

std::string Percent(double share)
{
  return std::to_string(static_cast<int>(std::lround(100.0 * share))) + " %";
}

/// An error naming `expected`, nothing drawn; then the good input renders again.
void ExpectError(
  Scene& scene, vtkDataObject* data, const std::string& expected, const std::string& what)
{
  const double shown = scene.Render(data);
  const std::string error = scene.Error();
  Check(error.find(expected) != std::string::npos && shown == 0.0,
    what + ": error '" + error + "', " + Percent(shown) + " of the pixels drawn");
  const double again = scene.Render(GoodAMR());
  Check(scene.Error().empty() && again > 0.05,
    what + ": the good input renders again afterwards (" + Percent(again) + ")");
}

/// No error; the volume shows on more than `least` of the pixels.
void ExpectImage(Scene& scene, vtkDataObject* data, double least, const std::string& what)
{
  const double shown = scene.Render(data);
  const std::string error = scene.Error();
  Check(error.empty() && shown > least,
    what + ": rendered on " + Percent(shown) + " of the pixels" +
      (error.empty() ? std::string() : ", error '" + error + "'"));
}

void TestInputs(Scene& scene)
{
  ExpectImage(scene, GoodAMR(), 0.05, "the good hierarchy");

  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 4, 4);
  ExpectError(scene, image, "not a vtkOverlappingAMR", "vtkImageData as input");

  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Block> two = { { 0, { 0, 0, 0 }, { 8, 8, 8 } },
    { 1, { 4, 4, 4 }, { 8, 8, 8 } } };
  ExpectError(scene, MakeAMR(8, { 1, 2 }, two, [nan](double, double, double) { return nan; }),
    "holds no finite value", "Density NaN everywhere");
  ExpectError(scene, MakeAMR(8, { 1, 2 }, two, [inf](double, double, double) { return inf; }),
    "holds no finite value", "Density +Inf everywhere");
  // NaN and Inf in some cells: NaN transparent, +-Inf the transfer function's ends, the rest
  // rendered with the finite range (Mapper.Analytic.nan checks the rule pixel by pixel)
  ExpectImage(scene,
    MakeAMR(8, { 1, 2 }, two,
      [nan, inf](double x, double y, double z)
      { return x < 0.25 ? nan : (y < 0.25 ? inf : (z < 0.2 ? -inf : Blob(x, y, z))); }),
    0.05, "NaN and +-Inf in some cells");

  // a level without blocks: between two levels with blocks, and at the end
  ExpectImage(scene,
    MakeAMR(8, { 1, 2, 2 }, { { 0, { 0, 0, 0 }, { 8, 8, 8 } }, { 2, { 12, 12, 12 }, { 8, 8, 8 } } },
      Blob),
    0.05, "level 1 without blocks, level 2 with one");
  ExpectImage(scene,
    MakeAMR(
      8, { 1, 2, 2 }, { { 0, { 0, 0, 0 }, { 8, 8, 8 } }, { 1, { 4, 4, 4 }, { 8, 8, 8 } } }, Blob),
    0.05, "the last level without blocks");

  // refinement ratio 1: level 1 has the spacing of level 0; its block (twice the field) replaces
  // level 0 where it lies, so the image differs from level 0 alone
  auto twiceInside = [](double x, double y, double z) { return 2.0 * Blob(x, y, z); };
  scene.Mapper->SetSampleDistanceFactor(0.125); // the block's faces restart the samples
  const double ratioOne = scene.Render(MakeAMR(8, { 1, 1 },
    { { 0, { 0, 0, 0 }, { 8, 8, 8 } }, { 1, { 2, 2, 2 }, { 4, 4, 4 } } }, twiceInside));
  const std::vector<unsigned char> withLevel1 = scene.Pixels();
  const std::string ratioOneError = scene.Error();
  scene.Render(MakeAMR(8, { 1 }, { { 0, { 0, 0, 0 }, { 8, 8, 8 } } }, twiceInside));
  const std::vector<unsigned char> levelZero = scene.Pixels();
  ExpectImage(scene, GoodAMR(), 0.05, "the good hierarchy after these");
  // the same field sampled segment by segment (the block's faces split the rays)
  const double same = amrsp::Rmse8(withLevel1, levelZero);
  Check(ratioOneError.empty() && ratioOne > 0.05 && same < 0.8,
    "a refinement ratio of 1 (the level-1 block holds the level-0 values): rendered on " +
      Percent(ratioOne) + " of the pixels, RMSE " + std::to_string(same) +
      " to level 0 alone (bound 0.8)" +
      (ratioOneError.empty() ? std::string() : ", error '" + ratioOneError + "'"));
  const double ratioOneChanged = scene.Render(
    MakeAMR(8, { 1, 1 }, { { 0, { 0, 0, 0 }, { 8, 8, 8 } }, { 1, { 2, 2, 2 }, { 4, 4, 4 } } },
      [](int level, double x, double y, double z)
      { return level == 1 ? 0.0 : 2.0 * Blob(x, y, z); }));
  const double changed = amrsp::Rmse8(scene.Pixels(), levelZero);
  Check(scene.Error().empty() && changed > 5.0 && ratioOneChanged > 0.0,
    "a refinement ratio of 1, the level-1 block empty (0): RMSE " + std::to_string(changed) +
      " to level 0 alone (must exceed 5)");
  scene.Mapper->SetSampleDistanceFactor(1.0);
}

/// A hierarchy the layout cannot encode: 32 levels of ratio 2 over an 8-cell root make the root
/// 2^34 finest cells wide, beyond the shader's 2^30.
void TestEncodingLimit(Scene& scene)
{
  std::vector<int> ratios(32, 2);
  ratios[0] = 1;
  std::vector<Block> blocks = { { 0, { 0, 0, 0 }, { 8, 8, 8 } } };
  for (int l = 1; l < 32; ++l)
  {
    blocks.push_back({ l, { 0, 0, 0 }, { 2, 2, 2 } });
  }
  ExpectError(scene, MakeAMR(8, ratios, blocks, Blob), "2^30", "32 levels of ratio 2");
}

void TestIsoValues(Scene& scene)
{
  vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
  scene.Mapper->SetBlendModeToIsoSurface();
  vtkContourValues* values = scene.Volume->GetProperty()->GetIsoSurfaceValues();
  for (int count = 1; count <= 9; ++count)
  {
    values->SetNumberOfContours(count);
    for (int i = 0; i < count; ++i)
    {
      values->SetValue(i, 0.15 + 0.8 * i / 9.0);
    }
    if (count <= 8)
    {
      ExpectImage(scene, amr, 0.02, std::to_string(count) + " iso-value(s)");
    }
    else
    {
      const double shown = scene.Render(amr);
      const std::string error = scene.Error();
      Check(error.find("1 to 8 values") != std::string::npos && shown == 0.0,
        "9 iso-values: error '" + error + "', " + Percent(shown) + " of the pixels drawn");
      values->SetNumberOfContours(8);
      ExpectImage(scene, amr, 0.02, "back to 8 iso-values");
    }
  }
  values->SetNumberOfContours(0);
  scene.Mapper->SetBlendModeToComposite();
}

/// A driver that runs out of memory (RefuseLargeTextures.c, preloaded by CTest, refuses every 3D
/// texture over AMRSP_REFUSE_TEXELS texels with GL_OUT_OF_MEMORY): one error, nothing drawn, and
/// the same data renders once the driver has the memory again (the CPU data was kept).
void TestOutOfMemory(Scene& scene)
{
  const bool linear = scene.Mapper->GetDataStorage() == vtkSinglePassAMRVolumeMapper::LINEAR_BRICKS;
  if (!dlsym(RTLD_DEFAULT, "amrsp_refuse_large_textures_loaded"))
  {
    const bool required = mappertest::EverythingRequired();
    Check(!required,
      std::string("out of GPU memory: RefuseLargeTextures is not preloaded (") +
        (required ? "required here: AMRSP_REQUIRE_GPU=1)" : "left out)"));
    return;
  }
  const int* active = static_cast<const int*>(dlsym(RTLD_DEFAULT,
    linear ? "amrsp_refuse_large_textures_2d_active" : "amrsp_refuse_large_textures_active"));
  if (!active || !*active)
  {
    // the preload wraps every way VTK loads OpenGL (GLEW's direct links, glXGetProcAddress,
    // eglGetProcAddress, OSMesaGetProcAddress and dlsym): a VTK that took it from elsewhere is
    // not checked, which in CI is a failure
    const bool required = mappertest::EverythingRequired();
    Check(!required,
      std::string("out of GPU memory: VTK loaded ") + (linear ? "glTexImage2D" : "glTexImage3D") +
        " past the preload, not checked here" +
        (required ? " (required here: AMRSP_REQUIRE_GPU=1)" : ""));
    return;
  }
  vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
  // packing: the atlas (two 8^3 bricks), not the tree; linear: the page (one row of 16,384
  // texels), not the transfer table (4,096 x 1) nor the window's 64 x 64 buffers
  const char* limitName = linear ? "AMRSP_REFUSE_TEXELS_2D" : "AMRSP_REFUSE_TEXELS";
  const std::string what = linear ? "linear page" : "atlas";
  const auto expectRefusal = [&](vtkOverlappingAMR* data, const std::string& upload, int frame)
  {
    const double shown = scene.Render(data);
    const std::string error = scene.Error();
    Check((error.find("out of GPU memory") != std::string::npos ||
            error.find("refused") != std::string::npos) &&
        shown == 0.0,
      "the driver refuses the " + what + " of " + upload + ", frame " + std::to_string(frame) +
        ": error '" + error + "', " + Percent(shown) + " of the pixels drawn");
  };
  // a whole upload: the textures freed first, as when the view's context went away
  scene.Mapper->ReleaseGraphicsResources(scene.Window);
  setenv(limitName, linear ? "8192" : "600", 1);
  expectRefusal(amr, "a whole upload", 1);
  expectRefusal(amr, "a whole upload", 2);
  unsetenv(limitName);
  ExpectImage(scene, amr, 0.05, "the same data once the driver has the memory again");
  // a new time step's values while the shown step's textures are kept: they need new textures
  // (without kept steps the values overwrite the shown step's textures and allocate nothing)
  scene.Mapper->SetMaximumKeptStepBytes(VTK_ID_MAX);
  setenv(limitName, linear ? "8192" : "600", 1);
  expectRefusal(GoodAMR(), "a new time step's values", 1);
  unsetenv(limitName);
  scene.Mapper->SetMaximumKeptStepBytes(0);
  ExpectImage(scene, GoodAMR(), 0.05, "a new step once the driver has the memory again");
  setenv(limitName, linear ? "8192" : "600", 1);
  ExpectImage(scene, GoodAMR(), 0.05,
    "a new step of the same structure with the driver refusing new textures (nothing kept: its "
    "values overwrite the shown step's)");
  unsetenv(limitName);
}

void TestShaderFailure(Scene& scene)
{
  vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
  vtkOpenGLShaderProperty* shader =
    vtkOpenGLShaderProperty::SafeDownCast(scene.Volume->GetShaderProperty());
  if (!shader)
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
    return;
  }
  // a replacement that breaks the fragment shader's source
  shader->AddFragmentShaderReplacement("//AMRSP::Defines", true, "this is not GLSL;", false);
  for (int frame = 0; frame < 2; ++frame)
  {
    const double shown = scene.Render(amr);
    const std::string error = scene.Error();
    Check(error.find("failed to compile") != std::string::npos && shown == 0.0,
      "a shader replacement that does not compile, frame " + std::to_string(frame + 1) +
        ": error '" + error + "', " + Percent(shown) + " of the pixels drawn");
  }
  shader->ClearAllFragmentShaderReplacements();
  ExpectImage(scene, amr, 0.05, "the replacement removed");
  // a replacement that compiles (an added, unused definition) renders
  shader->AddFragmentShaderReplacement(
    "//AMRSP::Defines", true, "//AMRSP::Defines\n#define AMRSP_USER_DEFINITION 1", false);
  ExpectImage(scene, amr, 0.05, "a replacement that compiles");
  shader->ClearAllFragmentShaderReplacements();
}

#ifdef AMRSP_VTK_AMR_DATA_OBJECT
/// `amr` with every block replaced by a vtkRectilinearGrid of the same coordinates and cell data;
/// the x coordinates of block 0 of `unevenLevel` get an uneven step when `unevenLevel` >= 0.
vtkSmartPointer<vtkOverlappingAMR> AsRectilinear(vtkOverlappingAMR* amr, int unevenLevel = -1)
{
  auto out = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkSinglePassAMRDataModel::CopyStructure(amr, out);
  for (unsigned int l = 0; l < amr->GetNumberOfLevels(); ++l)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(amr, l); ++i)
    {
      vtkImageData* image = vtkSinglePassAMRDataModel::ImageBlock(amr, l, i);
      int dims[3];
      double origin[3], spacing[3];
      image->GetDimensions(dims);
      image->GetOrigin(origin);
      image->GetSpacing(spacing);
      vtkNew<vtkRectilinearGrid> grid;
      grid->SetDimensions(dims);
      vtkNew<vtkDoubleArray> axes[3];
      for (int a = 0; a < 3; ++a)
      {
        axes[a]->SetNumberOfTuples(dims[a]);
        for (int k = 0; k < dims[a]; ++k)
        {
          axes[a]->SetValue(k, origin[a] + k * spacing[a]);
        }
      }
      if (static_cast<int>(l) == unevenLevel && i == 0)
      {
        axes[0]->SetValue(1, origin[0] + 0.6 * spacing[0]);
      }
      grid->SetXCoordinates(axes[0]);
      grid->SetYCoordinates(axes[1]);
      grid->SetZCoordinates(axes[2]);
      grid->GetCellData()->ShallowCopy(image->GetCellData());
      vtkSinglePassAMRDataModel::SetBlock(out, l, i, grid);
    }
  }
  return out;
}

/// The largest difference of one RGB byte between two frames.
int LargestDifference(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b)
{
  int largest = a.size() == b.size() ? 0 : 255;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    largest = std::max(largest, std::abs(static_cast<int>(a[i]) - static_cast<int>(b[i])));
  }
  return largest;
}
#endif

/// VTK 9.6's data model: a partitioned data set collection that is not AMR is refused by name;
/// an AMR of rectilinear blocks renders as its image-data twin when evenly spaced, and an uneven
/// block is refused by name.
void TestDataModel(Scene& scene)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 4, 4);
  vtkNew<vtkPartitionedDataSet> partitions;
  partitions->SetPartition(0, image);
  vtkNew<vtkPartitionedDataSetCollection> collection;
  collection->SetPartitionedDataSet(0, partitions);
  ExpectError(scene, collection, "a vtkPartitionedDataSetCollection, not a vtkOverlappingAMR",
    "a partitioned data set collection that is not AMR");
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
  vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
  scene.Render(amr);
  const std::vector<unsigned char> imageBlocks = scene.Pixels();
  ExpectImage(scene, AsRectilinear(amr), 0.05, "rectilinear blocks");
  const int same = LargestDifference(imageBlocks, scene.Pixels());
  Check(same <= 1,
    "rectilinear blocks render as their image-data twin: largest byte difference " +
      std::to_string(same) + " (at most 1)");
  // the comparison sees a change of the fine level's values
  vtkSmartPointer<vtkOverlappingAMR> dimmer =
    MakeAMR(8, { 1, 2 }, { { 0, { 0, 0, 0 }, { 8, 8, 8 } }, { 1, { 4, 4, 4 }, { 8, 8, 8 } } },
      [](int level, double x, double y, double z)
      { return (level == 1 ? 0.7 : 1.0) * Blob(x, y, z); });
  scene.Render(AsRectilinear(dimmer));
  const int changed = LargestDifference(imageBlocks, scene.Pixels());
  Check(changed > 8,
    "the comparison rejects a rectilinear AMR whose fine level is dimmer: largest byte "
    "difference " +
      std::to_string(changed) + " (more than 8)");
  ExpectError(scene, AsRectilinear(amr, 1), "block 0 of level 1 is a rectilinear grid",
    "a rectilinear block of uneven spacing");
#else
  std::cout << "rectilinear blocks: not checked, VTK " << VTK_VERSION
            << " has no AMR of rectilinear blocks (VTK 9.6 has)\n";
#endif
}

} // namespace

/// Hierarchies whose metadata contradicts itself or its blocks, damaged in memory as any
/// producer could hand them over: one named error each, nothing drawn, and the good hierarchy
/// renders again afterwards.
void TestContradictions(Scene& scene)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  {
    vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
    const double origin[3] = { nan, 0.0, 0.0 };
    amr->SetOrigin(origin);
    ExpectError(scene, amr, "origin (nan, 0, 0) is not finite", "a NaN origin");
  }
  {
    vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
    const double spacing[3] = { inf, 0.0625, 0.0625 };
    amr->SetSpacing(1, spacing);
    ExpectError(scene, amr, "level 1 has a spacing that is not finite", "an infinite spacing");
  }
  {
    vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
    amr->SetRefinementRatio(0, 4);
    ExpectError(scene, amr, "refines level 0 by 2 (their spacings), its refinement ratio says 4",
      "a refinement ratio that contradicts the spacings");
  }
  {
    vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
    const int lo[3] = { 4, 4, 1 << 30 };
    const int hi[3] = { 7, 7, (1 << 30) + 3 };
    amr->SetAMRBox(1, 0, vtkAMRBox(lo, hi));
    ExpectError(
      scene, amr, "block 0 of level 1 has an AMR box beyond 2^30 cells", "an AMR box at 2^30");
  }
  {
    vtkSmartPointer<vtkOverlappingAMR> amr = GoodAMR();
    const int lo[3] = { 4, 4, 4 };
    const int hi[3] = { 13, 11, 11 }; // ten cells per axis; the block holds eight
    amr->SetAMRBox(1, 0, vtkAMRBox(lo, hi));
    ExpectError(scene, amr, "block 0 of level 1 has dimensions that do not match its AMR box",
      "an AMR box larger than its block");
  }
}

int main(int argc, char* argv[])
{
  const bool linear = argc > 1 && std::string(argv[1]) == "linear";
  vtkNew<vtkRenderWindow> probe;
  std::string why;
  probe->SetOffScreenRendering(1);
  if (!vtkSinglePassAMRVolumeMapper::IsRenderSupported(probe, &why))
  {
    return mappertest::SkipOrFail(why);
  }
  probe->Finalize();
  Scene scene;
  if (linear)
  {
    scene.Mapper->SetDataStorageToLinearBricks();
  }
  TestInputs(scene);
  TestContradictions(scene);
  TestDataModel(scene);
  TestEncodingLimit(scene);
  TestIsoValues(scene);
  TestOutOfMemory(scene);
  TestShaderFailure(scene);
  scene.Window->Finalize();
  std::cout << (Failures() == 0 ? "PASSED" : "FAILED: " + std::to_string(Failures()) + " check(s)")
            << "\n";
  return Failures() == 0 ? 0 : 1;
}
