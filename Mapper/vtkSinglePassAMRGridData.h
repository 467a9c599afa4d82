// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRGridData
 * @brief   one storage of the grid values on the GPU, behind the interface the mapper uses
 *
 * Private to the module. Each storage is one class with one .cxx and one GLSL piece:
 * vtkAMRMapperAtlasTextures (PackedAtlas, Shaders/StoragePackedAtlas.glsl),
 * vtkSinglePassAMRBindlessBricks (BindlessTextures, Shaders/StorageBindless.glsl) and
 * vtkSinglePassAMRLinearBricks (LinearBricks, Shaders/StorageLinearBricks.glsl).
 * vtkSinglePassAMRGridStorage owns the tree textures every storage shares and one of these;
 * vtkSinglePassAMRStorageChoice decides which. A new storage is a class here, a GLSL piece, an
 * amrsp::DataStorage value and a case of the choice.
 *
 * Invariant: the methods that touch OpenGL run with the context of `renWin` current (as VTK
 * calls Render and ReleaseGraphicsResources); Upload and UploadValues leave nothing uploaded
 * when they fail.
 */
#ifndef vtkSinglePassAMRGridData_h
#define vtkSinglePassAMRGridData_h

#include "amrsp/DataStorage.h"
#include "amrsp/RayCastingData.h"

#include <functional>
#include <memory>
#include <string>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkWindow;
struct vtkSinglePassAMRShaderVariant;

class vtkSinglePassAMRGridData
{
public:
  virtual ~vtkSinglePassAMRGridData() = default;

  /// Which storage this is: PackedAtlas, BindlessTextures or LinearBricks.
  virtual amrsp::DataStorage GetStorage() const = 0;

  /// The data-node texels this storage's shader piece reads: the block's texel in the atlas, or
  /// in the grid's own brick.
  virtual const amrsp::UIntTexture3D& GetDataNodeTexels(const amrsp::RayCastingData& data) const
  {
    return data.BrickLocalDataNodeTexels;
  }

  /// Uploads the grid values of `data` into new textures, replacing what this holds. Returns
  /// false with a one-line `error` when a texture exceeds a limit or the driver refuses one.
  /// `progress` gets the fraction uploaded (0 to 1).
  virtual bool Upload(vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data,
    std::string& error, const std::function<void(double)>& progress) = 0;

  /// A new time step's values of the structure uploaded last (amrsp::RefreshValues), written in
  /// place where the textures allow it. Same errors as Upload.
  virtual bool UploadValues(vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data,
    std::string& error, const std::function<void(double)>& progress) = 0;

  /// An empty storage of this kind and these settings, for a time step kept beside this one;
  /// null where the storage keeps no steps (bindless: its resident handles are limited).
  virtual std::unique_ptr<vtkSinglePassAMRGridData> NewForAnotherStep() const = 0;

  /// The shader variant's fields of this storage (its pages, row width).
  virtual void Describe(vtkSinglePassAMRShaderVariant& variant) const = 0;

  /// Activates the textures and sets the samplers and sizes of the storage's GLSL piece in
  /// `program`; Deactivate undoes it.
  virtual void Activate(vtkShaderProgram* program) = 0;
  virtual void Deactivate() = 0;

  /// GPU bytes of the uploaded grid values (the tree textures not included).
  virtual long long GetBytes() const = 0;

  /// Frees the textures when `window` is their context.
  virtual void ReleaseGraphicsResources(vtkWindow* window) = 0;
};

#endif
