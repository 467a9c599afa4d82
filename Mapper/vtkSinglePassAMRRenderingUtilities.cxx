// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRRenderingUtilities.h"

#include "vtkSinglePassAMRConversion.h"

#include "amrsp/BrickPacking.h"
#include "amrsp/RayCastingData.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkColorTransferFunction.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderProperty.h"
#include "vtkShader.h"
#include "vtkShaderProgram.h"
#include "vtkOpenGLState.h"
#include "vtkOverlappingAMR.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"
#include "vtkSinglePassAMROpenGL.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <exception>
#include <functional>
#include <future>
#include <limits>
#include <sstream>
#include <utility>

namespace vtkSinglePassAMRRenderingUtilities
{

//------------------------------------------------------------------------------
std::string RequestedArray(vtkOverlappingAMR* amr, int accessMode, const char* name, int id)
{
  if (accessMode == VTK_GET_ARRAY_BY_NAME && name && *name)
  {
    return name;
  }
  if (accessMode == VTK_GET_ARRAY_BY_ID && id >= 0)
  {
    const std::vector<std::string> names = vtkSinglePassAMRConversion::CellArrayNames(amr);
    if (static_cast<std::size_t>(id) < names.size())
    {
      return names[static_cast<std::size_t>(id)];
    }
  }
  return std::string();
}

//------------------------------------------------------------------------------
void ToColumnMajor(vtkMatrix4x4* m, float out[16])
{
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out[c * 4 + r] = static_cast<float>(m->GetElement(r, c));
    }
  }
}

//------------------------------------------------------------------------------
void ClipBox(vtkVolumeMapper* mapper, const glm::dvec3& origin, const glm::dvec3& spacing0,
  const glm::vec3& rootLo, const glm::vec3& rootHi, glm::vec3& lo, glm::vec3& hi,
  std::string& warning)
{
  lo = rootLo;
  hi = rootHi;
  if (!mapper->GetCropping())
  {
    return;
  }
  if (mapper->GetCroppingRegionFlags() != VTK_CROP_SUBVOLUME)
  {
    std::ostringstream message;
    message << "cropping region flags 0x" << std::hex << mapper->GetCroppingRegionFlags()
            << " are not supported (only VTK_CROP_SUBVOLUME, the central sub-volume): "
               "cropping is ignored";
    warning = message.str();
    return;
  }
  const double* planes = mapper->GetCroppingRegionPlanes();
  for (int a = 0; a < 3; ++a)
  {
    const double p0 = (std::min(planes[2 * a], planes[2 * a + 1]) - origin[a]) / spacing0[a];
    const double p1 = (std::max(planes[2 * a], planes[2 * a + 1]) - origin[a]) / spacing0[a];
    lo[a] = std::max(rootLo[a], static_cast<float>(p0));
    hi[a] = std::max(lo[a], std::min(rootHi[a], static_cast<float>(p1)));
  }
}

//------------------------------------------------------------------------------
namespace
{
/// A 3D texture of unsigned integers with 2 (RG32UI) or 4 (RGBA32UI) components, nearest
/// filtering; null when the driver refuses it.
vtkSmartPointer<vtkTextureObject> MakeUIntTexture(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, int components, const void* texels)
{
  auto tex = vtkSmartPointer<vtkTextureObject>::New();
  tex->SetContext(renWin);
  tex->SetInternalFormat(components == 4 ? GL_RGBA32UI : GL_RG32UI);
  tex->SetFormat(components == 4 ? GL_RGBA_INTEGER : GL_RG_INTEGER);
  tex->SetDataType(GL_UNSIGNED_INT);
  tex->SetMinificationFilter(vtkTextureObject::Nearest);
  tex->SetMagnificationFilter(vtkTextureObject::Nearest);
  tex->SetWrapS(vtkTextureObject::ClampToEdge);
  tex->SetWrapT(vtkTextureObject::ClampToEdge);
  tex->SetWrapR(vtkTextureObject::ClampToEdge);
  const bool ok =
    tex->Create3DFromRaw(static_cast<unsigned int>(dims.x), static_cast<unsigned int>(dims.y),
      static_cast<unsigned int>(dims.z), components, VTK_UNSIGNED_INT, const_cast<void*>(texels));
  return ok ? tex : nullptr;
}
} // namespace

