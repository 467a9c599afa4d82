// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The GPU methods of the amrsp tool: one AMR volume mapper in an offscreen vtkRenderWindow with
/// the tool's camera, transfer-function and background conventions (README, "Rendering
/// conventions"). PackingRenderer (AmrspPacking.h) and MultipassRenderer (AmrspMultipass.h) add
/// their mapper.

#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"

#include <memory>
#include <stdexcept>
#include <string>

class vtkRenderer;
class vtkVolumeMapper;

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

class GpuRenderer
{
public:
  virtual ~GpuRenderer();
  GpuRenderer(const GpuRenderer&) = delete;
  GpuRenderer& operator=(const GpuRenderer&) = delete;

  /// Whether an OpenGL context with what the mappers need can be created here (an X display
  /// under GLX builds, OpenGL 3.2 core; both mappers need the same). `why` says what is missing.
  static bool Available(std::string& why);

  /// Renders one frame with the camera turned by `orbitDegrees` (vtkCamera::Azimuth after the
  /// view set-up) and reads it back. `milliseconds` is the time of Render() until the GPU
  /// finished. Throws GpuError when the mapper reports an error.
  Image Render(double orbitDegrees, double& milliseconds);

  /// Renders with the renderer's current camera and props (tests move the camera or add
  /// opaque geometry through GetRenderer()).
  Image RenderAsIs(double& milliseconds);
  vtkRenderer* GetRenderer();

  /// The VTK camera of the last frame as an amrsp::Camera (to check the conventions agree).
  Camera LastCamera() const;

  /// "OpenGL renderer string" of the context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string Device() const;
  /// The window system the frames were rendered through: "GLX", "EGL" or "OSMesa" (BackendOf).
  std::string Backend() const;
  /// The tool's name of the method ("packing", "multipass").
  const std::string& Method() const;

  /// Build (CPU: conversion, kD-tree, packing, encoding) and upload seconds of the mapper.
  virtual double BuildSeconds() const = 0;
  virtual double UploadSeconds() const = 0;
  virtual int NumberOfBuilds() const = 0;
  /// Bytes of the mapper's data textures.
  virtual long long TextureBytes() const = 0;
  std::string AtlasDimensions() const;

protected:
  /// Sets up the window, renderer, volume, property and camera around `mapper`, whose input
  /// becomes `h` (as a vtkOverlappingAMR) and whose array `h.ArrayName`. The subclass sets the
  /// mapper's own options. Throws GpuError ("the METHOD method cannot render here: ...") when no
  /// suitable OpenGL context can be created.
  GpuRenderer(const std::string& method, vtkVolumeMapper* mapper, const Hierarchy& h,
    const RenderSettings& s, const ViewAngles& view);

  /// The mapper's GetLastError() (empty after a successful frame).
  virtual std::string LastError() const = 0;
  /// The mapper's atlas dimensions.
  virtual void GetAtlasDimensions(int dims[3]) const = 0;

private:
  struct Internals;
  std::unique_ptr<Internals> I;
};

} // namespace tool
} // namespace amrsp
