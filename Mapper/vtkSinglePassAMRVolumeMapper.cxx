// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRVolumeMapper.h"

#include "vtkSinglePassAMRConversion.h"
#include "vtkSinglePassAMRRenderingUtilities.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/BrickAtlas.h"
#include "amrsp/BrickPacking.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkCamera.h"
#include "vtkContourValues.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLShaderProperty.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkOverlappingAMR.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkSinglePassAMROpenGL.h"

// GLSL embedded at build time (vtk_encode_string)
#include "amrsp_KdTreeLayout_glsl.h"
#include "amrsp_RayCommon_glsl.h"
#include "amrsp_SinglePassAMR_frag_glsl.h"
#include "amrsp_SinglePassAMR_vert_glsl.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <cfloat>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace
{


/// Base-2 logarithms of `ratios` (all > 0); empty unless every one is a power of two.
std::vector<int> PowerOfTwoExponents(const std::vector<int>& ratios)
{
  std::vector<int> exponents;
  for (int ratio : ratios)
  {
    int e = 0;
    while ((1 << e) < ratio)
    {
      ++e;
    }
    if ((1 << e) != ratio)
    {
      return {};
    }
    exponents.push_back(e);
  }
  return exponents;
}

/// k > 0 when `toFinestLog2` (3 per level, as LevelToFinestLog2) says every level refines the one
/// above by 2^k on every axis, i.e. level l has k (L - 1 - l) on every axis (one level: k = 1);
/// else 0.
int UniformRefinementExponent(const std::vector<int>& toFinestLog2)
{
  const int levels = static_cast<int>(toFinestLog2.size() / 3);
  if (levels == 0)
  {
    return 0;
  }
  const int k = levels > 1 ? toFinestLog2[0] / (levels - 1) : 1;
  if (k <= 0 || k * (levels - 1) >= 31)
  {
    return 0;
  }
  for (int l = 0; l < levels; ++l)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (toFinestLog2[3 * l + a] != k * (levels - 1 - l))
      {
        return 0;
      }
    }
  }
  return k;
}

double MinEdge(const glm::dvec3& v)
{
  return std::min(v.x, std::min(v.y, v.z));
}

using vtkSinglePassAMRRenderingUtilities::RequestedArray;
using vtkSinglePassAMRRenderingUtilities::TransferTableSize;

} // namespace

//------------------------------------------------------------------------------
class vtkSinglePassAMRVolumeMapper::vtkInternals
{
public:
  // ---- what the textures were built from
  vtkOverlappingAMR* BuiltInput = nullptr; // identity only, never dereferenced
  vtkMTimeType BuiltInputMTime = 0;
  std::string BuiltArray;
  int BuiltComponent = -1;
  bool Built = false;     // a build was attempted for the key above
  bool DataValid = false; // ... and succeeded
  std::string BuildError; // ... or failed with this message
  vtkTimeStamp BuildTime;
  int NumberOfBuilds = 0;
  int IsoCount = 0; // iso-values of the current frame
  double BuildSeconds = 0.0;
  double UploadSeconds = 0.0;

  // ---- CPU results of the build (what the shader needs as uniforms)
  glm::dvec3 Origin{ 0.0 };
  glm::dvec3 Spacing0{ 1.0 };
  glm::vec3 RootLo{ 0.0f };
  glm::vec3 RootHi{ 0.0f };
  int RootLoFinest[3] = { 0, 0, 0 };
  int RootHiFinest[3] = { 0, 0, 0 };
  std::vector<glm::vec3> LevelCellSize;
  std::vector<int> LevelToFinest;   // 3 per level
  // base-2 logarithms of LevelToFinest; empty unless every entry is a power of two
  std::vector<int> LevelToFinestLog2;
  // k > 0 when every level refines the one above by 2^k on every axis (else 0)
  int UniformRefinementLog2 = 0;
  std::vector<double> LevelMinEdge; // smallest model-space edge of a cell of each level
  double Bounds[6] = { 0, -1, 0, -1, 0, -1 };
  double ScalarRange[2] = { 0.0, 1.0 };
  long long KdNodes = 0;
  long long DataNodes = 0;
  long long TextureBytes = 0;
  long long GridCount = 0; // grids of the hierarchy: bricks, and textures of the bindless storage
  glm::ivec3 AtlasDims{ 0 };   // (0,0,0) when the bricks could not be packed
  double AtlasWaste = 0.0;     // unused fraction of the atlas's texels
  std::string PackingError;    // why no atlas could be packed (empty when packed)
  long long PackedBytes = 0;   // tree + data nodes + atlas (0 without an atlas)
  long long BindlessBytes = 0; // tree + data nodes + separate bricks + handles
  bool VertexCentred = false;  // vertex bricks, trilinear sampling; else cells, nearest
  int PackLimit = 0;           // MaximumAtlasSize the atlas was packed for (0 = none)

  // ---- CPU data waiting for upload (freed once uploaded): the converted hierarchy (its values
  // are the bricks), the tree and the two data-node encodings (atlas offsets, in-brick offsets)
  bool PendingUpload = false;
  amrsp::Hierarchy Data;
  amrsp::AtlasLayout Layout;
  amrsp::UIntTexture3D TreeTexels;
  amrsp::UIntTexture3D PackedDataNodeTexels;
  amrsp::UIntTexture3D BindlessDataNodeTexels;
  /// min, max scalar per data node (kept: 8 bytes per node, for the transparent-node count)
  std::vector<glm::vec2> NodeRanges;

  // ---- OpenGL resources of the storage uploaded last (UploadedStorage)
  int UploadedStorage = -1;
  int LastStorage = -1; // what rendered the last frame
  int LastAccess = -1;
  vtkSmartPointer<vtkTextureObject> Tree;
  vtkSmartPointer<vtkTextureObject> DataNodesTexture;
  vtkSmartPointer<vtkTextureObject> Atlas;         // packing
  vtkSmartPointer<vtkTextureObject> HandlesTexture; // bindless: RG32UI, one handle per brick
  std::vector<vtkSmartPointer<vtkTextureObject>> Bricks;
  std::vector<GLuint64> ResidentHandles;
  vtkSinglePassAMRRenderingUtilities::DepthCopy Depth;
  vtkSmartPointer<vtkTextureObject> BrickBoxes; // RG32UI, per brick and axis: grid cells lo, hi
  // empty-space skipping: R8, indexed like the data nodes, 255 where the node's value range is
  // transparent under the transfer table of FlagsTableTime (recomputed when it is re-tabulated)
  vtkSmartPointer<vtkTextureObject> TransparentFlags;
  vtkMTimeType FlagsTableTime = 0;
  long long FlaggedDataNodes = 0;     // data nodes flagged in TransparentFlags
  long long TransparentDataNodes = 0; // ... that the last frame skipped (0 with skipping off)
  vtkNew<vtkOpenGLBufferObject> BoxBuffer;
  vtkNew<vtkOpenGLVertexArrayObject> BoxArray;
  vtkShaderProgram* BoxArrayProgram = nullptr;
  vtkTimeStamp BoxBufferTime;
  vtkTimeStamp UploadTime;
  vtkOpenGLRenderWindow* Context = nullptr;
  int UploadLimit = 0; // MaximumAtlasSize of the last upload attempt
  int BuiltPackLimit = -1;

  // transfer function table
  vtkSinglePassAMRRenderingUtilities::TransferFunctionTable Transfer;

  // shader
  std::string FailedFragmentSource; // do not retry a program that failed to compile
  std::string LastError;
  std::string StorageNote; // why the last frame did not use the bindless storage it was asked for

