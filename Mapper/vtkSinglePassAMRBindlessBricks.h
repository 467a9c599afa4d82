// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRBindlessBricks
 * @brief   the bindless storage: one R32F 3D texture per grid, its handle resident
 *
 * Private to the module. The paper's bindless storage (section 5.2), behind the
 * vtkSinglePassAMRGridData interface: the bricks, and the RG32UI texture of their handles
 * (one texel per brick, low and high word) that Shaders/StorageBindless.glsl reads. The bricks
 * are plain OpenGL texture names, not vtkTextureObjects: each
 * vtkTextureObject keeps a vtkWeakPointer to its render window, and VTK's weak pointers (9.1 to
 * 9.6) are kept in one list per object, so creating and deleting n of them costs O(n^2): 280,000
 * bricks took 26.8 s to create on llvmpipe (VTK 9.2) and 25.5 s on an H100 (VTK 9.6), against
 * 1.1 s with plain names. Here the set holds one weak pointer, to the context of its textures.
 *
 * Invariants: Handles[i] is the resident bindless handle of texture Names[i], Extents[i] its
 * size; all are empty when nothing is uploaded. The textures are freed by ReleaseGraphicsResources
 * (the context current, as VTK calls it) or, when the set is destroyed first, with the context
 * pushed.
 */
#ifndef vtkSinglePassAMRBindlessBricks_h
#define vtkSinglePassAMRBindlessBricks_h

#include "vtkSinglePassAMRGridData.h"

#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkTextureObject;
class vtkWindow;

class vtkSinglePassAMRBindlessBricks : public vtkSinglePassAMRGridData
{
public:
  vtkSinglePassAMRBindlessBricks() = default;
  ~vtkSinglePassAMRBindlessBricks() override;
  vtkSinglePassAMRBindlessBricks(const vtkSinglePassAMRBindlessBricks&) = delete;
  vtkSinglePassAMRBindlessBricks& operator=(const vtkSinglePassAMRBindlessBricks&) = delete;

  /// Replaces the set (the previous textures are freed in their own context) with one texture
  /// per extent in `renWin`, its context current: brick g is extents[g] texels (x fastest) of
  /// texels(g), sampled linearly when `linear`, else nearest, clamped to the edge. Returns false
  /// with `error` when the driver refuses a texture or a handle; the set is then released.
  bool Create(vtkOpenGLRenderWindow* renWin, const std::vector<glm::ivec3>& extents,
    const std::function<const float*(std::size_t)>& texels, bool linear, std::string& error);

  /// Writes new texels into the set's textures in place when it holds one texture per extent,
  /// of these extents, in `renWin` (its context current): brick g gets texels(g). The handles
  /// stay resident and unchanged (the bindless extension allows new contents, not new storage).
  /// Returns false, changing nothing, when the set does not match; true after the writes.
  bool Overwrite(vtkOpenGLRenderWindow* renWin, const std::vector<glm::ivec3>& extents,
    const std::function<const float*(std::size_t)>& texels);

  /// The resident handles, one per brick (empty when nothing is uploaded).
  const std::vector<std::uint64_t>& GetHandles() const { return this->Handles; }
  /// The most textures one set of this object held when it was freed (Mesa's zink gives their
  /// slots back only later: vtkSinglePassAMRGridStorage::Choose counts them).
  long long GetLargestReleasedSet() const { return this->LargestReleased; }

  ///@{
  /// vtkSinglePassAMRGridData: one brick per grid of RayCastingData::Data (a brick over
  /// GL_MAX_3D_TEXTURE_SIZE is an error naming it) and the handles texture; UploadValues writes
  /// a step's values into the same bricks (the handles stay), or makes new ones when the set
  /// differs; no kept steps. Activate sets amrspHandles.
  amrsp::DataStorage GetStorage() const override { return amrsp::DataStorage::BindlessTextures; }
  bool Upload(vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data, std::string& error,
    const std::function<void(double)>& progress) override;
  bool UploadValues(vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data,
    std::string& error, const std::function<void(double)>& progress) override;
  std::unique_ptr<vtkSinglePassAMRGridData> NewForAnotherStep() const override { return nullptr; }
  void Describe(vtkSinglePassAMRShaderVariant& variant) const override;
  void Activate(vtkShaderProgram* program) override;
  void Deactivate() override;
  long long GetBytes() const override { return this->Bytes; }
  /// Makes the handles non-resident and deletes the textures when `window` is their context;
  /// another window's call frees nothing.
  void ReleaseGraphicsResources(vtkWindow* window) override;
  ///@}

private:
  /// Frees the textures in their context (pushed), or forgets them when that context is gone.
  void Clear();
  /// Frees the textures; their context is current.
  void Release();

  vtkWeakPointer<vtkOpenGLRenderWindow> Context;
  std::vector<unsigned int> Names;
  std::vector<std::uint64_t> Handles;
  std::vector<glm::ivec3> Extents;                  ///< of Names[i], in texels
  vtkSmartPointer<vtkTextureObject> HandlesTexture; ///< RG32UI, Handles[i] at texel i
  long long Bytes = 0; ///< bricks and handles texture (RayCastingData's figure)
  long long LargestReleased = 0;
};

#endif
