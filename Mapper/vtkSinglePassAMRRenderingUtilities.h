// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRRenderingUtilities.h
 * @brief   pieces shared by the AMR volume mappers (private to the module)
 *
 * What the single-pass and the multi-pass mapper have in common and must keep identical so that
 * their images agree: the array selection, the CPU build of the packed data (conversion, kD-tree,
 * brick atlas, scalar range, per-level sampling distances), the atlas upload and its size checks,
 * the transfer-function table, the matrices and ray origin derived from VTK's camera, and the
 * copy of the opaque geometry's depth buffer. The header exposes core (amrsp) types and is not
 * installed.
 *
 * Units: "index units" are level-0 cell indices (world = Origin + index * Spacing0); "model"
 * coordinates are the volume's own (before its vtkProp3D matrix); "finest cells" are cells of the
 * hierarchy's finest level, in which kD-tree regions are exact integers.
 */
#ifndef vtkSinglePassAMRRenderingUtilities_h
#define vtkSinglePassAMRRenderingUtilities_h

#include "amrsp/AtlasPages.h"
#include "amrsp/BrickAtlas.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"

#include "vtkOpenGLState.h" // for ScopedBlendedDraw
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h" // for TransferFunctionTable::GetTexture
#include "vtkTimeStamp.h"
#include "vtkType.h"

#include <functional> // for UploadInSlabs, UploadAtlasBySlabs
#include <string>
#include <utility>
#include <vector>

class vtkOpenGLFramebufferObject;
class vtkOpenGLRenderWindow;
class vtkMatrix4x4;
class vtkOverlappingAMR;
class vtkRenderWindow;
class vtkRenderer;
class vtkVolume;
class vtkVolumeMapper;
class vtkVolumeProperty;
class vtkWindow;

namespace vtkSinglePassAMRRenderingUtilities
{

/// Entries of the RGBA transfer-function table (linear filtering between entries).
constexpr int TransferTableSize = 4096;

/// The array a vtkAbstractVolumeMapper selection asks for: a name, an index into the cell arrays,
/// or "" (the first cell array, or the first point array if there is none).
std::string RequestedArray(vtkOverlappingAMR* amr, int accessMode, const char* name, int id);

/// Column-major float copy of a row-major vtkMatrix4x4, as glUniformMatrix4fv expects.
void ToColumnMajor(vtkMatrix4x4* m, float out[16]);

/**
 * The box the rays are integrated in, index units: the root box [rootLo, rootHi], intersected
 * with vtkVolumeMapper's cropping planes (model coordinates) when cropping is on with the flags
 * VTK_CROP_SUBVOLUME (the central sub-volume only). Other cropping flags are not supported:
 * the root box is returned and `warning` names the flags (else it is left empty). An empty
 * intersection gives a flat box (lo = hi on an axis: no ray integrates anything).
 */
void ClipBox(vtkVolumeMapper* mapper, const glm::dvec3& origin, const glm::dvec3& spacing0,
  const glm::vec3& rootLo, const glm::vec3& rootHi, glm::vec3& lo, glm::vec3& hi,
  std::string& warning);

/**
 * The CPU side of the packing storage (paper, sections 4.1 and 5.1): the hierarchy's structure,
 * its kD-tree, one brick per grid packed into one float atlas, and what the shaders need about
 * the levels.
 */
struct PackedHierarchy
{
  /// Grids, ratios, origin and spacing, and the values until the atlas holds them.
  amrsp::Hierarchy Structure;
  amrsp::KdTree Tree;
  /// Where each grid's brick lies in the atlas pages (usually one); Structure.Values are the
  /// bricks (borrowed from the input where possible), dropped by the caller after the upload.
  amrsp::AtlasPages Atlas;
  bool VertexCentred = false; ///< vertex bricks (trilinear) instead of cell bricks (nearest)
  /// Smallest model-space edge of a cell of each level (the sampling rule's D for factor 1).
  std::vector<double> LevelMinEdge;
  /// Finite value range of the selected scalars ([0, 1] when there is none).
  double ScalarRange[2] = { 0.0, 1.0 };
  /// Model-space bounds of the root box [xmin, xmax, ymin, ymax, zmin, zmax].
  double Bounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
};

/**
 * Converts `amr` (array `array`, component `component`), builds the kD-tree and packs the bricks
 * with the better packer within `packLimit` texels per axis (0: the 2048 the data-node offsets
 * address; a positive value lowers it), over atlas pages of at most `maxPageTexels` texels (0:
 * one atlas). Returns false with a one-line `error` (conversion, tree or packing failure).
 */
bool BuildPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, PackedHierarchy& out, std::string& error);

/**
 * A new time step for `out` built by BuildPackedHierarchy with the same array, component and
 * limits: when `mayRefresh` and `amr`'s hierarchy has `out`'s structure (amrsp::SameStructure),
 * `out` keeps its tree and atlas layout and takes the new values and their range (`refreshed`
 * true); otherwise it is built again as BuildPackedHierarchy does. Same errors.
 */
bool RefreshPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, bool mayRefresh, PackedHierarchy& out, bool& refreshed,
  std::string& error);