  // extensions of the context last asked (cached per context)
  vtkOpenGLRenderWindow* CapsContext = nullptr;
  bool HasBindless = false;
  bool HasNVShader5 = false;
  bool HasBallot = false;
  // bindless textures the driver can hold (-1: no known limit). Mesa's zink crashes when more
  // than 1023 handles are made resident (its bindless descriptor array has 1024 slots); checked
  // with Mesa 25.0.7: 1023 grids render, 1024 crash inside glMakeTextureHandleResidentARB.
  long long MaxBindlessTextures = -1;
  std::set<std::string> Warned; // fallback notes already given (each is said once)

  void FreePendingData()
  {
    this->Data = amrsp::Hierarchy();
    this->Layout = amrsp::AtlasLayout();
    this->TreeTexels = amrsp::UIntTexture3D();
    this->PackedDataNodeTexels = amrsp::UIntTexture3D();
    this->BindlessDataNodeTexels = amrsp::UIntTexture3D();
    this->PendingUpload = false;
  }

  void QueryCapabilities(vtkOpenGLRenderWindow* renWin)
  {
    if (this->CapsContext == renWin)
    {
      return;
    }
    renWin->MakeCurrent();
    this->HasBindless = vtkSinglePassAMROpenGL::HasExtension("GL_ARB_bindless_texture");
    this->HasNVShader5 = vtkSinglePassAMROpenGL::HasExtension("GL_NV_gpu_shader5");
    this->HasBallot = vtkSinglePassAMROpenGL::HasExtension("GL_ARB_shader_ballot");
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    this->MaxBindlessTextures =
      renderer && std::string(renderer).find("zink") != std::string::npos ? 1023 : -1;
    this->CapsContext = renWin;
  }

  /// The bindless access mode `requested` resolves to in the queried context, or -1 with `why`.
  int ResolveAccess(int requested, std::string& why) const
  {
    if (!this->HasBindless)
    {
      why = "the OpenGL context lacks GL_ARB_bindless_texture";
      return -1;
    }
    if (requested == vtkSinglePassAMRVolumeMapper::DIRECT_ACCESS ||
      (requested == vtkSinglePassAMRVolumeMapper::AUTO_ACCESS && this->HasNVShader5))
    {
      return vtkSinglePassAMRVolumeMapper::DIRECT_ACCESS;
    }
    if (this->HasBallot)
    {
      return vtkSinglePassAMRVolumeMapper::WATERFALL_ACCESS;
    }
    why = requested == vtkSinglePassAMRVolumeMapper::WATERFALL_ACCESS
      ? "the waterfall access needs GL_ARB_shader_ballot, which the OpenGL context lacks"
      : "non-uniform bindless handles need GL_NV_gpu_shader5 or GL_ARB_shader_ballot, and the "
        "OpenGL context has neither";
    return -1;
  }

  /// Makes every brick handle non-resident and frees the bindless textures (the context of the
  /// upload must be current).
  void ReleaseBindless(vtkWindow* window)
  {
    for (GLuint64 handle : this->ResidentHandles)
    {
      glMakeTextureHandleNonResidentARB(handle);
    }
    this->ResidentHandles.clear();
    for (vtkSmartPointer<vtkTextureObject>& brick : this->Bricks)
    {
      brick->ReleaseGraphicsResources(window);
    }
    this->Bricks.clear();
    if (this->HandlesTexture)
    {
      this->HandlesTexture->ReleaseGraphicsResources(window);
      this->HandlesTexture = nullptr;
    }
  }

  /// CPU side: convert, build the tree, pack, encode, fill the atlas. Returns false with
  /// BuildError set on failure.
  bool Build(vtkOverlappingAMR* amr, const std::string& array, int component);

  /// Builds when the input object, its modification time or the array selection differ from
  /// what the current textures were built from. Returns whether valid data is available.
  bool EnsureBuilt(vtkOverlappingAMR* amr, const std::string& array, int component)
  {
    if (!this->Built || this->BuiltInput != amr || this->BuiltInputMTime != amr->GetMTime() ||
      this->BuiltArray != array || this->BuiltComponent != component ||
      this->BuiltPackLimit != this->PackLimit)
    {
      this->BuiltPackLimit = this->PackLimit;
      this->BuiltInput = amr;
      this->BuiltInputMTime = amr->GetMTime();
      this->BuiltArray = array;
      this->BuiltComponent = component;
      this->Build(amr, array, component);
    }
    return this->DataValid;
  }

  /// Whether the packed atlas fits `renWin` within `atlasLimit` (0 = GL_MAX_3D_TEXTURE_SIZE);
  /// when not, `why` says which limit it exceeds.
  bool AtlasFits(vtkOpenGLRenderWindow* renWin, int atlasLimit, std::string& why) const;

