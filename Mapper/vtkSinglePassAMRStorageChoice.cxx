// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRStorageChoice.h"

//------------------------------------------------------------------------------
vtkSinglePassAMRStorageChoice vtkSinglePassAMRStorageChoice::Choose(
  const vtkSinglePassAMRStorageRequest& request, const vtkSinglePassAMRStorageFacts& facts)
{
  using Storage = amrsp::DataStorage;
  vtkSinglePassAMRStorageChoice c;
  const Storage requested = request.Storage;
  const bool bindlessRuns = facts.Bindless != amrsp::BindlessAccess::None;
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
  c.Access = storage == Storage::BindlessTextures ? facts.Bindless : amrsp::BindlessAccess::None;
  return c;
}