vtkSmartPointer<vtkTextureObject> MakeIntegerTexture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UIntTexture3D& texels)
{
  return MakeUIntTexture(renWin, texels.Dims, 2, texels.Texels.data());
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTextureObject> MakeInteger4Texture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UInt4Texture3D& texels)
{
  return MakeUIntTexture(renWin, texels.Dims, 4, texels.Texels.data());
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTextureObject> MakeScalarTexture(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, const float* texels, bool vertexCentred)
{
  auto tex = vtkSmartPointer<vtkTextureObject>::New();
  tex->SetContext(renWin);
  tex->SetInternalFormat(GL_R32F);
  tex->SetFormat(GL_RED);
  tex->SetDataType(GL_FLOAT);
  const int filter = vertexCentred ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
  tex->SetMinificationFilter(filter);
  tex->SetMagnificationFilter(filter);
  tex->SetWrapS(vtkTextureObject::ClampToEdge);
  tex->SetWrapT(vtkTextureObject::ClampToEdge);
  tex->SetWrapR(vtkTextureObject::ClampToEdge);
  const bool ok =
    tex->Create3DFromRaw(static_cast<unsigned int>(dims.x), static_cast<unsigned int>(dims.y),
      static_cast<unsigned int>(dims.z), 1, VTK_FLOAT, const_cast<float*>(texels));
  return ok ? tex : nullptr;
}

//------------------------------------------------------------------------------
std::vector<float> BoxTriangles(const double lo[3], const double hi[3])
{
  std::vector<float> vertices;
  vertices.reserve(36 * 3);
  for (int axis = 0; axis < 3; ++axis)
  {
    for (int side = 0; side < 2; ++side)
    {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      double quad[4][3];
      const int corners[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
      for (int c = 0; c < 4; ++c)
      {
        quad[c][axis] = side ? hi[axis] : lo[axis];
        quad[c][u] = corners[c][0] ? hi[u] : lo[u];
        quad[c][v] = corners[c][1] ? hi[v] : lo[v];
      }
      // (u, v, axis) is right-handed: u x v points along +axis, so this order faces +axis
      const int order[2][6] = { { 0, 2, 1, 0, 3, 2 }, { 0, 1, 2, 0, 2, 3 } };
      for (int k : order[side])
      {
        for (int a = 0; a < 3; ++a)
        {
          vertices.push_back(static_cast<float>(quad[k][a]));
        }
      }
    }
  }
  return vertices;
}

//------------------------------------------------------------------------------
ModelLight FirstLightInModel(vtkRenderer* ren, vtkVolume* vol)
{
  ModelLight light;
  vtkNew<vtkMatrix4x4> wcmc; // world -> model
  vtkMatrix4x4::Invert(vol->GetMatrix(), wcmc);
  vtkLightCollection* lights = ren->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* l = lights->GetNextLight(it))
  {
    if (!l->GetSwitch())
    {
      continue;
    }
    double position[4] = { 0.0, 0.0, 0.0, 1.0 }, focal[4] = { 0.0, 0.0, 0.0, 1.0 };
    l->GetTransformedPosition(position);
    l->GetTransformedFocalPoint(focal);
    double positionMC[4], focalMC[4];
    wcmc->MultiplyPoint(position, positionMC);
    wcmc->MultiplyPoint(focal, focalMC);
    double toLight[3];
    for (int a = 0; a < 3; ++a)
    {
      light.Position[a] = static_cast<float>(positionMC[a] / positionMC[3]);
      toLight[a] = positionMC[a] / positionMC[3] - focalMC[a] / focalMC[3];
    }
    if (vtkMath::Normalize(toLight) > 0.0)
    {
      for (int a = 0; a < 3; ++a)
      {
        light.Direction[a] = static_cast<float>(toLight[a]);
      }
    }
    const double* colour = l->GetDiffuseColor();
    for (int a = 0; a < 3; ++a)
    {
      light.Colour[a] = static_cast<float>(colour[a] * l->GetIntensity());
    }
    light.Positional = l->GetPositional() != 0;
    break;
  }
  return light;
}

//------------------------------------------------------------------------------
namespace
{
/// BuildPackedHierarchy on a converted hierarchy, or keeping `out`'s structure when `h` has it
/// and `mayRefresh`.
bool PackHierarchy(amrsp::Hierarchy converted, int packLimit, int64_t maxPageTexels,
  bool mayRefresh, PackedHierarchy& out, bool& refreshed, std::string& error)
{
  refreshed = false;
  try
  {
    if (mayRefresh && !out.Tree.Nodes.empty() && amrsp::SameStructure(out.Structure, converted))
    {
      amrsp::FiniteValueRange(converted, out.ScalarRange); // as the full build below
      out.Structure.Values = std::move(converted.Values);
      refreshed = true;
      return true;
    }
    out = PackedHierarchy();
    out.Structure = std::move(converted);
    const amrsp::Hierarchy& h = out.Structure;
    out.Tree = amrsp::BuildKdTree(h);
    // one brick per grid (cells, or vertices one texel larger), packed within the per-axis limit
    // the data-node offsets can address and MaximumAtlasSize when set
    out.Atlas =
      amrsp::PackBricksInPages(amrsp::BrickExtents(h, h.VertexCentred), amrsp::Packer::Best,
        amrsp::AtlasLimits(packLimit > 0 ? std::min(packLimit, 2048) : 2048), maxPageTexels);
    out.VertexCentred = h.VertexCentred;

    // the level table and the finite range as the single-pass build computes them
    const amrsp::LevelTable levels = amrsp::ComputeLevelTable(h, out.Tree);
    out.LevelMinEdge = levels.LevelMinEdge;
    std::copy(levels.Bounds, levels.Bounds + 6, out.Bounds);
    amrsp::FiniteValueRange(h, out.ScalarRange);
  }
  catch (const std::exception& e)
  {
    error = e.what();
    out = PackedHierarchy();
    return false;
  }
  return true;
}

bool ConvertAndPack(vtkOverlappingAMR* amr, const std::string& array, int component, int packLimit,
  int64_t maxPageTexels, bool mayRefresh, PackedHierarchy& out, bool& refreshed, std::string& error)
{
  refreshed = false;
  amrsp::Hierarchy h;
  try
  {
    vtkSinglePassAMRConversion::ArraySelection selection;
    selection.Name = array;
    selection.Component = component;
    if (!vtkSinglePassAMRConversion::FromOverlappingAMR(amr, selection, h, error))
    {
      out = PackedHierarchy();
      return false;
    }
  }
  catch (const std::exception& e)
  {
    error = e.what();
    out = PackedHierarchy();
    return false;
  }
  return PackHierarchy(std::move(h), packLimit, maxPageTexels, mayRefresh, out, refreshed, error);
}
} // namespace

bool BuildPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, PackedHierarchy& out, std::string& error)
{
  bool refreshed = false;
  return ConvertAndPack(
    amr, array, component, packLimit, maxPageTexels, false, out, refreshed, error);
}