  /// Uploads the tree and the grid data in `storage` (PACKED_ATLAS or BINDLESS_TEXTURES).
  bool Upload(vtkOpenGLRenderWindow* renWin, int storage, std::string& error);
  bool UploadBindless(vtkOpenGLRenderWindow* renWin, std::string& error);
  void ReleaseGraphicsResources(vtkWindow* window);
};

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::Build(vtkOverlappingAMR* amr,
  const std::string& array,
  int component)
{
  const auto t0 = std::chrono::steady_clock::now();
  this->Built = true;
  this->DataValid = false;
  this->BuildError.clear();
  this->FreePendingData();
  ++this->NumberOfBuilds;
  try
  {
    vtkSinglePassAMRConversion::ArraySelection selection;
    selection.Name = array;
    selection.Component = component;
    amrsp::Hierarchy h;
    std::string error;
    if (!vtkSinglePassAMRConversion::FromOverlappingAMR(amr, selection, h, error))
    {
      this->BuildError = error;
      return false;
    }
    const amrsp::KdTree tree = amrsp::BuildKdTree(h);
    this->VertexCentred = h.VertexCentred;
    // bindless: every data node stores the offset of its lower corner inside its own brick
    const std::vector<glm::ivec3> brickStarts(h.Grids.size(), glm::ivec3(0));
    amrsp::EncodedKdTree enc = amrsp::EncodeKdTree(h, tree, &brickStarts);
    this->NodeRanges = amrsp::ComputeDataNodeRanges(h, enc);
    this->BindlessDataNodeTexels = std::move(enc.DataNodes);
    // packing: one brick per grid (cells, or vertices one texel larger), packed within the
    // per-axis limit the data-node offsets can address and MaximumAtlasSize when set; a
    // hierarchy that cannot be packed can still be rendered bindless
    this->PackingError.clear();
    this->Layout = amrsp::AtlasLayout();
    try
    {
      this->Layout = amrsp::PackBricks(amrsp::BrickExtents(h, h.VertexCentred), amrsp::Packer::Best,
        amrsp::AtlasLimits(this->PackLimit > 0 ? std::min(this->PackLimit, 2048) : 2048));
      this->PackedDataNodeTexels =
        amrsp::EncodeKdTree(h, tree, &this->Layout.Origins).DataNodes;
    }
    catch (const std::exception& e)
    {
      this->PackingError = e.what();
      this->Layout = amrsp::AtlasLayout();
      this->PackedDataNodeTexels = amrsp::UIntTexture3D();
    }

    // exact integer bookkeeping of node boxes in finest-level cells (see the shader)
    const glm::i64vec3 finest = h.CumulativeRatio(tree.FinestLevel);
    const amrsp::Box& root = tree.Root().Region;
    const int64_t limit = int64_t(1) << 30;
    for (int a = 0; a < 3; ++a)
    {
      if (root.Lo[a] < -limit || root.Hi[a] > limit)
      {
        this->BuildError = "the root box spans more than 2^30 cells of the finest level; the "
                           "shader's integer node boxes cannot hold it";
        this->FreePendingData();
        return false;
      }
      this->RootLoFinest[a] = static_cast<int>(root.Lo[a]);
      this->RootHiFinest[a] = static_cast<int>(root.Hi[a]);
    }
    this->LevelToFinest.clear();
    this->LevelMinEdge.clear();
    for (int l = 0; l < h.NumberOfLevels(); ++l)
    {
      const glm::i64vec3 r = finest / h.CumulativeRatio(l);
      this->LevelToFinest.push_back(static_cast<int>(r.x));
      this->LevelToFinest.push_back(static_cast<int>(r.y));
      this->LevelToFinest.push_back(static_cast<int>(r.z));
      this->LevelMinEdge.push_back(MinEdge(h.Spacing0 * h.CellSize(l)));
    }
    this->LevelToFinestLog2 = PowerOfTwoExponents(this->LevelToFinest);
    this->UniformRefinementLog2 = UniformRefinementExponent(this->LevelToFinestLog2);
    this->LevelCellSize = enc.LevelCellSize;
    this->RootLo = enc.RootLo;
    this->RootHi = enc.RootHi;
    this->Origin = h.Origin;
    this->Spacing0 = h.Spacing0;
    const glm::dvec3 lo = h.Origin + glm::dvec3(enc.RootLo) * h.Spacing0;
    const glm::dvec3 hi = h.Origin + glm::dvec3(enc.RootHi) * h.Spacing0;
    this->Bounds[0] = lo.x;
    this->Bounds[1] = hi.x;
    this->Bounds[2] = lo.y;
    this->Bounds[3] = hi.y;
    this->Bounds[4] = lo.z;
    this->Bounds[5] = hi.z;
    this->KdNodes = enc.NodeCount;
    this->DataNodes = enc.DataNodeCount;

    this->AtlasDims = this->Layout.Dims;
    this->AtlasWaste = this->Layout.TotalTexels > 0 ? 1.0 - this->Layout.Efficiency : 0.0;
    double vmin = std::numeric_limits<double>::max();
    double vmax = -std::numeric_limits<double>::max();
    for (const amrsp::GridValues& values : h.Values)
    {
      for (float v : values)
      {
        if (std::isfinite(v))
        {
          vmin = std::min(vmin, static_cast<double>(v));
          vmax = std::max(vmax, static_cast<double>(v));
        }
      }
    }
    if (vmin > vmax && !h.Grids.empty())
    {
      this->BuildError = "the array '" + h.ArrayName +
        "' holds no finite value (NaN or +-Inf in every cell): nothing to render";
      this->FreePendingData();
      return false;
    }
    this->ScalarRange[0] = vmin <= vmax ? vmin : 0.0;
    this->ScalarRange[1] = vmin <= vmax ? vmax : 1.0;
    const long long treeBytes =
      static_cast<long long>(amrsp::KdTreeTextureBytes(enc.Tree, this->BindlessDataNodeTexels));
    this->BindlessBytes = treeBytes +
      static_cast<long long>(amrsp::SeparateBrickBytes(h) + amrsp::HandleTextureBytes(h.Grids.size()));
    this->PackedBytes = this->PackingError.empty()
      ? treeBytes + this->Layout.TotalTexels * static_cast<long long>(amrsp::AtlasTexelBytes)
      : 0;
    this->TextureBytes = 0;
    this->GridCount = static_cast<long long>(h.Grids.size());
    this->TreeTexels = std::move(enc.Tree);
    this->Data = std::move(h);
    this->PendingUpload = true;
    this->DataValid = true;
  }
  catch (const std::exception& e)
  {
    this->BuildError = e.what();
    this->FreePendingData();
    return false;
  }
  this->BuildTime.Modified();
  this->BuildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::AtlasFits(vtkOpenGLRenderWindow* renWin,
  int atlasLimit,
  std::string& why) const
{
  if (!this->PackingError.empty())
  {
    why = this->PackingError;
    return false;
  }
  return vtkSinglePassAMRRenderingUtilities::AtlasFitsContext(renWin, this->AtlasDims, atlasLimit, why);
}

//------------------------------------------------------------------------------
namespace
{
/// An RG32UI texture of the kD-tree encoding (nearest, clamped).
vtkSmartPointer<vtkTextureObject> MakeIntegerTexture(vtkOpenGLRenderWindow* renWin,
  const amrsp::UIntTexture3D& texels)
{
  auto tex = vtkSmartPointer<vtkTextureObject>::New();
  tex->SetContext(renWin);
  tex->SetInternalFormat(GL_RG32UI);
  tex->SetFormat(GL_RG_INTEGER);
  tex->SetDataType(GL_UNSIGNED_INT);
  tex->SetMinificationFilter(vtkTextureObject::Nearest);
  tex->SetMagnificationFilter(vtkTextureObject::Nearest);
  tex->SetWrapS(vtkTextureObject::ClampToEdge);
  tex->SetWrapT(vtkTextureObject::ClampToEdge);
  tex->SetWrapR(vtkTextureObject::ClampToEdge);
  const bool ok = tex->Create3DFromRaw(static_cast<unsigned int>(texels.Dims.x),
    static_cast<unsigned int>(texels.Dims.y),
    static_cast<unsigned int>(texels.Dims.z),
    2,
    VTK_UNSIGNED_INT,
    const_cast<glm::uvec2*>(texels.Texels.data()));
  return ok ? tex : nullptr;
}

/// An R32F brick or atlas texture: nearest for cells, trilinear for vertices (the shader never
/// samples outside a brick).
vtkSmartPointer<vtkTextureObject> MakeScalarTexture(vtkOpenGLRenderWindow* renWin,
  const glm::ivec3& dims,
  const float* texels,
  bool vertexCentred)
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
  const bool ok = tex->Create3DFromRaw(static_cast<unsigned int>(dims.x),
    static_cast<unsigned int>(dims.y),
    static_cast<unsigned int>(dims.z),
    1,
    VTK_FLOAT,
    const_cast<float*>(texels));
  return ok ? tex : nullptr;
}
} // namespace

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::Upload(vtkOpenGLRenderWindow* renWin,
  int storage,
  std::string& error)
{
  const auto t0 = std::chrono::steady_clock::now();
  const bool bindless = storage == vtkSinglePassAMRVolumeMapper::BINDLESS_TEXTURES;
  const int max3D = vtkTextureObject::GetMaximumTextureSize3D(renWin);
  for (const amrsp::UIntTexture3D* t : { &this->TreeTexels,
         bindless ? &this->BindlessDataNodeTexels : &this->PackedDataNodeTexels })
  {
    if (t->Dims.x > max3D || t->Dims.y > max3D || t->Dims.z > max3D)
    {
      error = "the kD-tree textures exceed GL_MAX_3D_TEXTURE_SIZE of this OpenGL context";
      return false;
    }
  }
  // the previous storage's textures go first (their handles are made non-resident)
  if (this->Context == renWin)
  {
    this->ReleaseBindless(renWin);
  }
  this->Bricks.clear();
  this->ResidentHandles.clear();
  this->HandlesTexture = nullptr;
  this->Atlas = nullptr;
  this->TransparentFlags = nullptr; // the data nodes may have changed: flagged again per frame
  this->UploadedStorage = -1;
  while (glGetError() != GL_NO_ERROR)
  {
  }

  this->Tree = MakeIntegerTexture(renWin, this->TreeTexels);
  this->DataNodesTexture = MakeIntegerTexture(
    renWin, bindless ? this->BindlessDataNodeTexels : this->PackedDataNodeTexels);
  bool ok = this->Tree && this->DataNodesTexture;
  long long bytes = 0;
  if (ok && bindless)
  {
    ok = this->UploadBindless(renWin, error);
    bytes = this->BindlessBytes;
  }
  else if (ok)
  {
    const amrsp::BrickAtlas atlas = amrsp::FillBrickAtlas(this->Data, this->Layout);
    this->Atlas = MakeScalarTexture(renWin, atlas.Layout.Dims, atlas.Texels.data(),
      this->VertexCentred);
    ok = this->Atlas != nullptr;
    bytes = this->PackedBytes;
  }
  if (ok)
  {
    // grid boxes for the smooth reconstruction: texel 3 g + axis holds grid g's (lo, hi) cells
    // on that axis, signed values bit for bit
    amrsp::UIntTexture3D boxes;
    boxes.Dims = amrsp::TextureDimsFor(3 * this->Data.Grids.size());
    boxes.Texels.assign(
      static_cast<std::size_t>(boxes.Dims.x) * boxes.Dims.y * boxes.Dims.z, glm::uvec2(0u));
    for (std::size_t g = 0; g < this->Data.Grids.size(); ++g)
    {
      const amrsp::Box& box = this->Data.Grids[g].Cells;
      for (int a = 0; a < 3; ++a)
      {
        boxes.Texels[3 * g + a] =
          glm::uvec2(static_cast<uint32_t>(static_cast<int32_t>(box.Lo[a])),
            static_cast<uint32_t>(static_cast<int32_t>(box.Hi[a])));
      }
    }
    this->BrickBoxes = MakeIntegerTexture(renWin, boxes);
    ok = this->BrickBoxes != nullptr;
  }
  const GLenum glError = glGetError();
  if (!ok || glError != GL_NO_ERROR)
  {
    if (error.empty())
    {
      std::ostringstream msg;
      msg << "uploading the kD-tree and " << (bindless ? "brick" : "atlas") << " textures ("
          << bytes / (1024.0 * 1024.0) << " MiB) failed"
          << (glError == GL_OUT_OF_MEMORY ? ": out of GPU memory" : "")
          << (glError == GL_NO_ERROR ? ": the driver refused a texture allocation (out of GPU "
                                       "memory, or over one of its limits)"
                                     : "")
          << (glError != GL_NO_ERROR ? " (OpenGL error " + std::to_string(glError) + ")" : "");
      error = msg.str();
    }
    this->ReleaseBindless(renWin);
    this->Tree = nullptr;
    this->DataNodesTexture = nullptr;
    this->Atlas = nullptr;
    this->BrickBoxes = nullptr;
    return false;
  }
  this->FreePendingData();
  this->TextureBytes = bytes;
  this->UploadedStorage = storage;
  this->Context = renWin;
  this->UploadTime.Modified();
  this->UploadSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::UploadBindless(vtkOpenGLRenderWindow* renWin,
  std::string& error)
{
  const int max3D = vtkTextureObject::GetMaximumTextureSize3D(renWin);
  const std::vector<glm::ivec3> extents = amrsp::BrickExtents(this->Data, this->VertexCentred);
  amrsp::UIntTexture3D handles;
  handles.Dims = amrsp::TextureDimsFor(extents.size());
  handles.Texels.assign(
    static_cast<std::size_t>(handles.Dims.x) * handles.Dims.y * handles.Dims.z, glm::uvec2(0u));
  this->Bricks.reserve(extents.size());
  this->ResidentHandles.reserve(extents.size());
  for (std::size_t g = 0; g < extents.size(); ++g)
  {
    const glm::ivec3 e = extents[g];
    if (e.x > max3D || e.y > max3D || e.z > max3D)
    {
      error = "grid " + std::to_string(g) + " (" + std::to_string(e.x) + " x " +
        std::to_string(e.y) + " x " + std::to_string(e.z) +
        " texels) exceeds GL_MAX_3D_TEXTURE_SIZE = " + std::to_string(max3D);
      return false;
    }
    vtkSmartPointer<vtkTextureObject> brick =
      MakeScalarTexture(renWin, e, this->Data.Values[g].data(), this->VertexCentred);
    if (!brick)
    {
      return false;
    }
    // the handle freezes the texture's sampling state, set above by Create3DFromRaw
    const GLuint64 handle = glGetTextureHandleARB(brick->GetHandle());
    if (handle == 0)
    {
      error = "glGetTextureHandleARB returned no handle for grid " + std::to_string(g);
      return false;
    }
    glMakeTextureHandleResidentARB(handle);
    this->Bricks.push_back(brick);
    this->ResidentHandles.push_back(handle);
    handles.Texels[g] = glm::uvec2(static_cast<uint32_t>(handle & 0xffffffffu),
      static_cast<uint32_t>(handle >> 32));
  }
  this->HandlesTexture = MakeIntegerTexture(renWin, handles);
  return this->HandlesTexture != nullptr;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Context == window)
  {
    this->ReleaseBindless(window);
  }
  this->Bricks.clear();
  this->ResidentHandles.clear();
  this->UploadedStorage = -1;
  for (vtkSmartPointer<vtkTextureObject>* t :
    { &this->Tree, &this->DataNodesTexture, &this->Atlas, &this->HandlesTexture,
      &this->BrickBoxes, &this->TransparentFlags })
  {
    if (*t)
    {
      (*t)->ReleaseGraphicsResources(window);
      *t = nullptr;
    }
  }
  this->Depth.ReleaseGraphicsResources(window);
  this->Transfer.ReleaseGraphicsResources(window);
  this->BoxBuffer->ReleaseGraphicsResources();
  this->BoxArray->ReleaseGraphicsResources();
  this->BoxArrayProgram = nullptr;
  this->Context = nullptr;
  this->CapsContext = nullptr;
  if (!this->PendingUpload)
  {
    // the CPU copies were freed after the upload: rebuild from the input next time
    this->Built = false;
    this->DataValid = false;
  }
}

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkSinglePassAMRVolumeMapper);

