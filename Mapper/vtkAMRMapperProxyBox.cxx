// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperProxyBox.h"

#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkShaderProgram.h"
#include "vtkVolumeMapper.h"

#include <algorithm>
#include <sstream>

namespace vtkAMRMapperProxyBox
{

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
bool BindTriangles(vtkOpenGLVertexArrayObject* array, vtkOpenGLBufferObject* buffer,
  vtkShaderProgram* program, const char* attribute, vtkShaderProgram*& boundProgram)
{
  array->Bind();
  if (boundProgram == program)
  {
    return true;
  }
  array->ReleaseGraphicsResources();
  array->Bind();
  if (!array->AddAttributeArray(
        program, buffer, attribute, 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
  {
    array->Release();
    return false;
  }
  boundProgram = program;
  return true;
}

} // namespace vtkAMRMapperProxyBox