bool RefreshPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, bool mayRefresh, PackedHierarchy& out, bool& refreshed,
  std::string& error)
{
  return ConvertAndPack(
    amr, array, component, packLimit, maxPageTexels, mayRefresh, out, refreshed, error);
}

//------------------------------------------------------------------------------
bool AtlasFitsContext(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, int atlasLimit, std::string& why)
{
  const int max3D = vtkTextureObject::GetMaximumTextureSize3D(renWin);
  const int limit = atlasLimit > 0 ? std::min(atlasLimit, max3D) : max3D;
  if (dims.x <= limit && dims.y <= limit && dims.z <= limit)
  {
    return true;
  }
  std::ostringstream msg;
  msg << "the packed atlas (" << dims.x << " x " << dims.y << " x " << dims.z
      << " texels) exceeds ";
  if (limit < max3D)
  {
    msg << "MaximumAtlasSize = " << limit << " (GL_MAX_3D_TEXTURE_SIZE is " << max3D << ")";
  }
  else
  {
    msg << "GL_MAX_3D_TEXTURE_SIZE = " << max3D << " of this OpenGL context";
  }
  why = msg.str();
  return false;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTextureObject> UploadAtlasBySlabs(vtkOpenGLRenderWindow* renWin,
  const amrsp::Hierarchy& h, const amrsp::AtlasLayout& layout, bool vertexCentred,
  const std::function<void(double)>& progress)
{
  const glm::ivec3 d = layout.Dims;
  vtkSmartPointer<vtkTextureObject> atlas = MakeScalarTexture(renWin, d, nullptr, vertexCentred);
  if (!atlas)
  {
    return nullptr;
  }
  const std::size_t layer = static_cast<std::size_t>(d.x) * static_cast<std::size_t>(d.y);
  const int slab = static_cast<int>(std::max<std::size_t>(
    1, std::min<std::size_t>(d.z, (std::size_t(16) << 20) / (layer * sizeof(float)))));
  const amrsp::AtlasSlabFiller filler(h, layout);
  atlas->Activate(); // bound to a texture unit of its own for the uploads
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  UploadInSlabs(
    d.z, slab, layer, [&filler](int z0, int z1, float* out) { filler.Fill(z0, z1, out); },
    [&d](int z0, int z1, const float* texels)
    { glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z0, d.x, d.y, z1 - z0, GL_RED, GL_FLOAT, texels); },
    progress);
  atlas->Deactivate();
  return atlas;
}