//------------------------------------------------------------------------------
vtkSinglePassAMRVolumeMapper::vtkSinglePassAMRVolumeMapper()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkSinglePassAMRVolumeMapper::~vtkSinglePassAMRVolumeMapper()
{
  delete this->Internals;
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeMapper::FillInputPortInformation(int vtkNotUsed(port),
  vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkOverlappingAMR");
  return 1;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::SetInputData(vtkOverlappingAMR* input)
{
  this->SetInputDataInternal(0, input);
}

void vtkSinglePassAMRVolumeMapper::SetInputData(vtkImageData*)
{
  vtkErrorMacro("vtkSinglePassAMRVolumeMapper renders vtkOverlappingAMR only");
}

void vtkSinglePassAMRVolumeMapper::SetInputData(vtkDataSet*)
{
  vtkErrorMacro("vtkSinglePassAMRVolumeMapper renders vtkOverlappingAMR only");
}

void vtkSinglePassAMRVolumeMapper::SetInputData(vtkRectilinearGrid*)
{
  vtkErrorMacro("vtkSinglePassAMRVolumeMapper renders vtkOverlappingAMR only");
}

//------------------------------------------------------------------------------
vtkOverlappingAMR* vtkSinglePassAMRVolumeMapper::GetAMRInput()
{
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return nullptr;
  }
  return vtkOverlappingAMR::SafeDownCast(this->GetInputDataObject(0, 0));
}

//------------------------------------------------------------------------------

//------------------------------------------------------------------------------
double* vtkSinglePassAMRVolumeMapper::GetBounds()
{
  vtkMath::UninitializeBounds(this->Bounds);
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return this->Bounds;
  }
  this->Update();
  vtkOverlappingAMR* amr = this->GetAMRInput();
  // An AMR without metadata or blocks (e.g. the empty placeholder a ParaView view's producer
  // holds until it delivers data) has no bounds; it is not built, so the textures of the last
  // real input stay valid and no build is counted.
  if (!amr || !amr->GetAMRInfo() || amr->GetTotalNumberOfBlocks() == 0)
  {
    return this->Bounds;
  }
  vtkInternals& in = *this->Internals;
  const std::string array =
    RequestedArray(amr, this->ArrayAccessMode, this->ArrayName, this->ArrayId);
  in.PackLimit = this->MaximumAtlasSize;
  if (in.EnsureBuilt(amr, array, this->ArrayComponent))
  {
    std::copy(in.Bounds, in.Bounds + 6, this->Bounds);
    return this->Bounds;
  }
  // the conversion failed (Render reports why): the AMR's own overall bounds
  amr->GetBounds(this->Bounds);
  return this->Bounds;
}

