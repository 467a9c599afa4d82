// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperProxyBox.h
 * @brief   the box the rays are integrated in, and its triangles (private to the module)
 *
 * Units: "index units" are level-0 cell indices (world = Origin + index * Spacing0); "model"
 * coordinates are the volume's own (before its vtkProp3D matrix).
 */
#ifndef vtkAMRMapperProxyBox_h
#define vtkAMRMapperProxyBox_h

#include <glm/glm.hpp>

#include <string>
#include <vector>

class vtkOpenGLBufferObject;
class vtkOpenGLVertexArrayObject;
class vtkShaderProgram;
class vtkVolumeMapper;

namespace vtkAMRMapperProxyBox
{

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

/// The 12 triangles (36 vertices, xyz) of the box [lo, hi], wound counter-clockwise seen from
/// outside: the proxy geometry whose back faces start the rays.
std::vector<float> BoxTriangles(const double lo[3], const double hi[3]);

/// Binds `array` and, when `program` is not `boundProgram` (then updated), attaches `buffer`'s
/// triangles (BoxTriangles' xyz floats) to `program`'s vec3 attribute `attribute`. Returns false,
/// leaving `array` released, when the attribute cannot be attached.
bool BindTriangles(vtkOpenGLVertexArrayObject* array, vtkOpenGLBufferObject* buffer,
  vtkShaderProgram* program, const char* attribute, vtkShaderProgram*& boundProgram);

} // namespace vtkAMRMapperProxyBox

#endif