//------------------------------------------------------------------------------
void UploadInSlabs(int units, int slab, std::size_t unitFloats,
  const std::function<void(int, int, float*)>& fill,
  const std::function<void(int, int, const float*)>& upload,
  const std::function<void(double)>& progress)
{
  slab = std::max(1, std::min(slab, units));
  std::vector<float> buffers[2] = { std::vector<float>(unitFloats * static_cast<std::size_t>(slab)),
    std::vector<float>(unitFloats * static_cast<std::size_t>(slab)) };
  const auto fillSlab = [&fill, units, slab](int first, std::vector<float>& texels)
  { fill(first, std::min(units, first + slab), texels.data()); };
  if (units > 0)
  {
    fillSlab(0, buffers[0]);
  }
  for (int first = 0, k = 0; first < units; first += slab, k ^= 1)
  {
    std::future<void> next;
    if (first + slab < units)
    {
      next = std::async(std::launch::async, fillSlab, first + slab, std::ref(buffers[k ^ 1]));
    }
    const int last = std::min(units, first + slab);
    upload(first, last, buffers[k].data());
    if (next.valid())
    {
      next.get(); // rethrows what the fill threw
    }
    if (progress)
    {
      progress(static_cast<double>(last) / units);
    }
  }
}

bool UploadAtlas(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h,
  const amrsp::AtlasLayout& layout, bool vertexCentred, int atlasLimit,
  vtkSmartPointer<vtkTextureObject>& texture, std::string& error,
  const std::function<void(double)>& progress)
{
  texture = nullptr;
  const glm::ivec3 d = layout.Dims;
  if (!AtlasFitsContext(renWin, d, atlasLimit, error))
  {
    return false;
  }
  while (glGetError() != GL_NO_ERROR)
  {
  }
  texture = UploadAtlasBySlabs(renWin, h, layout, vertexCentred, progress);
  const bool ok = texture != nullptr;
  const GLenum glError = glGetError();
  if (!ok || glError != GL_NO_ERROR)
  {
    std::ostringstream msg;
    msg << "uploading the atlas texture ("
        << static_cast<double>(layout.TotalTexels) * sizeof(float) / (1024.0 * 1024.0)
        << " MiB) failed" << (glError == GL_OUT_OF_MEMORY ? ": out of GPU memory" : "")
        << (glError == GL_NO_ERROR ? ": the driver refused the texture allocation (out of GPU "
                                     "memory, or over one of its limits)"
                                   : "")
        << (glError != GL_NO_ERROR ? " (OpenGL error " + std::to_string(glError) + ")" : "");
    error = msg.str();
    texture = nullptr;
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
ScopedBlendedDraw::ScopedBlendedDraw(
  vtkOpenGLState* state, unsigned int cullFace, unsigned int source, unsigned int destination)
  : State(state)
  , Culls(cullFace != GL_NONE)
  , CullSaved(state, GL_CULL_FACE)
  , DepthTestSaved(state, GL_DEPTH_TEST)
  , BlendSaved(state, GL_BLEND)
  , DepthMaskSaved(state)
  , BlendFuncSaved(state)
{
  if (this->Culls)
  {
    state->vtkglEnable(GL_CULL_FACE);
    state->vtkglCullFace(cullFace);
  }
  else
  {
    state->vtkglDisable(GL_CULL_FACE);
  }
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(source, destination, source, destination);
}

//------------------------------------------------------------------------------
ScopedBlendedDraw::~ScopedBlendedDraw()
{
  if (this->Culls)
  {
    this->State->vtkglCullFace(GL_BACK);
  }
}

namespace
{
/// `rgb` (3 per entry) and `alpha` (1 per entry), TransferTableSize entries over [range[0],
/// range[1]]: evenly spaced scalars, or log-spaced ones when `logarithmic`. Without `colour` the
/// grey function gives all three channels.
void Tabulate(vtkColorTransferFunction* colour, vtkPiecewiseFunction* greyFunction,
  vtkPiecewiseFunction* opacity, const double range[2], bool logarithmic, std::vector<float>& rgb,
  std::vector<float>& alpha)
{
  const int n = TransferTableSize;
  if (logarithmic)
  {
    // entry i at 10^(log a + i (log b - log a) / (n - 1)), as vtkColorTransferFunction::GetTable
    // samples a log-scaled function; each function evaluated with its own interpolation
    const double l0 = std::log10(range[0]), l1 = std::log10(range[1]);
    for (int i = 0; i < n; ++i)
    {
      const double x = i == 0 ? range[0]
        : i == n - 1          ? range[1]
                              : std::pow(10.0, l0 + i * (l1 - l0) / (n - 1));
      double c[3];
      if (colour)
      {
        colour->vtkColorTransferFunction::GetTable(x, x, 1, c);
      }
      else
      {
        c[0] = c[1] = c[2] = greyFunction->GetValue(x);
      }
      for (int k = 0; k < 3; ++k)
      {
        rgb[static_cast<std::size_t>(3 * i + k)] = static_cast<float>(c[k]);
      }
      alpha[static_cast<std::size_t>(i)] = static_cast<float>(opacity->GetValue(x));
    }
  }
  else
  {
    if (colour)
    {
      colour->GetTable(range[0], range[1], n, rgb.data());
    }
    else
    {
      greyFunction->GetTable(range[0], range[1], n, rgb.data(), 3);
      for (int i = 0; i < n; ++i)
      {
        rgb[3 * i + 1] = rgb[3 * i + 2] = rgb[3 * i];
      }
    }
    opacity->GetTable(range[0], range[1], n, alpha.data());
  }
}
} // namespace

//------------------------------------------------------------------------------
bool TransferFunctionTable::Update(vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property,
  const double scalarRange[2], const vtkTimeStamp& dataTime)
{
  if (this->Texture && this->Texture->GetContext() == renWin && this->Property == property &&
    this->PropertyMTime == property->GetMTime() && this->Time > dataTime)
  {
    return true;
  }
  const bool grey = property->GetColorChannels(0) == 1;
  vtkColorTransferFunction* colour = grey ? nullptr : property->GetRGBTransferFunction(0);
  vtkPiecewiseFunction* greyFunction = grey ? property->GetGrayTransferFunction(0) : nullptr;
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);

  // tabulate over the union of the functions' ranges; beyond it both clamp to their end points
  double range[2] = { std::numeric_limits<double>::max(), -std::numeric_limits<double>::max() };
  auto extend = [&range](const double* r, int points)
  {
    if (points > 0)
    {
      range[0] = std::min(range[0], r[0]);
      range[1] = std::max(range[1], r[1]);
    }
  };
  if (colour)
  {
    extend(colour->GetRange(), colour->GetSize());
  }
  if (greyFunction)
  {
    extend(greyFunction->GetRange(), greyFunction->GetSize());
  }
  extend(opacity->GetRange(), opacity->GetSize());
  if (!(range[1] > range[0]))
  {
    range[0] = std::min(range[0], scalarRange[0]);
    range[1] = std::max(range[1], scalarRange[1]);
    if (!(range[1] > range[0]))
    {
      range[1] = range[0] + 1.0;
    }
  }

  // log-scaled colours or opacities (docs/paraview.md): the table is indexed by log10 of the
  // scalar, its entries at log-spaced scalars; that needs a positive range
  const bool logRequested = (colour && colour->GetScale() == VTK_CTF_LOG10) ||
    (greyFunction && greyFunction->GetUseLogScale()) || opacity->GetUseLogScale();
  this->Logarithmic = logRequested && range[0] > 0.0;
  this->Warning.clear();
  // a log scale over a range that is not positive: copies of the functions on a linear scale
  // (VTK 9.3 and later tabulate a log-scaled map over such a range as NaN)
  vtkNew<vtkColorTransferFunction> linearColour;
  vtkNew<vtkPiecewiseFunction> linearGrey, linearOpacity;
  if (logRequested && !this->Logarithmic)
  {
    std::ostringstream msg;
    msg << "the log-scaled transfer function spans [" << range[0] << ", " << range[1]
        << "], which is not positive: it is drawn on a linear scale";
    this->Warning = msg.str();
    if (colour)
    {
      linearColour->DeepCopy(colour);
      linearColour->SetScaleToLinear();
      colour = linearColour;
    }
    if (greyFunction)
    {
      linearGrey->DeepCopy(greyFunction);
      linearGrey->SetUseLogScale(false);
      greyFunction = linearGrey;
    }
    linearOpacity->DeepCopy(opacity);
    linearOpacity->SetUseLogScale(false);
    opacity = linearOpacity;
  }

  const int n = TransferTableSize;
  std::vector<float> rgb(static_cast<std::size_t>(3 * n)), alpha(static_cast<std::size_t>(n));
  std::vector<float> rgba(static_cast<std::size_t>(4 * n));
  Tabulate(colour, greyFunction, opacity, range, this->Logarithmic, rgb, alpha);
  for (int i = 0; i < n; ++i)
  {
    rgba[4 * i + 0] = rgb[3 * i + 0];
    rgba[4 * i + 1] = rgb[3 * i + 1];
    rgba[4 * i + 2] = rgb[3 * i + 2];
    rgba[4 * i + 3] = alpha[i];
  }
  if (!this->Texture || this->Texture->GetContext() != renWin)
  {
    this->Texture = vtkSmartPointer<vtkTextureObject>::New();
    this->Texture->SetContext(renWin);
    this->Texture->SetInternalFormat(GL_RGBA32F);
    this->Texture->SetFormat(GL_RGBA);
    this->Texture->SetDataType(GL_FLOAT);
    this->Texture->SetMinificationFilter(vtkTextureObject::Linear);
    this->Texture->SetMagnificationFilter(vtkTextureObject::Linear);
    this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
  }
  if (!this->Texture->Create2DFromRaw(static_cast<unsigned int>(n), 1, 4, VTK_FLOAT, rgba.data()))
  {
    return false;
  }
  this->Range[0] = range[0];
  this->Range[1] = range[1];
  this->Opacity = std::move(alpha);
  this->Property = property;
  this->PropertyMTime = property->GetMTime();
  this->Time.Modified();
  return true;
}

void TransferFunctionTable::GetShaderRange(float range[2]) const
{
  const double lo = this->Logarithmic ? std::log10(this->Range[0]) : this->Range[0];
  const double hi = this->Logarithmic ? std::log10(this->Range[1]) : this->Range[1];
  range[0] = static_cast<float>(lo);
  range[1] = static_cast<float>(1.0 / (hi - lo));
}

float TransferFunctionTable::TableScalar(float scalar) const
{
  if (!this->Logarithmic)
  {
    return scalar;
  }
  // as the shader's amrspTableScalar: at or below 0 before every entry
  return scalar > 0.0f ? std::log10(scalar) : -FLT_MAX;
}

void TransferFunctionTable::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Texture)
  {
    this->Texture->ReleaseGraphicsResources(window);
    this->Texture = nullptr;
  }
  this->Property = nullptr;
}