void vtkSinglePassAMRVolumeMapper::GetBounds(double bounds[6])
{
  const double* b = this->GetBounds();
  std::copy(b, b + 6, bounds);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::IsRenderSupported(vtkRenderWindow* window, std::string* why)
{
  return vtkSinglePassAMRRenderingUtilities::IsRenderSupported(window, why);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  // the same error is reported once, not on every frame
  const std::string previousError = in.LastError;
  in.LastError.clear();
  in.LastStorage = -1;
  in.LastAccess = -1;
  in.StorageNote.clear();
  auto fail = [&](const std::string& message)
  {
    if (message != previousError)
    {
      vtkErrorMacro(<< message);
    }
    in.LastError = message;
  };

  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    fail("vtkSinglePassAMRVolumeMapper needs an OpenGL render window");
    return;
  }
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    fail("no input: set a vtkOverlappingAMR with SetInputData or SetInputConnection");
    return;
  }
  this->Update();
  vtkOverlappingAMR* amr = this->GetAMRInput();
  if (!amr)
  {
    fail("the input is not a vtkOverlappingAMR");
    return;
  }

  // ---- data: rebuilt only when the input or the array selection changed
  const std::string array =
    RequestedArray(amr, this->ArrayAccessMode, this->ArrayName, this->ArrayId);
  in.PackLimit = this->MaximumAtlasSize;
  if (!in.EnsureBuilt(amr, array, this->ArrayComponent))
  {
    fail(in.BuildError);
    return;
  }
  // ---- storage: what was asked, what the context offers, what fits
  in.QueryCapabilities(renWin);
  auto warnOnce = [&](const std::string& message)
  {
    if (in.Warned.insert(message).second)
    {
      vtkWarningMacro(<< message);
    }
  };
  std::string noBindless;
  int access = in.ResolveAccess(this->BindlessAccess, noBindless);
  if (access >= 0 && in.MaxBindlessTextures >= 0 && in.GridCount > in.MaxBindlessTextures)
  {
    noBindless = "this driver (Mesa's zink) holds at most " +
      std::to_string(in.MaxBindlessTextures) + " bindless textures and the hierarchy has " +
      std::to_string(in.GridCount) + " grids";
    access = -1;
  }
  std::string noAtlas;
  const bool atlasFits = in.AtlasFits(renWin, this->MaximumAtlasSize, noAtlas);
  int storage = PACKED_ATLAS;
  if (this->DataStorage == BINDLESS_TEXTURES)
  {
    if (access >= 0)
    {
      storage = BINDLESS_TEXTURES;
    }
    else
    {
      in.StorageNote = noBindless;
      warnOnce("bindless textures requested, but " + noBindless +
        ": rendering with the packed atlas instead");
    }
  }
  else if (this->DataStorage == AUTO_STORAGE && access >= 0 &&
    (!atlasFits || in.AtlasWaste > this->AutoBindlessWaste))
  {
    storage = BINDLESS_TEXTURES;
  }
  if (storage == PACKED_ATLAS && !atlasFits)
  {
    fail(noAtlas +
      (this->DataStorage == PACKED_ATLAS ? std::string()
                                         : "; bindless textures cannot be used: " + noBindless));
    return;
  }

  if (in.PendingUpload || in.UploadedStorage != storage || in.Context != renWin ||
    in.UploadLimit != this->MaximumAtlasSize)
  {
    in.UploadLimit = this->MaximumAtlasSize;
    if (!in.PendingUpload)
    {
      // the CPU copies were dropped after an upload of another storage or to another context:
      // rebuild them
      in.Build(amr, array, this->ArrayComponent);
      if (!in.DataValid)
      {
        fail(in.BuildError);
        return;
      }
    }
    std::string error;
    if (!in.Upload(renWin, storage, error))
    {
      // keep the CPU data: a later context (or a smaller input) may succeed
      fail(error);
      return;
    }
  }
  const bool bindless = storage == BINDLESS_TEXTURES;

  vtkVolumeProperty* property = vol->GetProperty();
  if (!property)
  {
    fail("the volume has no vtkVolumeProperty");
    return;
  }
  if (!in.Transfer.Update(renWin, property, in.ScalarRange, in.BuildTime))
  {
    fail("uploading the transfer-function table failed");
    return;
  }

  // ---- blend mode: composite, maximum, minimum and average intensity
  int blend = 0;
  switch (this->GetBlendMode())
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      blend = 0;
      break;
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      blend = 1;
      break;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      blend = 2;
      break;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      blend = 3;
      break;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      blend = 4;
      break;
    default:
      fail("blend mode " + std::to_string(this->GetBlendMode()) +
        " is not supported (composite, maximum, minimum, average intensity and iso-surface are)");
      return;
  }
  std::vector<float> isoValues;
  if (blend == 4)
  {
    vtkContourValues* values = property->GetIsoSurfaceValues();
    const int count = values ? values->GetNumberOfContours() : 0;
    if (count < 1 || count > 8)
    {
      fail("iso-surface blending needs 1 to 8 values in vtkVolumeProperty::GetIsoSurfaceValues() "
           "(it has " + std::to_string(count) + ")");
      return;
    }
    for (int i = 0; i < count; ++i)
    {
      isoValues.push_back(static_cast<float>(values->GetValue(i)));
    }
    std::sort(isoValues.begin(), isoValues.end());
    isoValues.resize(8, 0.0f);
    in.IsoCount = count;
  }
  // shading and shadows apply to composite and iso-surface blending only
  const bool lit = blend == 0 || blend == 4;
  const bool shade = lit && property->GetShade(0) != 0;
  const bool shadows = lit && this->Shadows;

  // ---- shader (one variant per level count and depth use; cached by VTK's shader cache)
  const int levels = static_cast<int>(in.LevelCellSize.size());
  const bool useDepth = this->UseDepthBuffer;
  std::string defines = "#define AMRSP_LEVEL_COUNT " + std::to_string(levels) + "\n" +
    (bindless ? "#define AMRSP_BINDLESS 1\n" : "#define AMRSP_PACKING 1\n") +
    (in.VertexCentred ? "#define AMRSP_VERTEX_CENTRED 1\n" : "#define AMRSP_CELL_CENTRED 1\n");
  if (bindless && access == WATERFALL_ACCESS)
  {
    defines += "#define AMRSP_WATERFALL 1\n";
  }
  if (useDepth)
  {
    defines += "#define AMRSP_USE_DEPTH 1\n";
  }
  const bool powerOfTwoRefinement = !in.LevelToFinestLog2.empty();
  if (powerOfTwoRefinement)
  {
    defines += "#define AMRSP_POWER_OF_TWO_REFINEMENT 1\n";
  }
  if (in.UniformRefinementLog2 > 0)
  {
    defines += "#define AMRSP_UNIFORM_REFINEMENT_LOG2 " + std::to_string(in.UniformRefinementLog2) + "\n";
  }
  defines += "#define AMRSP_BLEND_MODE " + std::to_string(blend) + "\n";
  const bool skipEmpty = this->EmptySpaceSkipping && blend == 0;
  if (skipEmpty)
  {
    defines += "#define AMRSP_SKIP_EMPTY 1\n";
  }
  if (this->CellInterpolation == SMOOTH_CELL && !in.VertexCentred)
  {
    defines += "#define AMRSP_SMOOTH_CELLS 1\n";
  }
  if (shade)
  {
    defines += "#define AMRSP_SHADE 1\n";
  }
  if (shadows)
  {
    defines += "#define AMRSP_SHADOWS 1\n";
  }
  if (this->WorkCountersOutput)
  {
    defines += "#define AMRSP_WORK_COUNTERS 1\n";
  }
  // the volume's vtkShaderProperty fragment replacements, as VTK's own mappers apply them: those
  // marked "replace first" before the mapper's substitutions, the others after
  vtkOpenGLShaderProperty* shaderProperty =
    vtkOpenGLShaderProperty::SafeDownCast(vol->GetShaderProperty());
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
  std::string fragment = amrsp_SinglePassAMR_frag_glsl;
  applyUserReplacements(fragment, true);
  vtkShaderProgram::Substitute(fragment, "//AMRSP::Defines", defines);
  vtkShaderProgram::Substitute(fragment, "//AMRSP::KdTreeLayout", amrsp_KdTreeLayout_glsl);
  vtkShaderProgram::Substitute(fragment, "//AMRSP::RayCommon", amrsp_RayCommon_glsl);
  applyUserReplacements(fragment, false);
  if (fragment == in.FailedFragmentSource)
  {
    fail("the single-pass AMR shader failed to compile or link (see the earlier error)");
    return;
  }
  vtkShaderProgram* program = renWin->GetShaderCache()->ReadyShaderProgram(
    amrsp_SinglePassAMR_vert_glsl, fragment.c_str(), "");
  if (!program)
  {
    in.FailedFragmentSource = fragment;
    fail("the single-pass AMR shader failed to compile or link (see the error above)");
    return;
  }

  // ---- the view: viewport, model <-> normalized device matrices and the rays' origin
  vtkSinglePassAMRRenderingUtilities::ViewGeometry view;
  std::string viewError;
  if (!vtkSinglePassAMRRenderingUtilities::ComputeViewGeometry(ren, vol, view, viewError))
  {
    fail(viewError);
    return;
  }
  vtkCamera* camera = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> wcmc; // world -> model, for the light
  vtkMatrix4x4::Invert(vol->GetMatrix(), wcmc);

  // ---- proxy geometry: the root box's faces, wound counter-clockwise seen from outside
  if (in.BoxBufferTime < in.BuildTime || in.BoxBuffer->GetHandle() == 0)
  {
    const double* b = in.Bounds;
    std::vector<float> vertices;
    for (int axis = 0; axis < 3; ++axis)
    {
      for (int side = 0; side < 2; ++side)
      {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        double quad[4][3];
        const int corners[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
        for (int c = 0; c < 4; ++c)
        {
          quad[c][axis] = b[2 * axis + side];
          quad[c][u] = b[2 * u + corners[c][0]];
          quad[c][v] = b[2 * v + corners[c][1]];
        }
        // (u, v, axis) is right-handed: u x v points along +axis, so this order faces +axis
        const int order[2][6] = { { 0, 2, 1, 0, 3, 2 }, { 0, 1, 2, 0, 2, 3 } };
        for (int k : order[side])
        {
          vertices.push_back(static_cast<float>(quad[k][0]));
          vertices.push_back(static_cast<float>(quad[k][1]));
          vertices.push_back(static_cast<float>(quad[k][2]));
        }
      }
    }
    in.BoxBuffer->Upload(vertices, vtkOpenGLBufferObject::ArrayBuffer);
    in.BoxBufferTime.Modified();
    in.BoxArrayProgram = nullptr;
  }
  in.BoxArray->Bind();
  if (in.BoxArrayProgram != program)
  {
    in.BoxArray->ReleaseGraphicsResources();
    in.BoxArray->Bind();
    if (!in.BoxArray->AddAttributeArray(
          program, in.BoxBuffer, "vertexMC", 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
    {
      in.BoxArray->Release();
      fail("cannot bind the proxy box's vertices to the shader");
      return;
    }
    in.BoxArrayProgram = program;
  }

  vtkOpenGLState* state = renWin->GetState();

  // ---- depth of the opaque geometry drawn so far
  if (useDepth)
  {
    vtkSinglePassAMRRenderingUtilities::CopyDepthBuffer(renWin, view, in.Depth);
  }

  // ---- empty-space skipping: one flag per data node, whether its value range is transparent
  // under the tabulated transfer function (amrsp::TableRangeTransparent on the table the shader
  // samples); recomputed when the table is re-tabulated (the node ranges never change with it)
  if (skipEmpty &&
    (!in.TransparentFlags || in.TransparentFlags->GetContext() != renWin ||
      in.FlagsTableTime != in.Transfer.GetTableTime()))
  {
    const std::vector<float> prefix = amrsp::OpacityPrefixCounts(in.Transfer.GetOpacityTable());
    float tableRange[2];
    in.Transfer.GetShaderRange(tableRange);
    // texel k at the data node's own texel; texel 0 and padding texels are never read
    const glm::ivec3 dims = amrsp::TextureDimsFor(in.NodeRanges.size());
    std::vector<unsigned char> flags(static_cast<std::size_t>(dims.x) * dims.y * dims.z, 0);
    in.FlaggedDataNodes = 0;
    for (std::size_t k = 1; k < in.NodeRanges.size(); ++k)
    {
      if (amrsp::TableRangeTransparent(
            prefix, tableRange, in.NodeRanges[k].x, in.NodeRanges[k].y))
      {
        flags[k] = 255;
        ++in.FlaggedDataNodes;
      }
    }
    // R8 rows need no unpack padding: a texture row is 256 texels, or the only row
    in.TransparentFlags = vtkSmartPointer<vtkTextureObject>::New();
    in.TransparentFlags->SetContext(renWin);
    in.TransparentFlags->SetInternalFormat(GL_R8);
    in.TransparentFlags->SetFormat(GL_RED);
    in.TransparentFlags->SetDataType(GL_UNSIGNED_BYTE);
    in.TransparentFlags->SetMinificationFilter(vtkTextureObject::Nearest);
    in.TransparentFlags->SetMagnificationFilter(vtkTextureObject::Nearest);
    if (!in.TransparentFlags->Create3DFromRaw(static_cast<unsigned int>(dims.x),
          static_cast<unsigned int>(dims.y), static_cast<unsigned int>(dims.z), 1,
          VTK_UNSIGNED_CHAR, flags.data()))
    {
      in.TransparentFlags = nullptr;
      fail("uploading the empty-space skipping flags failed");
      return;
    }
    in.FlagsTableTime = in.Transfer.GetTableTime();
  }
  // the flags stay valid while skipping is switched off: switching it on again reuses them
  in.TransparentDataNodes = skipEmpty ? in.FlaggedDataNodes : 0;

  // ---- uniforms
  const std::vector<glm::vec3>& cells = in.LevelCellSize;
  std::vector<float> steps;
  for (double edge : in.LevelMinEdge)
  {
    steps.push_back(static_cast<float>(this->SampleDistanceFactor * edge));
  }
  const float origin[3] = { static_cast<float>(in.Origin.x),
    static_cast<float>(in.Origin.y),
    static_cast<float>(in.Origin.z) };
  const float spacing[3] = { static_cast<float>(in.Spacing0.x),
    static_cast<float>(in.Spacing0.y),
    static_cast<float>(in.Spacing0.z) };
  const float viewport[4] = { static_cast<float>(view.X0),
    static_cast<float>(view.Y0),
    static_cast<float>(view.Width),
    static_cast<float>(view.Height) };
  float transferRange[2];
  in.Transfer.GetShaderRange(transferRange);

  vtkTextureObject* gridData = bindless ? in.HandlesTexture.Get() : in.Atlas.Get();
  in.Tree->Activate();
  in.DataNodesTexture->Activate();
  gridData->Activate();
  in.Transfer.GetTexture()->Activate();
  program->SetUniformi("amrspTree", in.Tree->GetTextureUnit());
  program->SetUniformi("amrspDataNodes", in.DataNodesTexture->GetTextureUnit());
  program->SetUniformi(bindless ? "amrspHandles" : "amrspAtlas", gridData->GetTextureUnit());
  program->SetUniformi("amrspTransfer", in.Transfer.GetTexture()->GetTextureUnit());
  program->SetUniformf("amrspOpacityThreshold", static_cast<float>(this->OpacityThreshold));
  const bool smoothCells = this->CellInterpolation == SMOOTH_CELL && !in.VertexCentred;
  if (smoothCells)
  {
    in.BrickBoxes->Activate();
    program->SetUniformi("amrspBrickBoxes", in.BrickBoxes->GetTextureUnit());
  }
  if (skipEmpty)
  {
    in.TransparentFlags->Activate();
    program->SetUniformi("amrspTransparentFlags", in.TransparentFlags->GetTextureUnit());
  }
  if (useDepth)
  {
    program->SetUniformi("amrspDepth", in.Depth.Depth->GetTextureUnit());
  }
  program->SetUniformMatrix4x4("amrspMCDCMatrix", view.MCDC);
  program->SetUniformMatrix4x4("amrspDCMCMatrix", view.DCMC);
  program->SetUniform4f("amrspViewport", viewport);
  program->SetUniform4f("amrspEyeMC", view.EyeMC);
  program->SetUniform3f("amrspOrigin", origin);
  program->SetUniform3f("amrspSpacing0", spacing);
  program->SetUniform3f("amrspRootLo", &in.RootLo.x);
  program->SetUniform3f("amrspRootHi", &in.RootHi.x);
  glm::vec3 clipLo, clipHi;
  std::string cropWarning;
  vtkSinglePassAMRRenderingUtilities::ClipBox(
    this, in.Origin, in.Spacing0, in.RootLo, in.RootHi, clipLo, clipHi, cropWarning);
  if (!cropWarning.empty())
  {
    warnOnce(cropWarning);
  }
  program->SetUniform3f("amrspClipLo", &clipLo.x);
  program->SetUniform3f("amrspClipHi", &clipHi.x);
  program->SetUniform1iv("amrspRootLoFinest", 3, in.RootLoFinest);
  program->SetUniform1iv("amrspRootHiFinest", 3, in.RootHiFinest);
  // (with uniform power-of-two refinement the shader computes these from the level)
  if (program->IsUniformUsed("amrspLevelCellSize"))
  {
    program->SetUniform3fv("amrspLevelCellSize", levels, &cells[0].x);
  }
  if (program->IsUniformUsed("amrspLevelToFinest"))
  {
    program->SetUniform1iv("amrspLevelToFinest", 3 * levels, in.LevelToFinest.data());
  }
  if (in.UniformRefinementLog2 > 0)
  {
    program->SetUniformf("amrspFinestCellSize", cells.back().x);
  }
  else if (powerOfTwoRefinement)
  {
    program->SetUniform1iv("amrspLevelToFinestLog2", 3 * levels, in.LevelToFinestLog2.data());
  }
  program->SetUniform1fv("amrspLevelStep", levels, steps.data());
  const long long guard = 4 * in.KdNodes + 16;
  program->SetUniformi("amrspMaxSegments", static_cast<int>(std::min<long long>(guard, 1 << 30)));
  program->SetUniform2f("amrspTransferRange", transferRange);
  program->SetUniformf("amrspTransferSize", static_cast<float>(TransferTableSize));
  const float atlasSize[3] = { static_cast<float>(in.AtlasDims.x),
    static_cast<float>(in.AtlasDims.y), static_cast<float>(in.AtlasDims.z) };
  if (!bindless)
  {
    program->SetUniform3f("amrspAtlasSize", atlasSize);
  }
  // level of detail: world size of a pixel at distance 1 (perspective) or everywhere (parallel),
  // as amrsp::LevelOfDetail
  const float pixelPerDistance = view.Parallel ? 0.0f
    : static_cast<float>(2.0 * std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) * 0.5) /
        view.Height);
  const float parallelPixel =
    view.Parallel ? static_cast<float>(2.0 * camera->GetParallelScale() / view.Height) : 0.0f;
  program->SetUniformf("amrspLodThreshold", static_cast<float>(this->LODThreshold));
  program->SetUniformf("amrspPixelSizePerDistance", pixelPerDistance);
  program->SetUniformf("amrspParallelPixelSize", parallelPixel);
  program->SetUniformf("amrspUnitDistance",
    static_cast<float>(std::max(property->GetScalarOpacityUnitDistance(0), 1e-12)));
  if (shade || shadows || blend == 4)
  {
    // the first switched-on light, in model coordinates (none: ambient only)
    float lightPosition[3] = { 0.0f, 0.0f, 0.0f };
    float lightDirection[3] = { 0.0f, 0.0f, 1.0f };
    float lightColour[3] = { 0.0f, 0.0f, 0.0f };
    int positional = 0;
    vtkLightCollection* lights = ren->GetLights();
    vtkCollectionSimpleIterator it;
    lights->InitTraversal(it);
    while (vtkLight* light = lights->GetNextLight(it))
    {
      if (!light->GetSwitch())
      {
        continue;
      }
      double position[4] = { 0.0, 0.0, 0.0, 1.0 }, focal[4] = { 0.0, 0.0, 0.0, 1.0 };
      light->GetTransformedPosition(position);
      light->GetTransformedFocalPoint(focal);
      double positionMC[4], focalMC[4];
      wcmc->MultiplyPoint(position, positionMC);
      wcmc->MultiplyPoint(focal, focalMC);
      double toLight[3];
      for (int a = 0; a < 3; ++a)
      {
        lightPosition[a] = static_cast<float>(positionMC[a] / positionMC[3]);
        toLight[a] = positionMC[a] / positionMC[3] - focalMC[a] / focalMC[3];
      }
      if (vtkMath::Normalize(toLight) > 0.0)
      {
        for (int a = 0; a < 3; ++a)
        {
          lightDirection[a] = static_cast<float>(toLight[a]);
        }
      }
      const double* colour = light->GetDiffuseColor();
      for (int a = 0; a < 3; ++a)
      {
        lightColour[a] = static_cast<float>(colour[a] * light->GetIntensity());
      }
      positional = light->GetPositional() ? 1 : 0;
      break;
    }
    const auto setIfUsed = [&](const char* name, auto&& set) {
      if (program->IsUniformUsed(name))
      {
        set(name);
      }
    };
    setIfUsed("amrspAmbient",
      [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetAmbient(0))); });
    setIfUsed("amrspDiffuse",
      [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetDiffuse(0))); });
    setIfUsed("amrspSpecular", [&](const char* n)
      { program->SetUniformf(n, static_cast<float>(property->GetSpecular(0))); });
    setIfUsed("amrspSpecularPower", [&](const char* n)
      { program->SetUniformf(n, static_cast<float>(property->GetSpecularPower(0))); });
    setIfUsed("amrspLightPositional", [&](const char* n) { program->SetUniformi(n, positional); });
    setIfUsed("amrspLightPositionMC", [&](const char* n) { program->SetUniform3f(n, lightPosition); });
    setIfUsed("amrspLightDirectionMC",
      [&](const char* n) { program->SetUniform3f(n, lightDirection); });
    setIfUsed("amrspLightColour", [&](const char* n) { program->SetUniform3f(n, lightColour); });
    const double shadowStep = this->ShadowSampleDistance > 0.0
      ? this->ShadowSampleDistance
      : (in.LevelMinEdge.empty() ? 1.0 : in.LevelMinEdge[0]);
    setIfUsed("amrspShadowStep",
      [&](const char* n) { program->SetUniformf(n, static_cast<float>(shadowStep)); });
    setIfUsed("amrspIsoCount", [&](const char* n) { program->SetUniformi(n, in.IsoCount); });
    if (!isoValues.empty())
    {
      setIfUsed("amrspIsoValues",
        [&](const char* n) { program->SetUniform1fv(n, 8, isoValues.data()); });
    }
  }

  // ---- draw the back faces once per pixel, blending premultiplied colour front to back
  {
    vtkOpenGLState::ScopedglEnableDisable cullSaved(state, GL_CULL_FACE);
    vtkOpenGLState::ScopedglEnableDisable depthSaved(state, GL_DEPTH_TEST);
    vtkOpenGLState::ScopedglEnableDisable blendSaved(state, GL_BLEND);
    vtkOpenGLState::ScopedglDepthMask depthMaskSaved(state);
    vtkOpenGLState::ScopedglBlendFuncSeparate blendFuncSaved(state);
    state->vtkglEnable(GL_CULL_FACE);
    // a mirroring volume transform flips the winding
    state->vtkglCullFace(view.Mirrored ? GL_BACK : GL_FRONT);
    state->vtkglDisable(GL_DEPTH_TEST);
    state->vtkglDepthMask(GL_FALSE);
    state->vtkglEnable(GL_BLEND);
    state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLES, 0, 36);
    state->vtkglCullFace(GL_BACK);
  }
  in.BoxArray->Release();

  in.Tree->Deactivate();
  in.DataNodesTexture->Deactivate();
  gridData->Deactivate();
  in.Transfer.GetTexture()->Deactivate();
  if (smoothCells)
  {
    in.BrickBoxes->Deactivate();
  }
  if (skipEmpty)
  {
    in.TransparentFlags->Deactivate();
  }
  if (useDepth)
  {
    in.Depth.Depth->Deactivate();
  }
  in.LastStorage = storage;
  in.LastAccess = bindless ? access : -1;
  vtkOpenGLCheckErrorMacro("failed after vtkSinglePassAMRVolumeMapper::Render");
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->ReleaseGraphicsResources(window);
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRVolumeMapper::GetLastError()
{
  return this->Internals->LastError.c_str();
}

