// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMultiPassAMRVolumeMapper.h"

#include "vtkSinglePassAMRDepthCopy.h"
#include "vtkSinglePassAMRPackedAtlas.h"
#include "vtkSinglePassAMRProxyBox.h"
#include "vtkSinglePassAMRScopedBlendedDraw.h"
#include "vtkSinglePassAMRShaderComposer.h"
#include "vtkSinglePassAMRTransferFunctionTable.h"
#include "vtkSinglePassAMRViewGeometry.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/IntegerMath.h"
#include "amrsp/SampleStep.h"
#include "amrsp/KdTree.h"

#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkOverlappingAMR.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkSinglePassAMROffscreenImage.h"
#include "vtkSinglePassAMROpenGL.h"

// GLSL embedded at build time (vtk_encode_string)
#include "amrsp_MultiPassAMR_frag_glsl.h"
#include "amrsp_MultiPassAMR_vert_glsl.h"
#include "amrsp_BrickSample_glsl.h"
#include "amrsp_RayCommon_glsl.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace
{

/// Everything one draw needs about its data node (the per-node uniforms).
struct NodeDraw
{
  /// The node's box in level-0 index units, computed from the root down in float exactly as the
  /// single-pass shader computes it during its traversal (plane = lo + split * cell size).
  float Lo[3];
  float Hi[3];
  /// Size of a cell of the node's data level, level-0 index units (float, as the shaders').
  float CellSize[3];
  int Level = 0;
  /// First and last cell of the node in its level's index space (exact: floor and ceiling of the
  /// node's finest-cell box), and the atlas texel holding FirstCell.
  int FirstCell[3];
  int LastCell[3];
  int AtlasOffset[3];
  int Page = 0; ///< the atlas page (texture) holding the node's brick
};

} // namespace

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
    const vtkSinglePassAMRViewGeometry::ViewGeometry& view);
  /// The box the rays integrate in (index units): the root box, cropped (warns once when the
  /// cropping flags are not supported).
  void ClipBox(glm::vec3& clipLo, glm::vec3& clipHi);

  vtkMultiPassAMRVolumeMapper* Self;

  // ---- CPU results of the build
  vtkSinglePassAMRPackedAtlas::PackedHierarchy
    Data;                          // Data.Structure.Values are dropped once uploaded
  std::vector<NodeDraw> Draws;     // one per leaf with data
  std::vector<int32_t> DrawOfNode; // kD node index -> index into Draws, -1 for none
  long long DataNodes = 0;         // types (a) and (b)
  long long TextureBytes = 0;

  // ---- per frame
  std::vector<int32_t> Order; // indices into Draws, front to back
  double OrderSeconds = 0.0;
  long long Passes = 0;

  // ---- OpenGL resources
  vtkOpenGLRenderWindow* Context = nullptr;
  int UploadLimit = 0;                // MaximumAtlasSize of the last upload attempt
  vtkMTimeType UploadedBuildTime = 0; // the build the atlas on the GPU holds
  std::vector<vtkSmartPointer<vtkTextureObject>> AtlasPages; // one per atlas page
  vtkSinglePassAMRDepthCopy Depth;
  vtkSinglePassAMROffscreenImage Accumulation; // viewport-sized, nearest filtering
  vtkSinglePassAMRTransferFunctionTable Transfer;
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
  void OrderNodes(const vtkSinglePassAMRViewGeometry::ViewGeometry& view);

  /// Clears the accumulation target and draws the ordered nodes into it, front to back. The
  /// program, its per-frame uniforms, the textures and the cube's vertex array are ready;
  /// `steps` is the sampling distance D of each level in model units. Each node's box is
  /// intersected with [clipLo, clipHi] (index units; the cropping sub-volume or the root box),
  /// and nodes outside it are not drawn.
  void DrawNodes(vtkOpenGLState* state, vtkShaderProgram* program,
    const vtkSinglePassAMRViewGeometry::ViewGeometry& view, const std::vector<float>& steps,
    const glm::vec3& clipLo, const glm::vec3& clipHi);

  void ReleaseGraphicsResources(vtkWindow* window);
};