//------------------------------------------------------------------------------
bool ComputeViewGeometry(vtkRenderer* ren, vtkVolume* vol, ViewGeometry& view, std::string& error)
{
  ren->GetTiledSizeAndOrigin(&view.Width, &view.Height, &view.X0, &view.Y0);
  vtkOpenGLCamera* camera = vtkOpenGLCamera::SafeDownCast(ren->GetActiveCamera());
  if (!camera || view.Width < 1 || view.Height < 1)
  {
    error = "the renderer has no OpenGL camera or an empty viewport";
    return false;
  }
  vtkMatrix4x4* wcvc = nullptr;
  vtkMatrix3x3* normal = nullptr;
  vtkMatrix4x4* vcdc = nullptr;
  vtkMatrix4x4* wcdcGL = nullptr;
  camera->GetKeyMatrices(ren, wcvc, normal, vcdc, wcdcGL);
  vtkNew<vtkMatrix4x4> wcdc; // GetKeyMatrices returns OpenGL (transposed) order
  vtkMatrix4x4::Transpose(wcdcGL, wcdc);
  vtkNew<vtkMatrix4x4> mcdc;
  vtkMatrix4x4::Multiply4x4(wcdc, vol->GetMatrix(), mcdc);
  vtkNew<vtkMatrix4x4> dcmc;
  vtkMatrix4x4::Invert(mcdc, dcmc);
  ToColumnMajor(mcdc, view.MCDC);
  ToColumnMajor(dcmc, view.DCMC);

  view.Parallel = camera->GetParallelProjection() != 0;
  vtkNew<vtkMatrix4x4> wcmc;
  vtkMatrix4x4::Invert(vol->GetMatrix(), wcmc);
  double eyeWC[4] = { 0.0, 0.0, 0.0, 1.0 };
  camera->GetPosition(eyeWC);
  double eyeMC[4];
  wcmc->MultiplyPoint(eyeWC, eyeMC);
  double focalWC[4] = { 0.0, 0.0, 0.0, 1.0 };
  camera->GetFocalPoint(focalWC);
  double focalMC[4];
  wcmc->MultiplyPoint(focalWC, focalMC);
  for (int a = 0; a < 3; ++a)
  {
    view.Eye[a] = eyeMC[a] / eyeMC[3];
    view.Direction[a] = focalMC[a] / focalMC[3] - view.Eye[a];
    view.EyeMC[a] = static_cast<float>(view.Eye[a]);
  }
  view.EyeMC[3] = view.Parallel ? 0.0f : 1.0f;
  view.Mirrored = vol->GetMatrix()->Determinant() < 0.0;
  return true;
}

