// SPDX-License-Identifier: BSD-3-Clause
// The one rule that picks the single pass's storage (vtkSinglePassAMRStorageChoice::Choose), on
// facts given by hand: no OpenGL. The expectations restate the documented rule (docs/paraview.md,
// Method; docs/design.md, data storage) case by case, not the code's branches.
#include "vtkSinglePassAMRStorageChoice.h"

#include <gtest/gtest.h>

#include <string>

namespace
{
using Storage = amrsp::DataStorage;
using Access = amrsp::BindlessAccess;

/// A GPU context where everything runs: bindless (direct), the atlas fits and wastes 10 %.
vtkSinglePassAMRStorageFacts Everything(int* linearAsked = nullptr)
{
  vtkSinglePassAMRStorageFacts f;
  f.Bindless = Access::Direct;
  f.AtlasFits = true;
  f.AtlasWaste = 0.10;
  f.BrickBytes = 100LL << 20;
  f.CpuDriver = false;
  f.LinearFits = [linearAsked]
  {
    if (linearAsked)
    {
      ++*linearAsked;
    }
    return true;
  };
  return f;
}

vtkSinglePassAMRStorageRequest Asking(Storage storage)
{
  vtkSinglePassAMRStorageRequest r;
  r.Storage = storage;
  r.AutoBindlessWaste = 0.25;
  r.AutoLinearBytes = 64LL << 20;
  return r;
}
} // namespace

TEST(StorageChoice, AnExplicitStorageIsTaken)
{
  for (Storage s : { Storage::PackedAtlas, Storage::BindlessTextures, Storage::LinearBricks })
  {
    const vtkSinglePassAMRStorageChoice c =
      vtkSinglePassAMRStorageChoice::Choose(Asking(s), Everything());
    EXPECT_EQ(c.Storage, s) << amrsp::DataStorageName(s);
    EXPECT_TRUE(c.FallbackReason.empty());
    EXPECT_TRUE(c.Error.empty());
    // the access is the resolved one for bindless only
    EXPECT_EQ(c.Access, s == Storage::BindlessTextures ? Access::Direct : Access::None);
  }
}

TEST(StorageChoice, BindlessFallsBackToTheAtlasWithItsReason)
{
  vtkSinglePassAMRStorageFacts f = Everything();
  f.Bindless = Access::None;
  f.NoBindless = "no GL_ARB_bindless_texture";
  const vtkSinglePassAMRStorageChoice c =
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::BindlessTextures), f);
  EXPECT_EQ(c.Storage, Storage::PackedAtlas);
  EXPECT_EQ(c.FallbackReason, "no GL_ARB_bindless_texture");
  // ... and to nothing, naming both causes, when the atlas does not fit either
  f.AtlasFits = false;
  f.NoAtlas = "the atlas exceeds GL_MAX_3D_TEXTURE_SIZE";
  const vtkSinglePassAMRStorageChoice none =
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::BindlessTextures), f);
  EXPECT_EQ(none.Storage, Storage::None);
  EXPECT_NE(none.Error.find("GL_MAX_3D_TEXTURE_SIZE"), std::string::npos) << none.Error;
  EXPECT_NE(none.Error.find("no GL_ARB_bindless_texture"), std::string::npos) << none.Error;
}

TEST(StorageChoice, TheAtlasThatDoesNotFitIsAnError)
{
  vtkSinglePassAMRStorageFacts f = Everything();
  f.AtlasFits = false;
  f.NoAtlas = "the atlas exceeds MaximumAtlasSize";
  const vtkSinglePassAMRStorageChoice c =
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::PackedAtlas), f);
  EXPECT_EQ(c.Storage, Storage::None);
  EXPECT_EQ(c.Error, "the atlas exceeds MaximumAtlasSize");
}

TEST(StorageChoice, AutoOnAGpu)
{
  int linearAsked = 0;
  // the atlas fits and wastes little: the atlas, without asking whether linear pages fit
  vtkSinglePassAMRStorageFacts f = Everything(&linearAsked);
  EXPECT_EQ(
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f).Storage, Storage::PackedAtlas);
  EXPECT_EQ(linearAsked, 0);
  // more than a quarter of the atlas empty: bindless
  f.AtlasWaste = 0.30;
  EXPECT_EQ(vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f).Storage,
    Storage::BindlessTextures);
  // the atlas does not fit: bindless where it runs ...
  f.AtlasWaste = 0.10;
  f.AtlasFits = false;
  EXPECT_EQ(vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f).Storage,
    Storage::BindlessTextures);
  // ... else the linear bricks
  f.Bindless = Access::None;
  EXPECT_EQ(
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f).Storage, Storage::LinearBricks);
  // ... else nothing, and the error says that the linear pages do not fit either
  f.LinearFits = [] { return false; };
  const vtkSinglePassAMRStorageChoice none =
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f);
  EXPECT_EQ(none.Storage, Storage::None);
  EXPECT_NE(none.Error.find("nor do the linear bricks fit"), std::string::npos) << none.Error;
}

TEST(StorageChoice, AutoOnACpuDriverTakesLinearFromItsThreshold)
{
  vtkSinglePassAMRStorageFacts f = Everything();
  f.Bindless = Access::None;
  f.CpuDriver = true;
  f.BrickBytes = 64LL << 20; // at the threshold
  EXPECT_EQ(
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f).Storage, Storage::LinearBricks);
  f.BrickBytes = (64LL << 20) - 1; // below it: the atlas
  EXPECT_EQ(
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f).Storage, Storage::PackedAtlas);
  // the same bytes on a GPU: the atlas
  f.BrickBytes = 1LL << 30;
  f.CpuDriver = false;
  EXPECT_EQ(
    vtkSinglePassAMRStorageChoice::Choose(Asking(Storage::Auto), f).Storage, Storage::PackedAtlas);
}

TEST(StorageChoice, NamesAreThoseTheToolAndPluginPrint)
{
  EXPECT_STREQ(amrsp::DataStorageName(Storage::PackedAtlas), "packing");
  EXPECT_STREQ(amrsp::DataStorageName(Storage::BindlessTextures), "bindless");
  EXPECT_STREQ(amrsp::DataStorageName(Storage::LinearBricks), "linear");
  EXPECT_STREQ(amrsp::DataStorageName(Storage::Auto), "auto");
  EXPECT_STREQ(amrsp::DataStorageName(Storage::None), "none");
  EXPECT_STREQ(amrsp::BindlessAccessName(Access::Waterfall), "waterfall");
}