/**
 * Whether an atlas of `dims` texels fits `renWin`'s GL_MAX_3D_TEXTURE_SIZE and `atlasLimit`
 * (> 0: a lower limit set by the user). When not, `why` names the limit it exceeds.
 */
bool AtlasFitsContext(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, int atlasLimit, std::string& why);

/// An RG32UI 3D texture of a kD-tree encoding (nearest, clamped); null when OpenGL refused it.
/// An RGBA32UI 3D texture of `texels` (nearest filtering); null when the driver refuses it.
vtkSmartPointer<vtkTextureObject> MakeInteger4Texture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UInt4Texture3D& texels);
vtkSmartPointer<vtkTextureObject> MakeIntegerTexture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UIntTexture3D& texels);

/// An R32F brick or atlas texture of `dims` texels: nearest for cell bricks, trilinear for vertex
/// bricks (the shaders never sample outside a brick), clamped; null when OpenGL refused it.
vtkSmartPointer<vtkTextureObject> MakeScalarTexture(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, const float* texels, bool vertexCentred);

/// The 12 triangles (36 vertices, xyz) of the box [lo, hi], wound counter-clockwise seen from
/// outside: the proxy geometry whose back faces start the rays.
std::vector<float> BoxTriangles(const double lo[3], const double hi[3]);

/// The first switched-on light of a renderer, in model coordinates (what the shaders light with).
struct ModelLight
{
  float Position[3] = { 0.0f, 0.0f, 0.0f };
  float Direction[3] = { 0.0f, 0.0f, 1.0f }; ///< unit vector from the focal point to the light
  float Colour[3] = { 0.0f, 0.0f, 0.0f };    ///< diffuse colour x intensity; black: no light
  bool Positional = false;
};

/// The first switched-on light of `ren` moved into the model coordinates of `vol` (none: black).
ModelLight FirstLightInModel(vtkRenderer* ren, vtkVolume* vol);

/**
 * Hands `units` units (atlas layers, page rows) of `unitFloats` floats each to `upload` in slabs
 * of at most `slab` units, double-buffered: a worker thread fills the next slab (`fill(first,
 * last, out)`, units first <= u < last) while `upload(first, last, texels)` hands the current one
 * to the driver. `progress` gets the fraction of the units done after each slab. Rethrows what
 * `fill` threw.
 */
void UploadInSlabs(int units, int slab, std::size_t unitFloats,
  const std::function<void(int, int, float*)>& fill,
  const std::function<void(int, int, const float*)>& upload,
  const std::function<void(double)>& progress);

/**
 * The atlas of `h`'s bricks placed by `layout` as an R32F 3D texture (MakeScalarTexture's
 * filtering), allocated empty and filled slab by slab (amrsp::AtlasSlabFiller, about 16 MiB per
 * glTexSubImage3D, the next slab filled on a worker thread meanwhile): the whole atlas never
 * exists in host memory. `progress` gets the fraction of the layers uploaded after each slab.
 * Null when OpenGL refused the allocation.
 */
vtkSmartPointer<vtkTextureObject> UploadAtlasBySlabs(vtkOpenGLRenderWindow* renWin,
  const amrsp::Hierarchy& h, const amrsp::AtlasLayout& layout, bool vertexCentred,
  const std::function<void(double)>& progress = nullptr);

/**
 * UploadAtlasBySlabs with checks: fails with a one-line `error` when an edge exceeds
 * GL_MAX_3D_TEXTURE_SIZE or `atlasLimit` (> 0), or when OpenGL reports an error (e.g. out of
 * memory); `texture` is then null.
 */
bool UploadAtlas(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h,
  const amrsp::AtlasLayout& layout, bool vertexCentred, int atlasLimit,
  vtkSmartPointer<vtkTextureObject>& texture, std::string& error,
  const std::function<void(double)>& progress = nullptr);

/**
 * The transfer function of component 0 of a vtkVolumeProperty as an RGBA32F table of
 * TransferTableSize entries (colour or grey, and the scalar opacity per unit distance). The table
 * spans the union of the functions' ranges (both clamp beyond their end points); when the
 * functions have no range, the data's scalar range.
 */
class TransferFunctionTable
{
public:
  /// Re-tabulates when the property, its MTime or `dataTime` (the data's build time) changed.
  /// Returns false when the texture cannot be created.
  bool Update(vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property,
    const double scalarRange[2], const vtkTimeStamp& dataTime);
  vtkTextureObject* GetTexture() const { return this->Texture; }
  /// The opacity column of the table (TransferTableSize entries) and when it was last tabulated.
  const std::vector<float>& GetOpacityTable() const { return this->Opacity; }
  vtkMTimeType GetTableTime() const { return this->Time.GetMTime(); }
  /// Scalar at the first entry and 1 / (last - first): the shader's amrspTransferRange (in
  /// log10 of the scalar when IsLogarithmic).
  void GetShaderRange(float range[2]) const;
  /// Whether the table is indexed by log10 of the scalar (a log-scaled colour or opacity
  /// function over a positive range): the shaders then need AMRSP_LOG_TRANSFER.
  bool IsLogarithmic() const { return this->Logarithmic; }
  /// The scalar in the table's units (its log10 when IsLogarithmic; -FLT_MAX at or below 0).
  float TableScalar(float scalar) const;
  /// Why a requested log scale was not used by the last Update (empty when none).
  const std::string& GetWarning() const { return this->Warning; }
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkSmartPointer<vtkTextureObject> Texture;
  vtkVolumeProperty* Property = nullptr; // identity only
  vtkMTimeType PropertyMTime = 0;
  vtkTimeStamp Time;
  double Range[2] = { 0.0, 1.0 };
  std::vector<float> Opacity;
  bool Logarithmic = false;
  std::string Warning;
};