double vtkSinglePassAMRVolumeMapper::GetLastBuildSeconds()
{
  return this->Internals->BuildSeconds;
}

double vtkSinglePassAMRVolumeMapper::GetLastUploadSeconds()
{
  return this->Internals->UploadSeconds;
}

int vtkSinglePassAMRVolumeMapper::GetNumberOfBuilds()
{
  return this->Internals->NumberOfBuilds;
}

void vtkSinglePassAMRVolumeMapper::GetAtlasDimensions(int dims[3])
{
  dims[0] = this->Internals->AtlasDims.x;
  dims[1] = this->Internals->AtlasDims.y;
  dims[2] = this->Internals->AtlasDims.z;
}

long long vtkSinglePassAMRVolumeMapper::GetTextureBytes()
{
  return this->Internals->TextureBytes;
}

long long vtkSinglePassAMRVolumeMapper::GetPackedTextureBytes()
{
  return this->Internals->PackedBytes;
}

long long vtkSinglePassAMRVolumeMapper::GetBindlessTextureBytes()
{
  return this->Internals->BindlessBytes;
}

double vtkSinglePassAMRVolumeMapper::GetAtlasWaste()
{
  return this->Internals->AtlasWaste;
}

int vtkSinglePassAMRVolumeMapper::GetLastDataStorage()
{
  return this->Internals->LastStorage;
}

