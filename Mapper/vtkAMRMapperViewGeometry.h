// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperViewGeometry.h
 * @brief   the renderer's view and light in the volume's model coordinates (private to the module)
 *
 * What both mappers derive from VTK's camera, the volume's matrix and the renderer's lights:
 * viewport, model <-> normalized device matrices, the rays' origin, the first light.
 * Units: "index units" are level-0 cell indices (world = Origin + index * Spacing0); "model"
 * coordinates are the volume's own (before its vtkProp3D matrix).
 */
#ifndef vtkAMRMapperViewGeometry_h
#define vtkAMRMapperViewGeometry_h

#include <string>

class vtkMatrix4x4;
class vtkRenderer;
class vtkVolume;

namespace vtkAMRMapperViewGeometry
{

/// Column-major float copy of a row-major vtkMatrix4x4, as glUniformMatrix4fv expects.
void ToColumnMajor(vtkMatrix4x4* m, float out[16]);

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

} // namespace vtkAMRMapperViewGeometry

#endif