//------------------------------------------------------------------------------
namespace
{
/// The vtkTextureObject depth format of the bound read framebuffer's depth buffer. A depth blit
/// needs the same format on both sides; a multisampled framebuffer (vtkRenderWindow's default of
/// 8 samples) often has a 24-bit one where a single-sampled one has 32-bit floats.
int ReadFramebufferDepthFormat()
{
  GLint type = GL_NONE, bits = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  while (glGetError() != GL_NO_ERROR)
  {
    // the default framebuffer names its depth differently: keep the float format
    type = GL_FLOAT;
  }
  if (type == GL_FLOAT)
  {
    return vtkTextureObject::Float32;
  }
  return bits <= 16 ? vtkTextureObject::Fixed16
                    : (bits <= 24 ? vtkTextureObject::Fixed24 : vtkTextureObject::Fixed32);
}
} // namespace

void DepthCopy::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Framebuffer)
  {
    this->Framebuffer->ReleaseGraphicsResources(window);
  }
  for (vtkTextureObject* t : { this->Depth.Get(), this->Colour.Get() })
  {
    if (t)
    {
      t->ReleaseGraphicsResources(window);
    }
  }
  *this = DepthCopy();
}

void CopyDepthBuffer(vtkOpenGLRenderWindow* renWin, const ViewGeometry& view, DepthCopy& copy)
{
  const int format = ReadFramebufferDepthFormat();
  const unsigned int width = static_cast<unsigned int>(view.Width);
  const unsigned int height = static_cast<unsigned int>(view.Height);
  vtkOpenGLState* state = renWin->GetState();
  if (!copy.Depth || copy.Depth->GetContext() != renWin || copy.Depth->GetWidth() != width ||
    copy.Depth->GetHeight() != height || copy.Format != format)
  {
    copy.Format = format;
    copy.Depth = vtkSmartPointer<vtkTextureObject>::New();
    copy.Depth->SetContext(renWin);
    copy.Depth->SetMinificationFilter(vtkTextureObject::Nearest);
    copy.Depth->SetMagnificationFilter(vtkTextureObject::Nearest);
    copy.Depth->SetWrapS(vtkTextureObject::ClampToEdge);
    copy.Depth->SetWrapT(vtkTextureObject::ClampToEdge);
    copy.Depth->AllocateDepth(width, height, format);
    copy.Colour = vtkSmartPointer<vtkTextureObject>::New();
    copy.Colour->SetContext(renWin);
    copy.Colour->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR);
    copy.Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    copy.Framebuffer->SetContext(renWin);
    state->PushDrawFramebufferBinding();
    copy.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
    copy.Framebuffer->AddDepthAttachment(copy.Depth);
    copy.Framebuffer->AddColorAttachment(0U, copy.Colour);
    state->PopDrawFramebufferBinding();
  }
  state->PushDrawFramebufferBinding();
  copy.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  state->vtkglBlitFramebuffer(view.X0, view.Y0, view.X0 + view.Width, view.Y0 + view.Height, 0, 0,
    view.Width, view.Height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  state->PopDrawFramebufferBinding();
  copy.Depth->Activate();
}

