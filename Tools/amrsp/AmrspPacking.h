// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The `packing` method of the amrsp tool: vtkSinglePassAMRVolumeMapper in an offscreen
/// vtkRenderWindow with the tool's camera, transfer-function and background conventions
/// (README, "Rendering conventions").

#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"

#include <memory>
#include <stdexcept>
#include <string>

class vtkRenderer;
class vtkSinglePassAMRVolumeMapper;

namespace amrsp
{
namespace tool
{

/// The mapper could not render (no display, missing OpenGL features, a mapper error). what() is
/// one line.
class GpuError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// The view as the tool's options give it: VTK camera operations applied after ResetCamera.
struct ViewAngles
{
  double Azimuth = 30.0;
  double Elevation = 20.0;
  double Zoom = 1.0;
  /// Take the camera of the RenderSettings as it is (a --view-json camera) instead of the
  /// conventions' ResetCamera + angles.
  bool UseSettingsCamera = false;
};

class PackingRenderer
{
public:
  /// `h` holds the scalars as they are displayed (after --scale); `s` gives the image size, the
  /// transfer function, its unit distance and the sample factor. Nothing is rendered yet.
  PackingRenderer(const Hierarchy& h, const RenderSettings& s, const ViewAngles& view);
  ~PackingRenderer();
  PackingRenderer(const PackingRenderer&) = delete;
  PackingRenderer& operator=(const PackingRenderer&) = delete;

  /// Whether an OpenGL context with what the mapper needs can be created here (an X display
  /// under GLX builds, OpenGL 3.2 core). `why` says what is missing.
  static bool Available(std::string& why);

  /// Renders one frame with the camera turned by `orbitDegrees` (vtkCamera::Azimuth after the
  /// view set-up) and reads it back. `milliseconds` is the time of Render() until the GPU
  /// finished. Throws GpuError when the mapper reports an error.
  Image Render(double orbitDegrees, double& milliseconds);

  /// Renders with the renderer's current camera and props (tests move the camera or add
  /// opaque geometry through GetRenderer()).
  Image RenderAsIs(double& milliseconds);
  vtkRenderer* GetRenderer();
  vtkSinglePassAMRVolumeMapper* GetMapper();

  /// The VTK camera of the last frame as an amrsp::Camera (to check the conventions agree).
  Camera LastCamera() const;

  /// Build (CPU: conversion, kD-tree, packing, encoding) and upload seconds of the mapper.
  double BuildSeconds() const;
  double UploadSeconds() const;
  int NumberOfBuilds() const;
  long long TextureBytes() const;
  std::string AtlasDimensions() const;
  /// "OpenGL renderer string" of the context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string Device() const;

private:
  struct Internals;
  std::unique_ptr<Internals> I;
};

} // namespace tool
} // namespace amrsp