/**
 * The renderer's view as the raycasting shaders use it: viewport, model -> normalized device
 * matrices and the rays' origin. Perspective rays start at the eye (the pinhole camera of
 * docs/design.md), parallel rays on the near plane.
 */
struct ViewGeometry
{
  int X0 = 0, Y0 = 0, Width = 0, Height = 0; ///< the viewport in window pixels
  float MCDC[16];                            ///< model -> normalized device, column-major
  float DCMC[16];                            ///< its inverse, column-major
  /// Eye in model coordinates; w = 1 for perspective, 0 for parallel projection.
  float EyeMC[4] = { 0.0f, 0.0f, 0.0f, 1.0f };
  bool Parallel = false;
  /// Eye (perspective) in model coordinates, and the viewing direction (model units, not
  /// normalized; parallel projection), in double for the CPU's visibility ordering.
  double Eye[3] = { 0.0, 0.0, 0.0 };
  double Direction[3] = { 0.0, 0.0, -1.0 };
  /// The volume's matrix mirrors (negative determinant): faces wind the other way.
  bool Mirrored = false;
};

/// Fills `view` from the renderer's active camera and the volume's matrix. Returns false with
/// `error` for a renderer without an OpenGL camera or with an empty viewport.
bool ComputeViewGeometry(vtkRenderer* ren, vtkVolume* vol, ViewGeometry& view, std::string& error);

/// The depth of the opaque geometry drawn so far, copied for the ray caster: a depth texture of
/// the viewport's size and of the framebuffer's depth format (a depth blit needs the same format
/// on both sides), and the framebuffer object the blit writes into (multisampled windows, VTK's
/// default, can be read only by a blit, which resolves them).
struct DepthCopy
{
  vtkSmartPointer<vtkTextureObject> Depth;
  vtkSmartPointer<vtkTextureObject> Colour; // completes the framebuffer object; never read
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  int Format = -1; // vtkTextureObject's depth format enum

  void ReleaseGraphicsResources(vtkWindow* window);
};

/// Copies the depth buffer of the viewport into `copy.Depth`, (re)creating the textures when
/// missing, of another context or size, or of another depth format. Leaves `copy.Depth` active.
void CopyDepthBuffer(vtkOpenGLRenderWindow* renWin, const ViewGeometry& view, DepthCopy& copy);

/**
 * A fragment shader from its template `source`: `defines` replaces the line //AMRSP::Defines,
 * each (tag, code) of `pieces` replaces its line //AMRSP::<tag> (the shared .glsl pieces), and
 * the volume's vtkShaderProperty fragment replacements apply as VTK's own mappers apply them:
 * those marked "replace first" before these substitutions, the others after.
 */
std::string ComposeFragmentShader(const char* source, const std::string& defines,
  const std::vector<std::pair<std::string, const char*>>& pieces, vtkVolume* vol);

/**
 * The OpenGL state of a blended draw of the volume's proxy geometry, for the lifetime of the
 * object: no depth test and no depth writes, blending on with the factors `source` and
 * `destination` for colour and alpha alike, and faces of `cullFace` (GL_FRONT or GL_BACK) culled,
 * or culling off (GL_NONE). Restores culling, depth test, blending, depth mask and blend factors
 * as they were, and the culled face to GL_BACK (VTK's default, which vtkOpenGLState does not
 * save).
 */
class ScopedBlendedDraw
{
public:
  ScopedBlendedDraw(
    vtkOpenGLState* state, unsigned int cullFace, unsigned int source, unsigned int destination);
  ~ScopedBlendedDraw();
  ScopedBlendedDraw(const ScopedBlendedDraw&) = delete;
  ScopedBlendedDraw& operator=(const ScopedBlendedDraw&) = delete;

private:
  vtkOpenGLState* State;
  bool Culls;
  vtkOpenGLState::ScopedglEnableDisable CullSaved;
  vtkOpenGLState::ScopedglEnableDisable DepthTestSaved;
  vtkOpenGLState::ScopedglEnableDisable BlendSaved;
  vtkOpenGLState::ScopedglDepthMask DepthMaskSaved;
  vtkOpenGLState::ScopedglBlendFuncSeparate BlendFuncSaved;
};

/// Whether `window` offers an OpenGL 3.2 core context (integer and float textures, GLSL 1.50,
/// float colour attachments, depth clamping). When it does not, `why` says what is missing.
bool IsRenderSupported(vtkRenderWindow* window, std::string* why);

} // namespace vtkSinglePassAMRRenderingUtilities

#endif
