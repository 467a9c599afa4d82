// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Where the single-pass mapper keeps the grid values on the GPU, and how its bindless storage
/// reads them: the one enumeration and name table of each setting, used by the mapper
/// (vtkSinglePassAMRVolumeMapper's DataStorageMode and BindlessAccessMode have these values), the
/// ParaView plugin, the amrsp tool (its method names, --bindless-access) and its bench ("storage").
/// The rule that resolves Auto is the mapper's (vtkSinglePassAMRStorageChoice.h).

#include "amrsp/SettingNames.h"

#include <string>

namespace amrsp
{

/// The grid data's storage (paper, section 5, and ours). None: nothing rendered or can render.
enum class DataStorage : int
{
  None = -1,
  Auto = 0,             ///< the mapper's rule
  PackedAtlas = 1,      ///< every brick packed into one R32F 3D atlas (or a few pages of it)
  BindlessTextures = 2, ///< one R32F 3D texture per brick, reached through bindless handles
  LinearBricks = 3      ///< the bricks back to back in 2D R32F pages, found through a table
};

constexpr SettingName<DataStorage> DataStorageNames[] = {
  { DataStorage::PackedAtlas, "packing" },
  { DataStorage::BindlessTextures, "bindless" },
  { DataStorage::LinearBricks, "linear" },
  { DataStorage::Auto, "auto" },
};

/// How the bindless storage reads a brick whose handle may differ between shader invocations.
enum class BindlessAccess : int
{
  None = -1,
  Auto = 0,      ///< direct with GL_NV_gpu_shader5, else waterfall with GL_ARB_shader_ballot
  Direct = 1,    ///< sampler3D(handle) as is
  Waterfall = 2, ///< one distinct handle per loop iteration (GL_ARB_shader_ballot)
};

constexpr SettingName<BindlessAccess> BindlessAccessNames[] = {
  { BindlessAccess::Auto, "auto" },
  { BindlessAccess::Direct, "direct" },
  { BindlessAccess::Waterfall, "waterfall" },
};

/// "packing", "bindless", "linear", "auto", or "none".
inline const char* DataStorageName(DataStorage storage)
{
  return NameIn(DataStorageNames, storage);
}

/// "auto", "direct", "waterfall", or "none".
inline const char* BindlessAccessName(BindlessAccess access)
{
  return NameIn(BindlessAccessNames, access);
}

/// What a frame rendered with, in words: the storage's name, and for bindless its access in
/// parentheses ("bindless (direct)"). What the tool prints, the bench writes as "storage" and the
/// plugin shows as SinglePassDataStorage.
inline std::string StorageInWords(DataStorage storage, BindlessAccess access)
{
  std::string words = DataStorageName(storage);
  if (storage == DataStorage::BindlessTextures)
  {
    words += std::string(" (") + BindlessAccessName(access) + ")";
  }
  return words;
}

} // namespace amrsp