//------------------------------------------------------------------------------
std::string ComposeFragmentShader(const char* source, const std::string& defines,
  const std::vector<std::pair<std::string, const char*>>& pieces, vtkVolume* vol)
{
  vtkOpenGLShaderProperty* shaderProperty =
    vtkOpenGLShaderProperty::SafeDownCast(vol ? vol->GetShaderProperty() : nullptr);
  auto applyUserReplacements = [&](std::string& code, bool first)
  {
    if (!shaderProperty)
    {
      return;
    }
    for (const auto& r : shaderProperty->GetAllShaderReplacements())
    {
      if (r.first.ShaderType == vtkShader::Fragment && r.first.ReplaceFirst == first)
      {
        vtkShaderProgram::Substitute(
          code, r.first.OriginalValue, r.second.Replacement, r.second.ReplaceAll);
      }
    }
  };
  std::string fragment = source;
  applyUserReplacements(fragment, true);
  vtkShaderProgram::Substitute(fragment, "//AMRSP::Defines", defines);
  for (const auto& piece : pieces)
  {
    vtkShaderProgram::Substitute(fragment, "//AMRSP::" + piece.first, piece.second);
  }
  applyUserReplacements(fragment, false);
  return fragment;
}

//------------------------------------------------------------------------------
bool IsRenderSupported(vtkRenderWindow* window, std::string* why)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  auto fail = [why](const std::string& reason)
  {
    if (why)
    {
      *why = reason;
    }
    return false;
  };
  if (!renWin)
  {
    return fail("the render window is not an OpenGL render window");
  }
  if (!renWin->SupportsOpenGL())
  {
    return fail("the OpenGL context cannot be created or is older than VTK's minimum (3.2 core)");
  }
  renWin->Initialize(); // creates the context if the window has none yet
  renWin->MakeCurrent();
  int major = 0, minor = 0;
  renWin->GetOpenGLVersion(major, minor);
  if (major < 3 || (major == 3 && minor < 2))
  {
    return fail("OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
      " lacks GLSL 1.50 integer textures (3.2 core needed)");
  }
  return true;
}

} // namespace vtkSinglePassAMRRenderingUtilities
