// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The GPU methods of the amrsp tool: one volume mapper in an offscreen vtkRenderWindow with the
/// tool's camera, transfer-function and background conventions (docs/design.md, "Rendering
/// conventions"). SinglePassRenderer (AmrspSinglePass.h), MultipassRenderer (AmrspMultipass.h),
/// UniformGpuRenderer (AmrspUniform.h) and AmrResampleRenderer (AmrspAmrResample.h) add their
/// mapper; AmrspMethods.h says which method uses which.

#include "amrsp/Camera.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/Image.h"
#include "amrsp/RenderSettings.h"

#include <memory>
#include <stdexcept>
#include <string>

class vtkRenderer;
class vtkAMRKdTreeVolumeMapper;
class vtkVolumeMapper;

class vtkOverlappingAMR;

namespace amrsp
{
namespace harness
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

/// What a GpuRenderer's scene takes from the hierarchy and the settings besides the image size,
/// the transfer function (nearest interpolation, unshaded unless Modes), the background and the
/// conventions' camera.
struct GpuScene
{
  /// The mapper's input is `h` as a vtkOverlappingAMR, array `h.ArrayName` (false: the
  /// subclass sets the mapper's input).
  bool AmrInput = true;
  /// With AmrInput: every block also carries the vtkGhostType blanking array (the finest ones all
  /// zero), for VTK's own AMR consumers, which need the same arrays in every block.
  bool Blanking = false;
  /// The settings' blend mode, lighting, cropping and --view-json camera (false: composite,
  /// unshaded, uncropped, the conventions' camera: uniform-gpu).
  bool Modes = true;
  /// The start of the error when no OpenGL context can be had (default: "the METHOD method
  /// cannot render here: ").
  std::string Unavailable;
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

  /// Hands the mapper another hierarchy as a new vtkOverlappingAMR (a time step), keeping the
  /// camera, transfer function and settings; `blanking` as GpuScene::Blanking. Only for
  /// renderers of AMR input (GpuScene::AmrInput).
  void SetData(const Hierarchy& h, bool blanking = false);
  /// Replaces the volume property's colour and opacity functions and unit distance (a series
  /// step mapped with its own range).
  void SetTransferFunction(const TransferFunction& t);
  /// The vtkOverlappingAMR the mapper reads now, and handing it one made before (a step shown
  /// again: the same object, as ParaView's animation cache hands it back).
  vtkOverlappingAMR* GetData() const;
  void SetDataObject(vtkOverlappingAMR* amr);

  /// Renders with the renderer's current camera and props (tests move the camera or add
  /// opaque geometry through GetRenderer()).
  Image RenderAsIs(double& milliseconds);
  vtkRenderer* GetRenderer();

  /// GPU time of the last frame in milliseconds, from timer queries around its Render() (not
  /// the read-back); -1 for the first frame of a window and where timer queries are unsupported.
  double LastGpuMilliseconds() const;

  /// The VTK camera of the last frame as an amrsp::Camera (to check the conventions agree).
  Camera LastCamera() const;

  /// "OpenGL renderer string" of the context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string Device() const;
  /// The context's OpenGL version string (GL_VERSION), after the first frame.
  std::string OpenGLVersion() const;
  /// The window system the frames were rendered through: "GLX", "EGL" or "OSMesa" (BackendOf).
  std::string Backend() const;
  /// The tool's name of the method ("packing", "bindless", "multipass", "uniform-gpu", ...).
  const std::string& Method() const;

  /// Build (CPU: conversion, kD-tree, packing, encoding) and upload seconds of the mapper, and
  /// how often it built. The base answers for the project's mappers (vtkAMRKdTreeVolumeMapper);
  /// a renderer around another mapper overrides these.
  virtual double BuildSeconds() const;
  virtual double UploadSeconds() const;
  virtual int NumberOfBuilds() const;
  /// Of the builds, those that kept the structure and took new values only
  /// (vtkAMRKdTreeVolumeMapper::GetNumberOfValueRefreshes; 0 for other mappers).
  virtual int NumberOfValueRefreshes() const;
  /// Bytes of the mapper's data textures.
  virtual long long TextureBytes() const;
  std::string AtlasDimensions() const;

protected:
  /// Sets up the window, renderer, volume, property and camera around `mapper` as `scene` says.
  /// The subclass sets the mapper's own options. Throws GpuError (scene.Unavailable + why) when
  /// no suitable OpenGL context can be created.
  GpuRenderer(const std::string& method, vtkVolumeMapper* mapper, const Hierarchy& h,
    const RenderSettings& s, const ViewAngles& view, const GpuScene& scene = GpuScene());

  /// The mapper when it is one of the project's (vtkAMRKdTreeVolumeMapper), else nullptr.
  vtkAMRKdTreeVolumeMapper* GetAmrMapper() const;

  /// The mapper's GetLastError() (empty after a successful frame).
  virtual std::string LastError() const;
  /// The mapper's atlas dimensions (0 where it has none).
  virtual void GetAtlasDimensions(int dims[3]) const;

private:
  struct Internals;
  std::unique_ptr<Internals> I;
};

} // namespace harness
} // namespace amrsp
