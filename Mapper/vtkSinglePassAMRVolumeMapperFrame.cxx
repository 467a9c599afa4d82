// SPDX-License-Identifier: BSD-3-Clause
// The steps of a frame after the storage is ready: appearance (transfer function, blending,
// shading), the shader variant, the proxy box, empty-space flags, textures and uniforms, and the
// draw of the proxy box's back faces (vtkSinglePassAMRVolumeMapperInternals.h).
#include "vtkSinglePassAMRVolumeMapperInternals.h"

#include "vtkAMRMapperProxyBox.h"
#include "vtkSinglePassAMRRayCasterChoice.h"
#include "vtkSinglePassAMRRayLoopChoice.h"
#include "vtkAMRMapperScopedBlendedDraw.h"
#include "vtkAMRMapperShaderComposer.h"
#include "vtkSinglePassAMRShaderVariant.h"

#include "amrsp/SampleStep.h"

#include "vtkCamera.h"
#include "vtkContourValues.h"
#include "vtkMath.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkAMRMapperOpenGL.h"

// GLSL embedded at build time (vtk_encode_string)
#include "amrsp_BrickSample_glsl.h"
#include "amrsp_KdTreeLayout_glsl.h"
#include "amrsp_RayCommon_glsl.h"
#include "amrsp_RaySteps_glsl.h"
#include "amrsp_Shading_glsl.h"
#include "amrsp_SmoothCells_glsl.h"
#include "amrsp_StorageBindless_glsl.h"
#include "amrsp_StorageLinearBricks_glsl.h"
#include "amrsp_StoragePackedAtlas_glsl.h"
#include "amrsp_SinglePassAMRRay_glsl.h"
#include "amrsp_SinglePassAMR_comp_glsl.h"
#include "amrsp_SinglePassAMR_frag_glsl.h"
#include "amrsp_SinglePassAMR_vert_glsl.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::PrepareAppearance(
  vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property, vtkSinglePassAMRFrameSettings& frame)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  if (!property)
  {
    self->ReportError("the volume has no vtkVolumeProperty");
    return false;
  }
  if (!this->Transfer.Update(renWin, property, this->Data.ScalarRange, self->GetBuildTime()))
  {
    self->ReportError("uploading the transfer-function table failed");
    return false;
  }
  if (!this->Transfer.GetWarning().empty())
  {
    self->WarnOnce(this->Transfer.GetWarning());
  }
  switch (self->GetBlendMode())
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      frame.Blend = amrsp::BlendMode::Composite;
      break;
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      frame.Blend = amrsp::BlendMode::Maximum;
      break;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      frame.Blend = amrsp::BlendMode::Minimum;
      break;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      frame.Blend = amrsp::BlendMode::Average;
      break;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      frame.Blend = amrsp::BlendMode::IsoSurface;
      break;
    default:
      self->ReportError("blend mode " + std::to_string(self->GetBlendMode()) +
        " is not supported (composite, maximum, minimum, average intensity and iso-surface are)");
      return false;
  }
  if (frame.Blend == amrsp::BlendMode::IsoSurface)
  {
    vtkContourValues* values = property->GetIsoSurfaceValues();
    const int count = values ? values->GetNumberOfContours() : 0;
    if (count < 1 || count > 8)
    {
      self->ReportError("iso-surface blending needs 1 to 8 values in "
                        "vtkVolumeProperty::GetIsoSurfaceValues() (it has " +
        std::to_string(count) + ")");
      return false;
    }
    for (int i = 0; i < count; ++i)
    {
      frame.IsoValues.push_back(static_cast<float>(values->GetValue(i)));
    }
    std::sort(frame.IsoValues.begin(), frame.IsoValues.end());
    frame.IsoValues.resize(8, 0.0f);
    frame.IsoCount = count;
  }
  // shading and shadows apply to composite and iso-surface blending only
  const bool lit =
    frame.Blend == amrsp::BlendMode::Composite || frame.Blend == amrsp::BlendMode::IsoSurface;
  frame.Shade = lit && property->GetShade(0) != 0;
  frame.Shadows = lit && self->Shadows;
  frame.SkipEmpty = self->EmptySpaceSkipping && frame.Blend == amrsp::BlendMode::Composite;
  frame.SmoothCells = self->CellInterpolation == SMOOTH_CELL && !this->Data.VertexCentred;
  frame.Ropes = self->Ropes && this->Storage->GetRopes() != nullptr;
  frame.FlatLoop = vtkSinglePassAMRChooseRayLoop(static_cast<amrsp::RayLoop>(self->RayLoop)) ==
    amrsp::RayLoop::Flat;
  frame.UseDepth = self->UseDepthBuffer;
  if (self->OccupancyProbe && !this->Storage->HasThreadBuiltins(renWin))
  {
    self->ReportError("the occupancy probe needs GL_NV_shader_thread_group, which the OpenGL "
                      "context lacks");
    return false;
  }
  const vtkSinglePassAMRRayCasterDecision caster = vtkSinglePassAMRChooseRayCaster(
    static_cast<amrsp::RayCaster>(self->RayCaster), this->Storage->RayCasterFacts(renWin));
  frame.Caster = caster.Caster;
  this->CasterNote = caster.FallbackReason;
  if (!caster.FallbackReason.empty())
  {
    self->WarnOnce(caster.FallbackReason + ": casting the rays with the fragment shader instead");
  }
  return true;
}

