// SPDX-License-Identifier: BSD-3-Clause
// The multi-pass frame's draws: the data nodes in visibility order, the node shaders and their
// uniforms, the unit cube each node is drawn as (vtkMultiPassAMRVolumeMapperInternals.h).
#include "vtkMultiPassAMRVolumeMapperInternals.h"

#include "vtkAMRMapperDepthCopy.h"
#include "vtkAMRMapperPackedAtlas.h"
#include "vtkAMRMapperProxyBox.h"
#include "vtkAMRMapperScopedBlendedDraw.h"
#include "vtkAMRMapperShaderComposer.h"
#include "vtkAMRMapperTransferFunctionTable.h"
#include "vtkAMRMapperViewGeometry.h"
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
#include "vtkAMRMapperOffscreenImage.h"
#include "vtkAMRMapperOpenGL.h"
#include "amrsp_MultiPassAMR_frag_glsl.h"
#include "amrsp_MultiPassAMR_vert_glsl.h"
#include "amrsp_BrickSample_glsl.h"
#include "amrsp_StoragePackedAtlas_glsl.h"
#include "amrsp_RayCommon_glsl.h"
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::OrderNodes(
  const vtkAMRMapperViewGeometry::ViewGeometry& view)
{
  const auto t0 = std::chrono::steady_clock::now();
  this->Order = amrsp::OrderFrontToBack(this->Data.Structure, this->Data.Tree, this->Nodes,
    glm::dvec3(view.Eye[0], view.Eye[1], view.Eye[2]),
    glm::dvec3(view.Direction[0], view.Direction[1], view.Direction[2]), view.Parallel);
  this->OrderSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::DrawNodes(vtkOpenGLState* state,
  vtkShaderProgram* program, const vtkAMRMapperViewGeometry::ViewGeometry& view,
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
  const vtkAMRMapperScopedBlendedDraw blended(
    state, view.Mirrored ? GL_BACK : GL_FRONT, GL_ONE_MINUS_DST_ALPHA, GL_ONE);
  // no near/far clipping: the back faces of a node between the eye and the near plane still
  // reach the shader, which starts the rays at the eye as the single-pass shader does
  // (primitives behind the eye are still clipped, w > 0)
  const bool depthClampWas = glIsEnabled(GL_DEPTH_CLAMP) == GL_TRUE;
  glEnable(GL_DEPTH_CLAMP);

  for (const int32_t d : this->Order)
  {
    const amrsp::NodeDraw& node = this->Nodes.Draws[static_cast<std::size_t>(d)];
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
      glUniform1i(atlas, this->Atlas.GetPage(node.Page)->GetTextureUnit());
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
    vtkAMRMapperShaderComposer::ComposeFragmentShader(amrsp_MultiPassAMR_frag_glsl, defines,
      { { "RayCommon", amrsp_RayCommon_glsl }, { "BrickSample", amrsp_BrickSample_glsl },
        { "GridStorage", amrsp_StoragePackedAtlas_glsl } },
      vol);
  std::string error;
  vtkShaderProgram* program = vtkAMRMapperShaderComposer::ReadyProgram(renWin,
    amrsp_MultiPassAMR_vert_glsl, fragment, "multi-pass AMR", this->FailedFragmentSource, error);
  if (!program)
  {
    self->ReportError(error);
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
      vtkAMRMapperProxyBox::BoxTriangles(lo, hi), vtkOpenGLBufferObject::ArrayBuffer);
    this->CubeArrayProgram = nullptr;
  }
  if (!vtkAMRMapperProxyBox::BindTriangles(
        this->CubeArray, this->CubeBuffer, program, "amrspCorner", this->CubeArrayProgram))
  {
    this->Self->ReportError("cannot bind the node box's vertices to the shader");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::SetFrameUniforms(vtkShaderProgram* program,
  vtkVolumeProperty* property, const vtkAMRMapperViewGeometry::ViewGeometry& view)
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

  this->Atlas.ActivatePages();
  this->Transfer.GetTexture()->Activate();
  program->SetUniformi("amrspAtlas", this->Atlas.GetPage(0)->GetTextureUnit());
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
    "amrspTransferSize", static_cast<float>(vtkAMRMapperTransferFunctionTable::Size));
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
  vtkAMRMapperProxyBox::ClipBox(this->Self, h.Origin, h.Spacing0, glm::vec3(root.Lo),
    glm::vec3(root.Hi), clipLo, clipHi, cropWarning);
  if (!cropWarning.empty())
  {
    this->Self->WarnOnce(cropWarning);
  }
}