//------------------------------------------------------------------------------
bool vtkMultiPassAMRVolumeMapper::vtkInternals::Build(vtkOverlappingAMR* amr,
  const std::string& array, int component, int packLimit, int64_t maxPageTexels, bool mayRefresh,
  bool& refreshed, std::string& error)
{
  const bool ok = vtkSinglePassAMRPackedAtlas::RefreshPackedHierarchy(
    amr, array, component, packLimit, maxPageTexels, mayRefresh, this->Data, refreshed, error);
  if (ok && refreshed)
  {
    return true; // a time step of the same structure: the nodes to draw are the same
  }
  this->Draws.clear();
  this->DrawOfNode.clear();
  if (!ok)
  {
    return false;
  }
  const amrsp::Hierarchy& h = this->Data.Structure;
  const amrsp::KdTree& tree = this->Data.Tree;
  const glm::i64vec3 finest = h.CumulativeRatio(tree.FinestLevel);
  std::vector<glm::vec3> levelCellSize;
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    levelCellSize.push_back(glm::vec3(h.CellSize(l)));
  }

  // Walk the tree from the root with the float boxes the single-pass traversal computes, and
  // record every leaf with data.
  struct Pending
  {
    int32_t Node;
    glm::vec3 Lo;
    glm::vec3 Hi;
  };
  std::vector<Pending> stack;
  stack.push_back(Pending{ 0, glm::vec3(amrsp::RegionLoIndex(h, tree, tree.Root().Region)),
    glm::vec3(amrsp::RegionHiIndex(h, tree, tree.Root().Region)) });
  this->DrawOfNode.assign(tree.Nodes.size(), -1);
  this->DataNodes = 0;
  while (!stack.empty())
  {
    const Pending p = stack.back();
    stack.pop_back();
    const amrsp::KdNode& node = tree.Nodes[static_cast<std::size_t>(p.Node)];
    this->DataNodes += node.HasData() ? 1 : 0;
    if (!node.IsLeaf())
    {
      const int a = node.Axis;
      const float plane = p.Lo[a] +
        static_cast<float>(node.Split) * levelCellSize[static_cast<std::size_t>(node.Level)][a];
      Pending lower{ node.FirstChild, p.Lo, p.Hi };
      Pending upper{ node.FirstChild + 1, p.Lo, p.Hi };
      lower.Hi[a] = plane;
      upper.Lo[a] = plane;
      stack.push_back(upper);
      stack.push_back(lower);
      continue;
    }
    if (!node.HasData())
    {
      continue; // empty space: nothing to draw
    }
    const amrsp::Grid& grid = h.Grids[static_cast<std::size_t>(node.Grid)];
    const glm::i64vec3 toData = finest / h.CumulativeRatio(grid.Level);
    const glm::ivec3 origin = this->Data.Atlas.Origins[static_cast<std::size_t>(node.Grid)];
    NodeDraw d;
    d.Level = grid.Level;
    d.Page = this->Data.Atlas.PageOfGrid[static_cast<std::size_t>(node.Grid)];
    for (int a = 0; a < 3; ++a)
    {
      d.Lo[a] = p.Lo[a];
      d.Hi[a] = p.Hi[a];
      d.CellSize[a] = levelCellSize[static_cast<std::size_t>(grid.Level)][a];
      const int64_t first = amrsp::FloorDiv(node.Region.Lo[a], toData[a]);
      const int64_t last = amrsp::CeilDiv(node.Region.Hi[a], toData[a]) - 1;
      d.FirstCell[a] = static_cast<int>(first);
      d.LastCell[a] = static_cast<int>(last);
      d.AtlasOffset[a] = origin[a] + static_cast<int>(first - grid.Cells.Lo[a]);
    }
    this->DrawOfNode[static_cast<std::size_t>(p.Node)] = static_cast<int32_t>(this->Draws.size());
    this->Draws.push_back(d);
  }
  this->TextureBytes = this->Data.Atlas.TotalTexels() * static_cast<long long>(sizeof(float));
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::OrderNodes(
  const vtkSinglePassAMRViewGeometry::ViewGeometry& view)
{
  const auto t0 = std::chrono::steady_clock::now();
  const amrsp::Hierarchy& h = this->Data.Structure;
  const amrsp::KdTree& tree = this->Data.Tree;
  // the eye in finest cells (the unit of the nodes' exact regions), and the viewing direction in
  // index space (only its signs matter)
  const glm::dvec3 finest(h.CumulativeRatio(tree.FinestLevel));
  const glm::dvec3 eye =
    (glm::dvec3(view.Eye[0], view.Eye[1], view.Eye[2]) - h.Origin) / h.Spacing0 * finest;
  const glm::dvec3 direction =
    glm::dvec3(view.Direction[0], view.Direction[1], view.Direction[2]) / h.Spacing0;

  this->Order.clear();
  std::vector<int32_t> stack{ 0 };
  while (!stack.empty())
  {
    const int32_t n = stack.back();
    stack.pop_back();
    const amrsp::KdNode& node = tree.Nodes[static_cast<std::size_t>(n)];
    if (node.IsLeaf())
    {
      const int32_t draw = this->DrawOfNode[static_cast<std::size_t>(n)];
      if (draw >= 0)
      {
        this->Order.push_back(draw);
      }
      continue;
    }
    // Any ray from the eye that crosses the split plane goes from the eye's side to the other
    // (parallel rays: from the side they come from), so visiting the eye's side first orders
    // every ray's segments front to back.
    const int a = node.Axis;
    const double plane =
      static_cast<double>(tree.Nodes[static_cast<std::size_t>(node.FirstChild)].Region.Hi[a]);
    const bool lowerFirst = view.Parallel ? direction[a] >= 0.0 : eye[a] < plane;
    stack.push_back(lowerFirst ? node.FirstChild + 1 : node.FirstChild); // visited second
    stack.push_back(lowerFirst ? node.FirstChild : node.FirstChild + 1);
  }
  this->OrderSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::DrawNodes(vtkOpenGLState* state,
  vtkShaderProgram* program, const vtkSinglePassAMRViewGeometry::ViewGeometry& view,
  const std::vector<float>& steps, const glm::vec3& clipLo, const glm::vec3& clipHi)
{
  // per-node uniforms are set directly through their locations (thousands per frame)
  const GLint nodeLo = program->FindUniform("amrspNodeLo");
  const GLint nodeHi = program->FindUniform("amrspNodeHi");
  const GLint cellSize = program->FindUniform("amrspCellSize");
  const GLint step = program->FindUniform("amrspStep");
  const GLint firstCell = program->FindUniform("amrspFirstCell");
  const GLint lastCell = program->FindUniform("amrspLastCell");
  const GLint atlasOffset = program->FindUniform("amrspAtlasOffset");
  const GLint atlas = program->FindUniform("amrspAtlas");
  const GLint atlasSize = program->FindUniform("amrspAtlasSize");
  int boundPage = 0; // SetFrameUniforms bound page 0

  // one draw per data node, blended front to back ("under") into the cleared target
  vtkOpenGLState::ScopedglViewport viewportSaved(state);
  vtkOpenGLState::ScopedglClearColor clearColorSaved(state);
  vtkOpenGLState::ScopedglEnableDisable scissorSaved(state, GL_SCISSOR_TEST);

  this->Accumulation.BeginDrawing(state);

  // back faces: one fragment per covered pixel, also with the eye inside the box; a mirroring
  // volume transform flips the winding. Front to back: dst += (1 - dst.a) * src for colour and
  // opacity (src premultiplied)
  const vtkSinglePassAMRScopedBlendedDraw blended(
    state, view.Mirrored ? GL_BACK : GL_FRONT, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  // no near/far clipping: the back faces of a node between the eye and the near plane still
  // reach the shader, which starts the rays at the eye as the single-pass shader does
  // (primitives behind the eye are still clipped, w > 0)
  const bool depthClampWas = glIsEnabled(GL_DEPTH_CLAMP) == GL_TRUE;
  glEnable(GL_DEPTH_CLAMP);

  for (const int32_t d : this->Order)
  {
    const NodeDraw& node = this->Draws[static_cast<std::size_t>(d)];
    float lo[3], hi[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::max(node.Lo[a], clipLo[a]);
      hi[a] = std::min(node.Hi[a], clipHi[a]);
      inside = inside && lo[a] < hi[a];
    }
    if (!inside)
    {
      continue;
    }
    glUniform3fv(nodeLo, 1, lo);
    glUniform3fv(nodeHi, 1, hi);
    glUniform3fv(cellSize, 1, node.CellSize);
    glUniform1f(step, steps[static_cast<std::size_t>(node.Level)]);
    glUniform3iv(firstCell, 1, node.FirstCell);
    glUniform3iv(lastCell, 1, node.LastCell);
    glUniform3iv(atlasOffset, 1, node.AtlasOffset);
    if (node.Page != boundPage)
    {
      // several atlas pages: every page is active on a unit of its own
      const glm::vec3 size(this->Data.Atlas.Pages[static_cast<std::size_t>(node.Page)].Dims);
      glUniform1i(atlas, this->AtlasPages[static_cast<std::size_t>(node.Page)]->GetTextureUnit());
      glUniform3fv(atlasSize, 1, &size.x);
      boundPage = node.Page;
    }
    glDrawArrays(GL_TRIANGLES, 0, 36);
  }
  this->Passes = static_cast<long long>(this->Order.size());

  if (!depthClampWas)
  {
    glDisable(GL_DEPTH_CLAMP);
  }
  this->CubeArray->Release();
  this->Accumulation.EndDrawing();
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Depth.ReleaseGraphicsResources(window);
  for (vtkSmartPointer<vtkTextureObject>& page : this->AtlasPages)
  {
    page->ReleaseGraphicsResources(window);
  }
  this->AtlasPages.clear();
  this->Accumulation.ReleaseGraphicsResources(window);
  this->Transfer.ReleaseGraphicsResources(window);
  this->CubeBuffer->ReleaseGraphicsResources();
  this->CubeArray->ReleaseGraphicsResources();
  this->CubeArrayProgram = nullptr;
  this->Context = nullptr;
}

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkMultiPassAMRVolumeMapper);

//------------------------------------------------------------------------------
vtkMultiPassAMRVolumeMapper::vtkMultiPassAMRVolumeMapper()
  : Internals(new vtkInternals(this))
{
}

//------------------------------------------------------------------------------
vtkMultiPassAMRVolumeMapper::~vtkMultiPassAMRVolumeMapper()
{
  delete this->Internals;
}

//------------------------------------------------------------------------------
bool vtkMultiPassAMRVolumeMapper::BuildData(vtkOverlappingAMR* amr, const std::string& array,
  bool mayRefresh, bool& refreshed, std::string& error)
{
  // ProgressEvent: 0 and 1 around the build; the upload in the first render 0 to 1 again
  this->BeginProgressPhase(PROGRESS_BUILD, "converting the AMR blocks, kD-tree and packing");
  const bool built =
    this->Internals->Build(amr, array, this->ArrayComponent, this->MaximumAtlasSize,
      static_cast<int64_t>(this->MaximumAtlasPageBytes / amrsp::AtlasTexelBytes), mayRefresh,
      refreshed, error);
  this->UpdateProgress(1.0);
  return built;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::GetBuiltBounds(double bounds[6])
{
  const double* b = this->Internals->Data.Bounds;
  std::copy(b, b + 6, bounds);
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  in.Passes = 0;
  vtkOpenGLRenderWindow* renWin = nullptr;
  vtkOverlappingAMR* amr = this->BeginFrame(ren, renWin);
  if (!amr)
  {
    return;
  }
  if (this->GetBlendMode() != vtkVolumeMapper::COMPOSITE_BLEND)
  {
    this->ReportError("the multi-pass method implements composite blending only (blend mode " +
      std::to_string(this->GetBlendMode()) + " requested)");
    return;
  }
  // data: rebuilt only when the input, the array selection or the packing limit changed
  if (!this->EnsureBuilt(amr))
  {
    this->ReportError(this->GetBuildError());
    return;
  }
  vtkVolumeProperty* property = vol->GetProperty();
  if (!property)
  {
    this->ReportError("the volume has no vtkVolumeProperty");
    return;
  }
  if (!in.UploadAtlas(renWin, amr))
  {
    return;
  }
  if (!in.Transfer.Update(renWin, property, in.Data.ScalarRange, this->GetBuildTime()))
  {
    this->ReportError("uploading the transfer-function table failed");
    return;
  }
  if (!in.Transfer.GetWarning().empty())
  {
    this->WarnOnce(in.Transfer.GetWarning());
  }
  vtkShaderProgram* program = in.ReadyShaders(renWin, vol);
  if (!program)
  {
    return;
  }
  vtkSinglePassAMRViewGeometry::ViewGeometry view;
  std::string error;
  if (!vtkSinglePassAMRViewGeometry::ComputeViewGeometry(ren, vol, view, error) ||
    !in.Accumulation.Ensure(renWin, view.Width, view.Height, false, error))
  {
    this->ReportError(error);
    return;
  }
  if (!in.BindCube(program))
  {
    return;
  }
  // the opaque geometry's depth, read before the accumulation target is bound
  if (this->UseDepthBuffer)
  {
    in.Depth.CopyFrom(renWin, view); // leaves the depth texture active
  }
  in.OrderNodes(view); // CPU: the data nodes front to back for this camera
  in.SetFrameUniforms(program, property, view);
  std::vector<float> steps;
  for (double edge : in.Data.LevelMinEdge)
  {
    steps.push_back(static_cast<float>(amrsp::LevelSampleStep(this->SampleDistanceFactor, edge)));
  }
  glm::vec3 clipLo, clipHi;
  in.ClipBox(clipLo, clipHi);
  in.DrawNodes(renWin->GetState(), program, view, steps, clipLo, clipHi);
  for (vtkTextureObject* page : in.AtlasPages)
  {
    page->Deactivate();
  }
  in.Transfer.GetTexture()->Deactivate();
  if (this->UseDepthBuffer)
  {
    in.Depth.Depth->Deactivate();
  }
  // the accumulated image over the renderer's framebuffer (premultiplied "over")
  if (!in.Accumulation.CompositeOver(renWin, error))
  {
    this->ReportError(error);
    return;
  }
  vtkOpenGLCheckErrorMacro("failed after vtkMultiPassAMRVolumeMapper::Render");
}

//------------------------------------------------------------------------------
bool vtkMultiPassAMRVolumeMapper::vtkInternals::UploadAtlas(
  vtkOpenGLRenderWindow* renWin, vtkOverlappingAMR* amr)
{
  vtkMultiPassAMRVolumeMapper* self = this->Self;
  if (!this->AtlasPages.empty() && this->Context == renWin &&
    this->UploadLimit == self->MaximumAtlasSize &&
    this->UploadedBuildTime == self->GetBuildTime().GetMTime())
  {
    return true;
  }
  this->UploadLimit = self->MaximumAtlasSize;
  // the CPU copy is dropped after an upload: uploading to another context rebuilds it
  if (!this->Data.Structure.HasValues() && !self->Rebuild(amr))
  {
    self->ReportError(self->GetBuildError());
    return false;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  this->AtlasPages.clear();
  const amrsp::AtlasPages& pages = this->Data.Atlas;
  self->BeginProgressPhase(PROGRESS_UPLOAD, "uploading the atlas");
  for (std::size_t p = 0; p < pages.Pages.size(); ++p)
  {
    vtkSmartPointer<vtkTextureObject> page;
    const double share = 1.0 / static_cast<double>(pages.Pages.size());
    if (!vtkSinglePassAMRPackedAtlas::UploadAtlas(renWin,
          pages.Pages.size() == 1
            ? this->Data.Structure
            : amrsp::PageHierarchy(this->Data.Structure, pages, static_cast<int>(p)),
          pages.Pages[p], this->Data.VertexCentred, self->MaximumAtlasSize, page, error,
          [self, p, share](double f)
          { self->UpdateProgress((static_cast<double>(p) + f) * share); }))
    {
      // keep the CPU data: a later context (or a smaller input) may succeed
      this->AtlasPages.clear();
      self->ReportError(error);
      return false;
    }
    this->AtlasPages.push_back(page);
  }
  std::vector<amrsp::GridValues>().swap(this->Data.Structure.Values); // the atlas holds them
  this->Context = renWin;
  this->UploadedBuildTime = self->GetBuildTime().GetMTime();
  self->UploadSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

//------------------------------------------------------------------------------
vtkShaderProgram* vtkMultiPassAMRVolumeMapper::vtkInternals::ReadyShaders(
  vtkOpenGLRenderWindow* renWin, vtkVolume* vol)
{
  vtkMultiPassAMRVolumeMapper* self = this->Self;
  std::string defines = this->Data.VertexCentred ? "#define AMRSP_VERTEX_CENTRED 1\n"
                                                 : "#define AMRSP_CELL_CENTRED 1\n";
  if (self->UseDepthBuffer)
  {
    defines += "#define AMRSP_USE_DEPTH 1\n";
  }
  if (this->Transfer.IsLogarithmic())
  {
    defines += "#define AMRSP_LOG_TRANSFER 1\n";
  }
  const std::string fragment =
    vtkSinglePassAMRShaderComposer::ComposeFragmentShader(amrsp_MultiPassAMR_frag_glsl, defines,
      { { "RayCommon", amrsp_RayCommon_glsl }, { "BrickSample", amrsp_BrickSample_glsl } }, vol);
  if (fragment == this->FailedFragmentSource)
  {
    self->ReportError(
      "the multi-pass AMR shader failed to compile or link (see the earlier error)");
    return nullptr;
  }
  vtkShaderProgram* program = renWin->GetShaderCache()->ReadyShaderProgram(
    amrsp_MultiPassAMR_vert_glsl, fragment.c_str(), "");
  if (!program)
  {
    this->FailedFragmentSource = fragment;
    self->ReportError("the multi-pass AMR shader failed to compile or link (see the error above)");
  }
  return program;
}

//------------------------------------------------------------------------------
bool vtkMultiPassAMRVolumeMapper::vtkInternals::BindCube(vtkShaderProgram* program)
{
  if (this->CubeBuffer->GetHandle() == 0)
  {
    const double lo[3] = { 0.0, 0.0, 0.0 }, hi[3] = { 1.0, 1.0, 1.0 };
    this->CubeBuffer->Upload(
      vtkSinglePassAMRProxyBox::BoxTriangles(lo, hi), vtkOpenGLBufferObject::ArrayBuffer);
    this->CubeArrayProgram = nullptr;
  }
  this->CubeArray->Bind();
  if (this->CubeArrayProgram != program)
  {
    this->CubeArray->ReleaseGraphicsResources();
    this->CubeArray->Bind();
    if (!this->CubeArray->AddAttributeArray(
          program, this->CubeBuffer, "amrspCorner", 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
    {
      this->CubeArray->Release();
      this->Self->ReportError("cannot bind the node box's vertices to the shader");
      return false;
    }
    this->CubeArrayProgram = program;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::SetFrameUniforms(vtkShaderProgram* program,
  vtkVolumeProperty* property, const vtkSinglePassAMRViewGeometry::ViewGeometry& view)
{
  const amrsp::Hierarchy& h = this->Data.Structure;
  const glm::vec3 origin(h.Origin);
  const glm::vec3 spacing(h.Spacing0);
  // the accumulation target holds the viewport only: its pixel (0, 0) is the viewport's corner
  const float viewport[4] = { 0.0f, 0.0f, static_cast<float>(view.Width),
    static_cast<float>(view.Height) };
  float transferRange[2];
  this->Transfer.GetShaderRange(transferRange);
  const glm::vec3 atlasSize(this->Data.Atlas.Pages[0].Dims);

  for (vtkTextureObject* page : this->AtlasPages)
  {
    page->Activate();
  }
  this->Transfer.GetTexture()->Activate();
  program->SetUniformi("amrspAtlas", this->AtlasPages[0]->GetTextureUnit());
  program->SetUniformi("amrspTransfer", this->Transfer.GetTexture()->GetTextureUnit());
  if (this->Self->UseDepthBuffer)
  {
    program->SetUniformi("amrspDepth", this->Depth.Depth->GetTextureUnit());
  }
  program->SetUniformMatrix4x4("amrspMCDCMatrix", const_cast<float*>(view.MCDC));
  program->SetUniformMatrix4x4("amrspDCMCMatrix", const_cast<float*>(view.DCMC));
  program->SetUniform4f("amrspViewport", viewport);
  program->SetUniform4f("amrspEyeMC", view.EyeMC);
  program->SetUniform3f("amrspOrigin", &origin.x);
  program->SetUniform3f("amrspSpacing0", &spacing.x);
  program->SetUniform2f("amrspTransferRange", transferRange);
  program->SetUniformf(
    "amrspTransferSize", static_cast<float>(vtkSinglePassAMRTransferFunctionTable::Size));
  program->SetUniformf("amrspUnitDistance",
    static_cast<float>(std::max(property->GetScalarOpacityUnitDistance(0), 1e-12)));
  program->SetUniform3f("amrspAtlasSize", &atlasSize.x);
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::ClipBox(glm::vec3& clipLo, glm::vec3& clipHi)
{
  const amrsp::Hierarchy& h = this->Data.Structure;
  const amrsp::Box root = h.RootCells();
  std::string cropWarning;
  vtkSinglePassAMRProxyBox::ClipBox(this->Self, h.Origin, h.Spacing0, glm::vec3(root.Lo),
    glm::vec3(root.Hi), clipLo, clipHi, cropWarning);
  if (!cropWarning.empty())
  {
    this->Self->WarnOnce(cropWarning);
  }
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->ReleaseGraphicsResources(window);
  if (!this->Internals->Data.Structure.HasValues())
  {
    // the CPU copy of the atlas was freed after the upload: rebuild from the input next time
    this->InvalidateBuild();
  }
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::GetAtlasDimensions(int dims[3])
{
  const glm::ivec3 d =
    (this->Internals->Data.Atlas.Pages.empty() ? glm::ivec3(0)
                                               : this->Internals->Data.Atlas.Pages[0].Dims);
  dims[0] = d.x;
  dims[1] = d.y;
  dims[2] = d.z;
}

long long vtkMultiPassAMRVolumeMapper::GetTextureBytes()
{
  return this->Internals->TextureBytes;
}

long long vtkMultiPassAMRVolumeMapper::GetAccumulationBytes()
{
  const vtkSinglePassAMROffscreenImage& a = this->Internals->Accumulation;
  return 16LL * a.GetWidth() * a.GetHeight();
}

long long vtkMultiPassAMRVolumeMapper::GetNumberOfKdNodes()
{
  return static_cast<long long>(this->Internals->Data.Tree.Nodes.size());
}

long long vtkMultiPassAMRVolumeMapper::GetNumberOfDataNodes()
{
  return this->Internals->DataNodes;
}

long long vtkMultiPassAMRVolumeMapper::GetLastNumberOfPasses()
{
  return this->Internals->Passes;
}

double vtkMultiPassAMRVolumeMapper::GetLastOrderSeconds()
{
  return this->Internals->OrderSeconds;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& in = *this->Internals;
  os << indent << "KdNodes: " << in.Data.Tree.Nodes.size() << ", DataNodes: " << in.DataNodes
     << ", drawn leaves: " << in.Draws.size() << "\n";
  const glm::ivec3 d = (in.Data.Atlas.Pages.empty() ? glm::ivec3(0) : in.Data.Atlas.Pages[0].Dims);
  os << indent << "AtlasDimensions: " << d.x << " x " << d.y << " x " << d.z << "\n";
  os << indent << "LastNumberOfPasses: " << in.Passes << "\n";
}
