// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkMultiPassAMRVolumeMapperInternals.h
 * @brief   the multi-pass mapper's state and its per-node draws (private to the module)
 *
 * vtkMultiPassAMRVolumeMapper.cxx holds the build, the upload and the frame;
 * vtkMultiPassAMRVolumeMapperDraw.cxx the node order, the shaders, their uniforms and the draws.
 */
#ifndef vtkMultiPassAMRVolumeMapperInternals_h
#define vtkMultiPassAMRVolumeMapperInternals_h

#include "vtkMultiPassAMRVolumeMapper.h"

#include "vtkAMRMapperAtlasTextures.h"
#include "vtkAMRMapperDepthCopy.h"
#include "vtkAMRMapperOffscreenImage.h"
#include "vtkAMRMapperPackedAtlas.h"
#include "vtkAMRMapperTransferFunctionTable.h"
#include "vtkAMRMapperViewGeometry.h"

#include "amrsp/MultiPassNodes.h"

#include "vtkNew.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkOpenGLState;
class vtkOverlappingAMR;
class vtkRenderer;
class vtkShaderProgram;
class vtkVolume;
class vtkVolumeProperty;
class vtkWindow;

//------------------------------------------------------------------------------
class vtkMultiPassAMRVolumeMapper::vtkInternals
{
public:
  explicit vtkInternals(vtkMultiPassAMRVolumeMapper* self)
    : Self(self)
  {
  }

  // The steps of a frame (see Render). Each returns false after Self->ReportError when the frame
  // cannot be drawn.
  /// Uploads the atlas after a build, or to another context or atlas limit.
  bool UploadAtlas(vtkOpenGLRenderWindow* renWin, vtkOverlappingAMR* amr);
  /// The node raycaster (one variant per centring and depth use; cached by VTK's shader cache)
  /// and the final composite.
  vtkShaderProgram* ReadyShaders(vtkOpenGLRenderWindow* renWin, vtkVolume* vol);
  /// The unit cube's triangles (placed per node by the vertex shader), bound to `program`.
  bool BindCube(vtkShaderProgram* program);
  /// Activates the atlas and transfer table and sets the per-frame uniforms.
  void SetFrameUniforms(vtkShaderProgram* program, vtkVolumeProperty* property,
    const vtkAMRMapperViewGeometry::ViewGeometry& view);
  /// The box the rays integrate in (index units): the root box, cropped (warns once when the
  /// cropping flags are not supported).
  void ClipBox(glm::vec3& clipLo, glm::vec3& clipHi);

  vtkMultiPassAMRVolumeMapper* Self;

  // ---- CPU results of the build
  vtkAMRMapperPackedAtlas::PackedHierarchy Data; // Data.Structure.Values are dropped once uploaded
  amrsp::MultiPassNodes Nodes; // one draw per leaf with data (amrsp/MultiPassNodes.h)
  long long TextureBytes = 0;

  // ---- per frame
  std::vector<int32_t> Order; // indices into Nodes.Draws, front to back
  double OrderSeconds = 0.0;
  long long Passes = 0;

  // ---- OpenGL resources
  vtkOpenGLRenderWindow* Context = nullptr;
  int UploadLimit = 0;                // MaximumAtlasSize of the last upload attempt
  vtkMTimeType UploadedBuildTime = 0; // the build the atlas on the GPU holds
  vtkAMRMapperAtlasTextures Atlas;    // the packed atlas's pages
  vtkAMRMapperDepthCopy Depth;
  vtkAMRMapperOffscreenImage Accumulation; // viewport-sized, nearest filtering
  vtkAMRMapperTransferFunctionTable Transfer;
  vtkNew<vtkOpenGLBufferObject> CubeBuffer;
  vtkNew<vtkOpenGLVertexArrayObject> CubeArray;
  vtkShaderProgram* CubeArrayProgram = nullptr;

  std::string FailedFragmentSource; // do not retry a program that failed to compile

  /// CPU side: convert, build the tree, pack, and list the nodes' draws. Returns false with
  /// `error` set on failure.
  /// `mayRefresh`: a hierarchy of the built structure keeps the tree, layout and draws
  /// (`refreshed` true) and takes the new values only.
  bool Build(vtkOverlappingAMR* amr, const std::string& array, int component, int packLimit,
    int64_t maxPageTexels, bool mayRefresh, bool& refreshed, std::string& error);

  /// Fills Order with the data leaves front to back for rays from `view` (see the class comment).
  void OrderNodes(const vtkAMRMapperViewGeometry::ViewGeometry& view);

  /// Clears the accumulation target and draws the ordered nodes into it, front to back. The
  /// program, its per-frame uniforms, the textures and the cube's vertex array are ready;
  /// `steps` is the sampling distance D of each level in model units. Each node's box is
  /// intersected with [clipLo, clipHi] (index units; the cropping sub-volume or the root box),
  /// and nodes outside it are not drawn.
  void DrawNodes(vtkOpenGLState* state, vtkShaderProgram* program,
    const vtkAMRMapperViewGeometry::ViewGeometry& view, const std::vector<float>& steps,
    const glm::vec3& clipLo, const glm::vec3& clipHi);

  void ReleaseGraphicsResources(vtkWindow* window);
};

#endif
