// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspGpuRenderer.h"

#include "AmrspDriver.h"
#include "AmrspSceneLighting.h"
#include "AmrspProgress.h"

#include "vtkAMRMapperConversion.h"
#include "vtkAMRKdTreeVolumeMapper.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkSmartPointer.h"
#include "vtkVolumeMapper.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOpenGLRenderTimer.h"
#include "vtkOverlappingAMR.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#if AMRSP_GLX_ONLY
#include <X11/Xlib.h>
#endif

#include <chrono>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <thread>

namespace amrsp
{
namespace harness
{

struct GpuRenderer::Internals
{
  std::string Method;
  vtkSmartPointer<vtkOverlappingAMR> Amr = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkSmartPointer<vtkVolumeMapper> Mapper;
  vtkAMRKdTreeVolumeMapper* AmrMapper = nullptr; // Mapper, when it is one of the project's
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkColorTransferFunction> Colour;
  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkCamera> Start; // the camera after the view set-up, before any orbit
  int Width = 0;
  int Height = 0;
  std::string Device;
  std::string OpenGLVersion; ///< the context's GL_VERSION string
  std::string Backend;
  /// GPU time of the frames: timer queries around Render() (GL_TIMESTAMP at its start and end)
  vtkOpenGLRenderTimer Timer;
  double GpuMilliseconds = -1.0; // of the last frame; -1 where timer queries are unsupported
};

namespace
{
/// Level-0 bounding box in world coordinates, as the tool's CPU paths use it.
void Level0Bounds(const Hierarchy& h, double bounds[6])
{
  const glm::dvec3 lo = h.WorldLo(h.RootCells(), 0), hi = h.WorldHi(h.RootCells(), 0);
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = lo[a];
    bounds[2 * a + 1] = hi[a];
  }
}

/// The settings' blend mode, lighting and cropping on the mapper, property and renderer.
void SetModes(const RenderSettings& s, vtkVolumeProperty* property, vtkVolumeMapper* mapper,
  vtkRenderer* renderer)
{
  switch (s.Blend)
  {
    case BlendMode::Composite:
      mapper->SetBlendModeToComposite();
      break;
    case BlendMode::Maximum:
      mapper->SetBlendModeToMaximumIntensity();
      break;
    case BlendMode::Minimum:
      mapper->SetBlendModeToMinimumIntensity();
      break;
    case BlendMode::Average:
      mapper->SetBlendModeToAverageIntensity();
      break;
    case BlendMode::IsoSurface:
      break; // ApplyLighting sets it with the iso-values
  }
  ApplyLighting(s, property, mapper, renderer);
  if (s.Clip)
  {
    mapper->SetCropping(1);
    mapper->SetCroppingRegionFlagsToSubVolume();
    mapper->SetCroppingRegionPlanes(
      s.ClipLo.x, s.ClipHi.x, s.ClipLo.y, s.ClipHi.y, s.ClipLo.z, s.ClipHi.z);
  }
}
} // namespace

bool GpuRenderer::Available(std::string& why)
{
#if AMRSP_GLX_ONLY
  // VTK's GLX window aborts the process when it cannot open the display: probe first
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    why = "no X display (DISPLAY is not set; this VTK renders through GLX only: start Xvfb, e.g. "
          "'. scripts/start-xvfb.sh')";
    return false;
  }
  // The connection stays open for the life of the process: an X server started without
  // -noreset (Xvfb's default) resets whenever its last client disconnects, and a window VTK opens
  // during that reset fails ("bad X server connection", then abort()). Closing the probe right
  // before VTK connects made every other run abort.
  static Display* keepAlive = nullptr;
  // (the previous client's exit may have started such a reset: retry for a second)
  for (int attempt = 0; !keepAlive && attempt < 10; ++attempt)
  {
    keepAlive = XOpenDisplay(nullptr);
    if (!keepAlive)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  if (!keepAlive)
  {
    why = std::string("cannot open the X display ") + display;
    return false;
  }
#endif
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(8, 8);
  // both mappers need the same: an OpenGL 3.2 core context
  return vtkSinglePassAMRVolumeMapper::IsRenderSupported(window, &why);
}

GpuRenderer::GpuRenderer(const std::string& method, vtkVolumeMapper* mapper, const Hierarchy& h,
  const RenderSettings& s, const ViewAngles& view, const GpuScene& scene)
  : I(new Internals)
{
  I->Method = method;
  I->Mapper = mapper;
  I->AmrMapper = vtkAMRKdTreeVolumeMapper::SafeDownCast(mapper);
  if (I->AmrMapper)
  {
    // the mapper's build and upload on the terminal's progress bar (AmrspProgress.h)
    vtkNew<vtkCallbackCommand> progress;
    progress->SetCallback(
      [](vtkObject* caller, unsigned long, void*, void* call)
      {
        auto* amrMapper = static_cast<vtkAMRKdTreeVolumeMapper*>(caller);
        const char* text = amrMapper->GetProgressText();
        if (!text)
        {
          return; // the executive's events around the input's update, not a preparation's
        }
        const bool upload =
          amrMapper->GetProgressPhase() == vtkAMRKdTreeVolumeMapper::PROGRESS_UPLOAD;
        ReportProgress(upload ? "upload" : "build", text, *static_cast<double*>(call));
      });
    I->AmrMapper->AddObserver(vtkCommand::ProgressEvent, progress);
  }
  std::string why;
  if (!Available(why))
  {
    throw GpuError((scene.Unavailable.empty() ? "the " + method + " method cannot render here: "
                                              : scene.Unavailable) +
      why);
  }
  I->Width = s.Width;
  I->Height = s.Height;

  SetTransferFunction(s.Transfer);
  I->Property->SetColor(I->Colour);
  I->Property->SetScalarOpacity(I->Opacity);
  I->Property->ShadeOff();
  I->Property->SetInterpolationTypeToNearest();

  if (scene.AmrInput)
  {
    // the project's mappers do not read blanking: no vtkGhostType array (1 byte per cell)
    vtkAMRMapperConversion::ToOverlappingAMR(h, I->Amr, scene.Blanking);
    I->Mapper->SetInputDataObject(0, I->Amr);
    I->Mapper->SelectScalarArray(h.ArrayName.empty() ? "values" : h.ArrayName.c_str());
  }
  if (scene.Modes)
  {
    SetModes(s, I->Property, I->Mapper, I->Renderer);
  }
  I->Volume->SetMapper(I->Mapper);
  I->Volume->SetProperty(I->Property);

  I->Renderer->SetBackground(s.Background.r, s.Background.g, s.Background.b);
  I->Renderer->AddVolume(I->Volume);
  I->Window->SetOffScreenRendering(1);
  I->Window->SetMultiSamples(0);
  I->Window->SetSize(s.Width, s.Height);
  I->Window->AddRenderer(I->Renderer);

  // the camera of docs/design.md, "Rendering conventions": ResetCamera on the level-0 bounds,
  // Azimuth, Elevation, OrthogonalizeViewUp, Zoom
  double bounds[6];
  Level0Bounds(h, bounds);
  I->Renderer->ResetCamera(bounds);
  vtkCamera* camera = I->Renderer->GetActiveCamera();
  if (scene.Modes && view.UseSettingsCamera)
  {
    camera->SetPosition(s.View.Position.x, s.View.Position.y, s.View.Position.z);
    camera->SetFocalPoint(s.View.FocalPoint.x, s.View.FocalPoint.y, s.View.FocalPoint.z);
    camera->SetViewUp(s.View.ViewUp.x, s.View.ViewUp.y, s.View.ViewUp.z);
    camera->SetViewAngle(s.View.ViewAngle);
    camera->SetParallelProjection(s.View.Parallel ? 1 : 0);
    camera->SetParallelScale(s.View.ParallelScale);
  }
  else
  {
    camera->Azimuth(view.Azimuth);
    camera->Elevation(view.Elevation);
    camera->OrthogonalizeViewUp();
    camera->Zoom(view.Zoom);
  }
  I->Start->DeepCopy(camera);
}

GpuRenderer::~GpuRenderer()
{
  if (I)
  {
    I->Window->MakeCurrent();
    I->Timer.ReleaseGraphicsResources();
    I->Window->Finalize();
  }
}

Image GpuRenderer::Render(double orbitDegrees, double& milliseconds)
{
  vtkCamera* camera = I->Renderer->GetActiveCamera();
  camera->DeepCopy(I->Start);
  camera->Azimuth(orbitDegrees);
  I->Renderer->ResetCameraClippingRange();
  return this->RenderAsIs(milliseconds);
}

vtkRenderer* GpuRenderer::GetRenderer()
{
  return I->Renderer;
}

Image GpuRenderer::RenderAsIs(double& milliseconds)
{
  // the window's context exists after its first frame (which sets Device): the GPU is timed
  // from the second frame on
  bool timed = false;
  if (!I->Device.empty())
  {
    I->Window->MakeCurrent();
    timed = vtkOpenGLRenderTimer::IsSupported();
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (timed)
  {
    I->Timer.Reset();
    I->Timer.Start();
  }
  I->Window->Render();
  if (timed)
  {
    I->Window->MakeCurrent();
    I->Timer.Stop();
  }
  I->Window->WaitForCompletion();
  milliseconds =
    1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  I->GpuMilliseconds = -1.0;
  if (timed)
  {
    for (int wait = 0; wait < 1000 && !I->Timer.Ready(); ++wait)
    {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    if (I->Timer.Ready())
    {
      I->GpuMilliseconds = I->Timer.GetElapsedMilliseconds();
    }
  }
  const std::string error = this->LastError();
  if (!error.empty())
  {
    throw GpuError(std::string(I->Mapper->GetClassName()) + ": " + error);
  }
  if (I->Device.empty())
  {
    std::istringstream caps(I->Window->ReportCapabilities());
    for (std::string line; std::getline(caps, line);)
    {
      const std::string renderer = "OpenGL renderer string:";
      const std::string version = "OpenGL version string:";
      if (line.compare(0, renderer.size(), renderer) == 0)
      {
        I->Device = line.substr(line.find_first_not_of(' ', renderer.size()));
      }
      else if (line.compare(0, version.size(), version) == 0)
      {
        I->OpenGLVersion = line.substr(line.find_first_not_of(' ', version.size()));
      }
    }
    I->Backend = BackendOf(I->Window);
  }

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(I->Window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkImageData* data = grab->GetOutput();
  int dims[3];
  data->GetDimensions(dims);
  vtkUnsignedCharArray* rgb =
    vtkUnsignedCharArray::SafeDownCast(data->GetPointData()->GetScalars());
  if (!rgb || dims[0] != I->Width || dims[1] != I->Height || rgb->GetNumberOfComponents() != 3)
  {
    throw GpuError("reading the rendered image back failed");
  }
  Image img;
  img.Width = I->Width;
  img.Height = I->Height;
  img.Pixels.resize(static_cast<std::size_t>(img.Width) * img.Height);
  const unsigned char* p = rgb->GetPointer(0);
  for (std::size_t i = 0; i < img.Pixels.size(); ++i)
  {
    // 8-bit framebuffer; alpha is not read back (1 where anything was drawn, for coverage)
    const glm::vec3 c(p[3 * i] / 255.0f, p[3 * i + 1] / 255.0f, p[3 * i + 2] / 255.0f);
    img.Pixels[i] = glm::vec4(c, (c.r + c.g + c.b) > 0.0f ? 1.0f : 0.0f);
  }
  return img;
}

double GpuRenderer::LastGpuMilliseconds() const
{
  return I->GpuMilliseconds;
}

Camera GpuRenderer::LastCamera() const
{
  vtkCamera* c = I->Renderer->GetActiveCamera();
  Camera out;
  c->GetPosition(&out.Position.x);
  c->GetFocalPoint(&out.FocalPoint.x);
  c->GetViewUp(&out.ViewUp.x);
  out.ViewAngle = c->GetViewAngle();
  out.Parallel = c->GetParallelProjection() != 0;
  out.ParallelScale = c->GetParallelScale();
  return out;
}

vtkAMRKdTreeVolumeMapper* GpuRenderer::GetAmrMapper() const
{
  return I->AmrMapper;
}

double GpuRenderer::BuildSeconds() const
{
  return I->AmrMapper ? I->AmrMapper->GetLastBuildSeconds() : 0.0;
}

double GpuRenderer::UploadSeconds() const
{
  return I->AmrMapper ? I->AmrMapper->GetLastUploadSeconds() : 0.0;
}

int GpuRenderer::NumberOfBuilds() const
{
  return I->AmrMapper ? I->AmrMapper->GetNumberOfBuilds() : 0;
}

int GpuRenderer::NumberOfValueRefreshes() const
{
  return I->AmrMapper ? I->AmrMapper->GetNumberOfValueRefreshes() : 0;
}

void GpuRenderer::SetTransferFunction(const TransferFunction& t)
{
  // the same piecewise-linear functions as amrsp::TransferFunction (clamped beyond the ends)
  I->Colour->RemoveAllPoints();
  I->Opacity->RemoveAllPoints();
  for (const TransferFunction::ColorPoint& p : t.Color)
  {
    I->Colour->AddRGBPoint(p.X, p.Rgb.r, p.Rgb.g, p.Rgb.b);
  }
  for (const TransferFunction::OpacityPoint& p : t.Opacity)
  {
    I->Opacity->AddPoint(p.X, p.Opacity);
  }
  if (t.ColorLogScale)
  {
    I->Colour->SetScaleToLog10();
  }
  else
  {
    I->Colour->SetScaleToLinear();
  }
  I->Opacity->SetUseLogScale(t.OpacityLogScale);
  I->Colour->SetColorSpaceToRGB();
  I->Colour->ClampingOn();
  I->Opacity->ClampingOn();
  I->Property->SetScalarOpacityUnitDistance(t.UnitDistance);
}

void GpuRenderer::SetData(const Hierarchy& h, bool blanking)
{
  // a new data object, as a reader's next time step is: the mapper sees another input
  I->Amr = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkAMRMapperConversion::ToOverlappingAMR(h, I->Amr, blanking);
  I->Mapper->SetInputDataObject(0, I->Amr);
  // a step may map its values otherwise (log10 or not): its array's name
  I->Mapper->SelectScalarArray(h.ArrayName.empty() ? "values" : h.ArrayName.c_str());
}

vtkOverlappingAMR* GpuRenderer::GetData() const
{
  return I->Amr;
}

void GpuRenderer::SetDataObject(vtkOverlappingAMR* amr)
{
  I->Amr = amr;
  I->Mapper->SetInputDataObject(0, I->Amr);
}

long long GpuRenderer::TextureBytes() const
{
  return I->AmrMapper ? I->AmrMapper->GetTextureBytes() : 0;
}

std::string GpuRenderer::LastError() const
{
  return I->AmrMapper ? I->AmrMapper->GetLastError() : std::string();
}

void GpuRenderer::GetAtlasDimensions(int dims[3]) const
{
  dims[0] = dims[1] = dims[2] = 0;
  if (I->AmrMapper)
  {
    I->AmrMapper->GetAtlasDimensions(dims);
  }
}

std::string GpuRenderer::AtlasDimensions() const
{
  int d[3];
  this->GetAtlasDimensions(d);
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}

const std::string& GpuRenderer::Method() const
{
  return I->Method;
}

std::string GpuRenderer::Device() const
{
  return I->Device;
}

std::string GpuRenderer::OpenGLVersion() const
{
  return I->OpenGLVersion;
}

std::string GpuRenderer::Backend() const
{
  return I->Backend;
}

} // namespace harness
} // namespace amrsp