//------------------------------------------------------------------------------
vtkSinglePassAMRShaderVariant vtkSinglePassAMRVolumeMapper::vtkInternals::ShaderVariant(
  const vtkSinglePassAMRFrameSettings& frame) const
{
  const vtkSinglePassAMRVolumeMapper* self = this->Self;
  const amrsp::LevelTable& levels = this->Data.Levels;
  vtkSinglePassAMRShaderVariant v;
  v.Caster = frame.Caster;
  this->Storage->DescribeGridData(v);
  v.Waterfall = frame.Access == amrsp::BindlessAccess::Waterfall;
  v.LevelCount = static_cast<int>(this->Data.LevelCellSize.size());
  v.VertexCentred = this->Data.VertexCentred;
  v.LogTransfer = this->Transfer.IsLogarithmic();
  v.UseDepth = frame.UseDepth;
  v.ReducedImage = frame.Reduced();
  v.PowerOfTwoRefinement = !levels.LevelToFinestLog2.empty();
  v.UniformRefinementLog2 = levels.UniformRefinementLog2;
  v.Blend = frame.Blend;
  v.SkipEmpty = frame.SkipEmpty;
  v.SmoothCells = frame.SmoothCells;
  v.Ropes = frame.Ropes;
  v.FlatLoop = frame.FlatLoop;
  v.Ablation = self->DiagnosticAblation;
  v.Shade = frame.Shade;
  v.Shadows = frame.Shadows;
  v.AccelerationCounts = self->AccelerationCountsOutput;
  v.LoopCount = self->LoopCountOutput;
  v.OccupancyProbe = self->OccupancyProbe;
  v.GroupWidth = vtkSinglePassAMRComputeGroup::Width;
  v.GroupHeight = vtkSinglePassAMRComputeGroup::Height;
  return v;
}

//------------------------------------------------------------------------------
vtkShaderProgram* vtkSinglePassAMRVolumeMapper::vtkInternals::ReadyShader(
  vtkOpenGLRenderWindow* renWin, vtkVolume* vol, const vtkSinglePassAMRFrameSettings& frame)
{
  static const vtkSinglePassAMRShaderSources sources{ amrsp_SinglePassAMR_frag_glsl,
    amrsp_SinglePassAMR_comp_glsl, amrsp_SinglePassAMRRay_glsl, amrsp_KdTreeLayout_glsl,
    amrsp_RayCommon_glsl, amrsp_BrickSample_glsl, amrsp_StoragePackedAtlas_glsl,
    amrsp_StorageBindless_glsl, amrsp_StorageLinearBricks_glsl, amrsp_SmoothCells_glsl,
    amrsp_Shading_glsl, amrsp_RaySteps_glsl };
  const bool compute = frame.Caster == amrsp::RayCaster::Compute;
  const std::string source = vtkSinglePassAMRComposeShader(this->ShaderVariant(frame), sources,
    compute ? this->Storage->GetComputeVersion(renWin) : std::string(), vol);
  if (compute)
  {
    return this->ReadyComputeProgram(renWin, source);
  }
  std::string error;
  vtkShaderProgram* program = vtkAMRMapperShaderComposer::ReadyProgram(renWin,
    amrsp_SinglePassAMR_vert_glsl, source, "single-pass AMR", this->FailedFragmentSource, error);
  if (!program)
  {
    this->Self->ReportError(error);
  }
  return program;
}