const char* vtkSinglePassAMRVolumeMapper::GetBindlessFallbackReason()
{
  return this->Internals->StorageNote.c_str();
}

int vtkSinglePassAMRVolumeMapper::GetLastBindlessAccess()
{
  return this->Internals->LastAccess;
}

const char* vtkSinglePassAMRVolumeMapper::GetDataStorageName(int storage)
{
  switch (storage)
  {
    case PACKED_ATLAS:
      return "packing";
    case BINDLESS_TEXTURES:
      return "bindless";
    case AUTO_STORAGE:
      return "auto";
    default:
      return "none";
  }
}

const char* vtkSinglePassAMRVolumeMapper::GetBindlessAccessName(int access)
{
  switch (access)
  {
    case DIRECT_ACCESS:
      return "direct";
    case WATERFALL_ACCESS:
      return "waterfall";
    case AUTO_ACCESS:
      return "auto";
    default:
      return "none";
  }
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::IsBindlessSupported(vtkRenderWindow* window, std::string* why)
{
  std::string reason;
  if (!IsRenderSupported(window, &reason))
  {
    if (why)
    {
      *why = reason;
    }
    return false;
  }
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  vtkInternals caps;
  caps.QueryCapabilities(renWin);
  if (caps.ResolveAccess(AUTO_ACCESS, reason) < 0)
  {
    if (why)
    {
      *why = reason;
    }
    return false;
  }
  return true;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfKdNodes()
{
  return this->Internals->KdNodes;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfDataNodes()
{
  return this->Internals->DataNodes;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfTransparentDataNodes()
{
  return this->Internals->TransparentDataNodes;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& in = *this->Internals;
  os << indent << "ArrayComponent: " << this->ArrayComponent << "\n";
  os << indent << "SampleDistanceFactor: " << this->SampleDistanceFactor << "\n";
  os << indent << "MaximumAtlasSize: " << this->MaximumAtlasSize << "\n";
  os << indent << "LODThreshold: " << this->LODThreshold << "\n";
  os << indent << "UseDepthBuffer: " << (this->UseDepthBuffer ? "on" : "off") << "\n";
  os << indent << "DataStorage: " << GetDataStorageName(this->DataStorage) << "\n";
  os << indent << "BindlessAccess: " << GetBindlessAccessName(this->BindlessAccess) << "\n";
  os << indent << "AutoBindlessWaste: " << this->AutoBindlessWaste << "\n";
  os << indent << "LastDataStorage: " << GetDataStorageName(in.LastStorage)
     << ", LastBindlessAccess: " << GetBindlessAccessName(in.LastAccess) << "\n";
  os << indent << "OpacityThreshold: " << this->OpacityThreshold << "\n";
  os << indent << "EmptySpaceSkipping: " << (this->EmptySpaceSkipping ? "on" : "off") << "\n";
  os << indent << "WorkCountersOutput: " << (this->WorkCountersOutput ? "on" : "off") << "\n";
  os << indent << "CellInterpolation: "
     << (this->CellInterpolation == SMOOTH_CELL ? "smooth" : "nearest") << "\n";
  os << indent << "TransparentDataNodes: " << in.TransparentDataNodes << "\n";
  os << indent << "Shadows: " << (this->Shadows ? "on" : "off")
     << ", ShadowSampleDistance: " << this->ShadowSampleDistance << "\n";
  os << indent << "NumberOfBuilds: " << in.NumberOfBuilds << "\n";
  os << indent << "KdNodes: " << in.KdNodes << ", DataNodes: " << in.DataNodes << "\n";
  os << indent << "AtlasDimensions: " << in.AtlasDims.x << " x " << in.AtlasDims.y << " x "
     << in.AtlasDims.z << "\n";
  os << indent << "LastError: " << (in.LastError.empty() ? "(none)" : in.LastError) << "\n";
}
