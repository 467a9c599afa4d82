// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRStorageChoice.h
 * @brief   the single pass's grid-data storages and the one rule that picks one (private)
 *
 * The storages of the paper (section 5) and ours: the packed atlas, bindless textures, linear
 * bricks (amrsp::DataStorage and amrsp::BindlessAccess, amrsp/DataStorage.h). The mapper's public
 * DataStorageMode and BindlessAccessMode have the same values (checked in
 * vtkSinglePassAMRVolumeMapper.cxx). vtkSinglePassAMRGridStorage gathers the facts
 * from the OpenGL context and the build; vtkSinglePassAMRStorageChoice::Choose decides, with no
 * OpenGL of its own, so the rule lives in this one place.
 */
#ifndef vtkSinglePassAMRStorageChoice_h
#define vtkSinglePassAMRStorageChoice_h

#include "amrsp/DataStorage.h"

#include <functional>
#include <string>

/// What the mapper asks for: its DataStorage and BindlessAccess, and the Auto rule's thresholds.
struct vtkSinglePassAMRStorageRequest
{
  amrsp::DataStorage Storage = amrsp::DataStorage::Auto;
  amrsp::BindlessAccess Access = amrsp::BindlessAccess::Auto;
  /// Auto takes bindless when the atlas would leave more than this fraction of its texels empty.
  double AutoBindlessWaste = 0.25;
  /// Auto takes the linear bricks on a CPU driver from this many bytes of grid data.
  long long AutoLinearBytes = 0;
  /// Whether a new build waits for its upload (new textures); false when the frame draws (or
  /// refreshes the values of) what is uploaded.
  bool NewTextures = true;
};

/// What the OpenGL context and the build allow.
struct vtkSinglePassAMRStorageFacts
{
  /// The bindless access that runs here, or None with the reason in NoBindless.
  amrsp::BindlessAccess Bindless = amrsp::BindlessAccess::None;
  std::string NoBindless;
  /// Whether the packed atlas was built and fits the context, else why not.
  bool AtlasFits = false;
  std::string NoAtlas;
  double AtlasWaste = 0.0;  ///< fraction of the atlas's texels no brick uses
  long long BrickBytes = 0; ///< bytes of grid data
  bool CpuDriver = false;   ///< llvmpipe, softpipe, lavapipe
  /// Whether the linear bricks fit the pages the context allows (asked only when needed).
  std::function<bool()> LinearFits;
};

/// The storage a frame renders with, and why the requested one was not used.
struct vtkSinglePassAMRStorageChoice
{
  amrsp::DataStorage Storage = amrsp::DataStorage::None;      ///< None: nothing can render
  amrsp::BindlessAccess Access = amrsp::BindlessAccess::None; ///< bindless only
  /// Why bindless was not used although it was requested (the frame falls back to the atlas).
  std::string FallbackReason;
  /// Why nothing can render (Storage None).
  std::string Error;

  /**
   * The rule. LinearBricks: always (2D textures, what every context that renders offers).
   * BindlessTextures: where the context runs them, else the atlas with FallbackReason.
   * PackedAtlas: where it fits. Auto: bindless where it runs and the atlas does not fit or wastes
   * more than AutoBindlessWaste of its texels; else the linear bricks where they fit and either
   * the atlas does not fit or a CPU driver holds at least AutoLinearBytes; else the atlas.
   */
  static vtkSinglePassAMRStorageChoice Choose(
    const vtkSinglePassAMRStorageRequest& request, const vtkSinglePassAMRStorageFacts& facts);
};

#endif
