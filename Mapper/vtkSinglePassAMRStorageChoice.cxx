// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRStorageChoice.h"

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRStorageName(vtkSinglePassAMRStorage storage)
{
  switch (storage)
  {
    case vtkSinglePassAMRStorage::PackedAtlas:
      return "packing";
    case vtkSinglePassAMRStorage::BindlessTextures:
      return "bindless";
    case vtkSinglePassAMRStorage::LinearBricks:
      return "linear";
    case vtkSinglePassAMRStorage::Auto:
      return "auto";
    default:
      return "none";
  }
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRBindlessAccessName(vtkSinglePassAMRBindlessAccess access)
{
  switch (access)
  {
    case vtkSinglePassAMRBindlessAccess::Direct:
      return "direct";
    case vtkSinglePassAMRBindlessAccess::Waterfall:
      return "waterfall";
    case vtkSinglePassAMRBindlessAccess::Auto:
      return "auto";
    default:
      return "none";
  }
}

//------------------------------------------------------------------------------
vtkSinglePassAMRStorageChoice vtkSinglePassAMRStorageChoice::Choose(
  const vtkSinglePassAMRStorageRequest& request, const vtkSinglePassAMRStorageFacts& facts)
{
  using Storage = vtkSinglePassAMRStorage;
  vtkSinglePassAMRStorageChoice c;
  const Storage requested = request.Storage;
  const bool bindlessRuns = facts.Bindless != vtkSinglePassAMRBindlessAccess::None;
  if (requested == Storage::LinearBricks)
  {
    c.Storage = requested;
    return c;
  }
  Storage storage = Storage::PackedAtlas;
  if (requested == Storage::BindlessTextures)
  {
    if (bindlessRuns)
    {
      storage = Storage::BindlessTextures;
    }
    else
    {
      c.FallbackReason = facts.NoBindless;
    }
  }
  else if (requested == Storage::Auto && bindlessRuns &&
    (!facts.AtlasFits || facts.AtlasWaste > request.AutoBindlessWaste))
  {
    storage = Storage::BindlessTextures;
  }
  else if (requested == Storage::Auto &&
    (!facts.AtlasFits || (facts.CpuDriver && facts.BrickBytes >= request.AutoLinearBytes)) &&
    facts.LinearFits && facts.LinearFits())
  {
    c.Storage = Storage::LinearBricks;
    return c;
  }
  if (storage == Storage::PackedAtlas && !facts.AtlasFits)
  {
    c.Error = facts.NoAtlas +
      (requested == Storage::PackedAtlas
          ? std::string()
          : "; bindless textures cannot be used: " + facts.NoBindless) +
      (requested == Storage::Auto ? "; nor do the linear bricks fit the pages this context allows"
                                  : "");
    return c;
  }
  c.Storage = storage;
  c.Access =
    storage == Storage::BindlessTextures ? facts.Bindless : vtkSinglePassAMRBindlessAccess::None;
  return c;
}