//------------------------------------------------------------------------------
vtkShaderProgram* vtkSinglePassAMRVolumeMapper::vtkInternals::ReadyComputeProgram(
  vtkOpenGLRenderWindow* renWin, const std::string& source)
{
  if (this->ComputeContext != renWin)
  {
    this->FreeComputePrograms(this->ComputeContext);
    this->ComputeContext = renWin;
  }
  for (auto it = this->ComputePrograms.begin(); it != this->ComputePrograms.end(); ++it)
  {
    if (it->first == source)
    {
      this->ComputePrograms.splice(this->ComputePrograms.begin(), this->ComputePrograms, it);
      it->second->Use(renWin);
      return it->second;
    }
  }
  if (source == this->FailedComputeSource)
  {
    this->Self->ReportError(
      "the single-pass AMR compute shader failed to compile or link (see the earlier error)");
    return nullptr;
  }
  vtkSmartPointer<vtkSinglePassAMRComputeProgram> program =
    vtkSmartPointer<vtkSinglePassAMRComputeProgram>::New();
  std::string error;
  if (!program->Build(renWin, source, error))
  {
    this->FailedComputeSource = source;
    this->Self->ReportError("the single-pass AMR compute shader failed to " + error);
    return nullptr;
  }
  this->ComputePrograms.emplace_front(source, program);
  while (this->ComputePrograms.size() > MaxComputePrograms)
  {
    this->ComputePrograms.back().second->Free(renWin);
    this->ComputePrograms.pop_back();
  }
  program->Use(renWin);
  return program;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::FreeComputePrograms(vtkWindow* window)
{
  for (auto& entry : this->ComputePrograms)
  {
    if (window)
    {
      entry.second->Free(window);
    }
  }
  this->ComputePrograms.clear();
  this->ComputeContext = nullptr;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::DispatchRays(
  vtkShaderProgram* program, const vtkAMRMapperViewGeometry::ViewGeometry& rays, bool reduced)
{
  namespace group = vtkSinglePassAMRComputeGroup;
  vtkAMRMapperOffscreenImage& image = this->RaysImage(reduced);
  const int unit = 0;
  image.BindAsImage(unit);
  program->SetUniformi("amrspRayImage", unit);
  auto* compute = static_cast<vtkSinglePassAMRComputeProgram*>(program);
  compute->Dispatch(
    group::Count(rays.Width, group::Width), group::Count(rays.Height, group::Height));
  compute->Unuse();
  image.UnbindImage(unit);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::BindProxyBox(vtkShaderProgram* program)
{
  const vtkMTimeType buildTime = this->Self->GetBuildTime().GetMTime();
  if (this->BoxBufferTime != buildTime || this->BoxBuffer->GetHandle() == 0)
  {
    const double* b = this->Data.Levels.Bounds;
    const double lo[3] = { b[0], b[2], b[4] };
    const double hi[3] = { b[1], b[3], b[5] };
    this->BoxBuffer->Upload(
      vtkAMRMapperProxyBox::BoxTriangles(lo, hi), vtkOpenGLBufferObject::ArrayBuffer);
    this->BoxBufferTime = buildTime;
    this->BoxArrayProgram = nullptr;
  }
  if (!vtkAMRMapperProxyBox::BindTriangles(
        this->BoxArray, this->BoxBuffer, program, "vertexMC", this->BoxArrayProgram))
  {
    this->Self->ReportError("cannot bind the proxy box's vertices to the shader");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::UpdateEmptySpaceFlags(
  vtkOpenGLRenderWindow* renWin, const vtkSinglePassAMRFrameSettings& frame)
{
  // the flags stay valid while skipping is switched off: switching it on again reuses them
  this->TransparentDataNodes = 0;
  if (!frame.SkipEmpty)
  {
    return true;
  }
  // the node ranges were joined after the upload (PrepareStorage)
  float tableRange[2];
  this->Transfer.GetShaderRange(tableRange);
  const vtkAMRMapperTransferFunctionTable& table = this->Transfer;
  if (!this->Storage->UpdateTransparentFlags(renWin, this->Data.NodeRanges, table.GetOpacityTable(),
        tableRange, table.GetTableTime(), [&table](float s) { return table.TableScalar(s); }))
  {
    this->Self->ReportError("uploading the empty-space skipping flags failed");
    return false;
  }
  this->TransparentDataNodes = this->Storage->GetFlaggedDataNodes();
  return true;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::ActivateTextures(
  vtkShaderProgram* program, const vtkSinglePassAMRFrameSettings& frame)
{
  vtkSinglePassAMRGridStorage& s = *this->Storage;
  s.GetTree()->Activate();
  s.GetDataNodes()->Activate();
  s.ActivateGridData(program);
  this->Transfer.GetTexture()->Activate();
  program->SetUniformi("amrspTree", s.GetTree()->GetTextureUnit());
  program->SetUniformi("amrspDataNodes", s.GetDataNodes()->GetTextureUnit());
  program->SetUniformi("amrspTransfer", this->Transfer.GetTexture()->GetTextureUnit());
  if (frame.SmoothCells)
  {
    s.GetBrickBoxes()->Activate();
    program->SetUniformi("amrspBrickBoxes", s.GetBrickBoxes()->GetTextureUnit());
  }
  if (frame.SkipEmpty)
  {
    s.GetTransparentFlags()->Activate();
    program->SetUniformi("amrspTransparentFlags", s.GetTransparentFlags()->GetTextureUnit());
  }
  if (frame.Ropes)
  {
    s.GetRopes()->Activate();
    program->SetUniformi("amrspRopes", s.GetRopes()->GetTextureUnit());
    program->SetUniform3f("amrspRopeCellSize", &this->Data.RopeCellSize.x);
  }
  if (frame.UseDepth)
  {
    program->SetUniformi("amrspDepth", this->Depth.Depth->GetTextureUnit());
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::SetDataUniforms(vtkShaderProgram* program,
  vtkRenderer* ren, vtkVolumeProperty* property, const vtkAMRMapperViewGeometry::ViewGeometry& view,
  const vtkSinglePassAMRFrameSettings& frame)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  const amrsp::RayCastingData& d = this->Data;
  const amrsp::LevelTable& levels = d.Levels;
  const int levelCount = static_cast<int>(d.LevelCellSize.size());
  std::vector<float> steps;
  for (double edge : levels.LevelMinEdge)
  {
    steps.push_back(static_cast<float>(amrsp::LevelSampleStep(
      self->SampleDistanceFactor * frame.Quality.SampleDistanceScale, edge)));
  }
  const glm::vec3 origin(d.Data.Origin);
  const glm::vec3 spacing(d.Data.Spacing0);
  const float viewport[4] = { static_cast<float>(view.X0), static_cast<float>(view.Y0),
    static_cast<float>(view.Width), static_cast<float>(view.Height) };
  float transferRange[2];
  this->Transfer.GetShaderRange(transferRange);

  program->SetUniformf("amrspOpacityThreshold", static_cast<float>(self->OpacityThreshold));
  program->SetUniformMatrix4x4("amrspMCDCMatrix", const_cast<float*>(view.MCDC));
  program->SetUniformMatrix4x4("amrspDCMCMatrix", const_cast<float*>(view.DCMC));
  program->SetUniform4f("amrspViewport", viewport);
  program->SetUniform4f("amrspEyeMC", view.EyeMC);
  program->SetUniform3f("amrspOrigin", &origin.x);
  program->SetUniform3f("amrspSpacing0", &spacing.x);
  program->SetUniform3f("amrspRootLo", &d.RootLo.x);
  program->SetUniform3f("amrspRootHi", &d.RootHi.x);
  glm::vec3 clipLo, clipHi;
  std::string cropWarning;
  vtkAMRMapperProxyBox::ClipBox(
    self, d.Data.Origin, d.Data.Spacing0, d.RootLo, d.RootHi, clipLo, clipHi, cropWarning);
  if (!cropWarning.empty())
  {
    self->WarnOnce(cropWarning);
  }
  program->SetUniform3f("amrspClipLo", &clipLo.x);
  program->SetUniform3f("amrspClipHi", &clipHi.x);
  program->SetUniform1iv("amrspRootLoFinest", 3, &levels.RootLoFinest.x);
  program->SetUniform1iv("amrspRootHiFinest", 3, &levels.RootHiFinest.x);
  // (with uniform power-of-two refinement the shader computes these from the level)
  if (program->IsUniformUsed("amrspLevelCellSize"))
  {
    program->SetUniform3fv("amrspLevelCellSize", levelCount, &d.LevelCellSize[0].x);
  }
  if (program->IsUniformUsed("amrspLevelToFinest"))
  {
    program->SetUniform1iv("amrspLevelToFinest", 3 * levelCount, levels.LevelToFinest.data());
  }
  if (levels.UniformRefinementLog2 > 0)
  {
    program->SetUniformf("amrspFinestCellSize", d.LevelCellSize.back().x);
  }
  else if (!levels.LevelToFinestLog2.empty())
  {
    program->SetUniform1iv(
      "amrspLevelToFinestLog2", 3 * levelCount, levels.LevelToFinestLog2.data());
  }
  program->SetUniform1fv("amrspLevelStep", levelCount, steps.data());
  const long long guard = 4 * d.KdNodes + 16;
  program->SetUniformi("amrspMaxSegments", static_cast<int>(std::min<long long>(guard, 1 << 30)));
  if (self->DiagnosticAblation == SAMPLING_ONLY)
  {
    program->SetUniformi("amrspAblationSamples", self->DiagnosticAblationSamples);
  }
  program->SetUniform2f("amrspTransferRange", transferRange);
  program->SetUniformf(
    "amrspTransferSize", static_cast<float>(vtkAMRMapperTransferFunctionTable::Size));
  // level of detail: world size of a pixel at distance 1 (perspective) or everywhere (parallel),
  // as amrsp::LevelOfDetail
  vtkCamera* camera = ren->GetActiveCamera();
  const float pixelPerDistance = view.Parallel
    ? 0.0f
    : static_cast<float>(
        2.0 * std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) * 0.5) / view.Height);
  const float parallelPixel =
    view.Parallel ? static_cast<float>(2.0 * camera->GetParallelScale() / view.Height) : 0.0f;
  program->SetUniformf("amrspLodThreshold", static_cast<float>(self->LODThreshold));
  program->SetUniformf("amrspPixelSizePerDistance", pixelPerDistance);
  program->SetUniformf("amrspParallelPixelSize", parallelPixel);
  program->SetUniformf("amrspUnitDistance",
    static_cast<float>(std::max(property->GetScalarOpacityUnitDistance(0), 1e-12)));
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::SetLightingUniforms(vtkShaderProgram* program,
  vtkRenderer* ren, vtkVolume* vol, vtkVolumeProperty* property,
  const vtkSinglePassAMRFrameSettings& frame)
{
  const vtkAMRMapperViewGeometry::ModelLight light =
    vtkAMRMapperViewGeometry::FirstLightInModel(ren, vol);
  const auto setIfUsed = [program](const char* name, auto&& set)
  {
    if (program->IsUniformUsed(name))
    {
      set(name);
    }
  };
  setIfUsed("amrspAmbient",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetAmbient(0))); });
  setIfUsed("amrspDiffuse",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetDiffuse(0))); });
  setIfUsed("amrspSpecular",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetSpecular(0))); });
  setIfUsed("amrspSpecularPower",
    [&](const char* n)
    { program->SetUniformf(n, static_cast<float>(property->GetSpecularPower(0))); });
  setIfUsed("amrspLightPositional",
    [&](const char* n) { program->SetUniformi(n, light.Positional ? 1 : 0); });
  setIfUsed(
    "amrspLightPositionMC", [&](const char* n) { program->SetUniform3f(n, light.Position); });
  setIfUsed(
    "amrspLightDirectionMC", [&](const char* n) { program->SetUniform3f(n, light.Direction); });
  setIfUsed("amrspLightColour", [&](const char* n) { program->SetUniform3f(n, light.Colour); });
  const std::vector<double>& minEdge = this->Data.Levels.LevelMinEdge;
  const double shadowStep = this->Self->ShadowSampleDistance > 0.0
    ? this->Self->ShadowSampleDistance
    : (minEdge.empty() ? 1.0 : minEdge[0]);
  setIfUsed("amrspShadowStep",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(shadowStep)); });
  setIfUsed("amrspIsoCount", [&](const char* n) { program->SetUniformi(n, frame.IsoCount); });
  if (!frame.IsoValues.empty())
  {
    setIfUsed("amrspIsoValues",
      [&](const char* n) { program->SetUniform1fv(n, 8, frame.IsoValues.data()); });
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::DrawBackFaces(
  vtkOpenGLRenderWindow* renWin, const vtkAMRMapperViewGeometry::ViewGeometry& view)
{
  {
    // back faces only (a mirroring volume transform flips the winding), premultiplied "over"
    const vtkAMRMapperScopedBlendedDraw blended(
      renWin->GetState(), view.Mirrored ? GL_BACK : GL_FRONT, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLES, 0, 36);
  }
  this->BoxArray->Release();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::DeactivateTextures(
  const vtkSinglePassAMRFrameSettings& frame)
{
  vtkSinglePassAMRGridStorage& s = *this->Storage;
  s.GetTree()->Deactivate();
  s.GetDataNodes()->Deactivate();
  s.DeactivateGridData();
  this->Transfer.GetTexture()->Deactivate();
  if (frame.SmoothCells)
  {
    s.GetBrickBoxes()->Deactivate();
  }
  if (frame.SkipEmpty)
  {
    s.GetTransparentFlags()->Deactivate();
  }
  if (frame.Ropes)
  {
    s.GetRopes()->Deactivate();
  }
  if (frame.UseDepth)
  {
    this->Depth.Depth->Deactivate();
  }
}
