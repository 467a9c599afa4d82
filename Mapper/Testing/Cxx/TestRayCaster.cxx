// SPDX-License-Identifier: BSD-3-Clause
// The two casters of vtkSinglePassAMRVolumeMapper (RayCaster): the fragment shader over the proxy
// box and the compute shader over the rays' image put the same bytes on the screen.
//
//   (no argument)  AUTO_CASTER takes the caster its rule names for this driver; both casters
//                  render the same bytes in a renderer whose viewport is not the window's (as
//                  ParaView's tiles and IceT's regions are), with the volume cut by opaque
//                  geometry, and with another volume in front; and the comparison rejects a
//                  compute caster broken on purpose (its pixels shifted by one, its rays through
//                  the pixels' corners instead of their centres: shader replacements that only
//                  the compute stage contains).
//   no-compute     run by CTest in a context without compute shaders (Mesa's
//                  MESA_GL_VERSION_OVERRIDE=4.2 and GL_ARB_compute_shader switched off):
//                  COMPUTE_CASTER and AUTO_CASTER fall back to the fragment shader, say why
//                  (GetRayCasterFallbackReason) with one warning, and render its image.
#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"
#include "MapperTestScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkOpenGLShaderProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"

#include <iostream>
#include <string>

namespace
{
using namespace amrsp;
using namespace amrsp::harness;
using mappertest::Check;
using mappertest::ShaderProperty;
using Mapper = vtkSinglePassAMRVolumeMapper;

/// The frame cast by `caster`, with a failed check when another caster ran.
Image CastBy(SinglePassRenderer& gpu, int caster)
{
  gpu.GetMapper()->SetRayCaster(caster);
  double ms = 0.0;
  Image image = gpu.RenderAsIs(ms);
  const int ran = gpu.GetMapper()->GetLastRayCaster();
  if (ran != caster)
  {
    Check(false,
      std::string("asked for the ") + Mapper::GetRayCasterName(caster) + " caster, the " +
        Mapper::GetRayCasterName(ran) + " caster ran");
  }
  return image;
}

/// The fragment and the compute caster's frames compared (every pixel the same), labelled.
void SameBytes(SinglePassRenderer& gpu, const std::string& what)
{
  const Image fragment = CastBy(gpu, Mapper::FRAGMENT_CASTER);
  const Image compute = CastBy(gpu, Mapper::COMPUTE_CASTER);
  const mappertest::FrameComparison c = mappertest::CompareFrames(compute, fragment);
  Check(c.DifferentPixels == 0 && c.CoveredPixels > 100,
    what + ": compute against fragment: " + c.Describe());
}

void TestCasters()
{
  Hierarchy h = mappertest::LoadHierarchy("synthetic:cosmo:grids=120,levels=3,cells=500k,seed=3");
  const RenderSettings s = mappertest::Settings(
    h, mappertest::Request(120, 96, [](amrsp::harness::RenderRequest& r) { r.Shade = true; }));
  SinglePassRenderer gpu(h, s, ViewAngles(), DataStorage::PackedAtlas);
  Mapper* mapper = gpu.GetMapper();
  double ms = 0.0;

  // the automatic choice on this driver (read from the window once it has a context)
  mapper->SetRayCaster(Mapper::AUTO_CASTER);
  gpu.Render(0.0, ms);
  const bool cpuDriver = mappertest::IsCpuDriver(gpu.GetRenderer()->GetRenderWindow());
  const int expected = cpuDriver ? Mapper::FRAGMENT_CASTER : Mapper::COMPUTE_CASTER;
  Check(mapper->GetLastRayCaster() == expected &&
      std::string(mapper->GetRayCasterFallbackReason()).empty(),
    std::string("AUTO_CASTER on ") + (cpuDriver ? "a CPU driver" : "a GPU") + " casts with the " +
      Mapper::GetRayCasterName(mapper->GetLastRayCaster()) + " shader");

  // a context without compute shaders: the fallback is Mapper.RayCaster.NoCompute's subject
  mapper->SetRayCaster(Mapper::COMPUTE_CASTER);
  gpu.RenderAsIs(ms);
  const std::string noCompute = mapper->GetRayCasterFallbackReason();
  std::cout << "casters here: "
            << (noCompute.empty() ? "fragment and compute" : "fragment only (" + noCompute + ")")
            << "\n";
  if (!noCompute.empty())
  {
    Check(mapper->GetLastRayCaster() == Mapper::FRAGMENT_CASTER,
      "without compute shaders the fragment shader cast the rays");
    return;
  }

  SameBytes(gpu, "the whole window");

  // a viewport that is not the window's: the rays' image is the viewport's, composited there
  gpu.GetRenderer()->SetViewport(0.2, 0.15, 0.95, 0.9);
  SameBytes(gpu, "a renderer over part of the window");

  // opaque geometry cutting the volume: both casters read its depth at their pixels
  mappertest::AddCentralSphere(gpu.GetRenderer(), h);
  SameBytes(gpu, "opaque geometry inside the volume");

  // the comparison rejects a compute caster broken on purpose
  vtkOpenGLShaderProperty* shader = ShaderProperty(gpu);
  if (!shader)
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
    return;
  }
  const Image fragment = CastBy(gpu, Mapper::FRAGMENT_CASTER);
  const struct
  {
    const char* What;
    const char* Original;
    const char* Broken;
  } broken[] = {
    { "its pixels shifted by one", "imageStore(amrspRayImage, pixel, result);",
      "imageStore(amrspRayImage, pixel + ivec2(1, 0), result);" },
    { "its rays through the pixels' corners", "amrspViewport.xy + vec2(pixel) + 0.5",
      "amrspViewport.xy + vec2(pixel)" },
  };
  for (const auto& b : broken)
  {
    shader->AddFragmentShaderReplacement(b.Original, false, b.Broken, false);
    const Image wrong = CastBy(gpu, Mapper::COMPUTE_CASTER);
    shader->ClearAllFragmentShaderReplacements();
    const mappertest::FrameComparison c = mappertest::CompareFrames(wrong, fragment);
    Check(c.DifferentPixels > c.CoveredPixels / 10,
      std::string("a compute caster with ") + b.What + " is rejected: " + c.Describe());
  }
  const mappertest::FrameComparison repaired =
    mappertest::CompareFrames(CastBy(gpu, Mapper::COMPUTE_CASTER), fragment);
  Check(repaired.DifferentPixels == 0, "without the breakage the same bytes again");
}

/// The exit code of a test that found it cannot run here (0: it ran).
int& Skipped()
{
  static int code = 0;
  return code;
}

/// In a context without compute shaders: both requests fall back, with one warning.
void TestNoCompute()
{
  Hierarchy h = mappertest::LoadHierarchy("synthetic:cosmo:grids=60,levels=3,cells=200k,seed=2");
  const RenderSettings s = mappertest::Settings(h, mappertest::Request(96, 96));
  SinglePassRenderer gpu(h, s, ViewAngles(), DataStorage::PackedAtlas);
  Mapper* mapper = gpu.GetMapper();
  int warnings = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&warnings);
  counter->SetCallback(
    [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  mapper->AddObserver(vtkCommand::WarningEvent, counter);
  const Image fragment = CastBy(gpu, Mapper::FRAGMENT_CASTER);
  Check(
    warnings == 0, "the fragment caster asked for: no warning (" + std::to_string(warnings) + ")");
  mapper->SetRayCaster(Mapper::COMPUTE_CASTER);
  double first = 0.0;
  gpu.RenderAsIs(first);
  if (mapper->GetLastRayCaster() == Mapper::COMPUTE_CASTER)
  {
    // not a context without compute shaders (a driver that ignores Mesa's overrides)
    Skipped() = mappertest::SkipOrFail(
      "the driver kept its compute shaders under MESA_GL_VERSION_OVERRIDE=4.2 and "
      "MESA_EXTENSION_OVERRIDE=-GL_ARB_compute_shader (Mesa honours them)");
    return;
  }
  for (int requested : { Mapper::COMPUTE_CASTER, Mapper::AUTO_CASTER, Mapper::COMPUTE_CASTER })
  {
    mapper->SetRayCaster(requested);
    double ms = 0.0;
    const Image image = gpu.RenderAsIs(ms);
    const std::string why = mapper->GetRayCasterFallbackReason();
    Check(mapper->GetLastRayCaster() == Mapper::FRAGMENT_CASTER &&
        why.find("compute shaders") != std::string::npos,
      std::string(Mapper::GetRayCasterName(requested)) +
        " asked for: the fragment shader cast the rays, because: " + why);
    const mappertest::FrameComparison c = mappertest::CompareFrames(image, fragment);
    Check(c.DifferentPixels == 0 && c.CoveredPixels > 100, "its image: " + c.Describe());
  }
  Check(warnings == 1, "one warning in all (" + std::to_string(warnings) + ")");
}

} // namespace

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode != "" && mode != "no-compute")
  {
    std::cerr << "usage: TestRayCaster [no-compute]\n";
    return 2;
  }
  const int rc = mappertest::RunChecks(mode == "no-compute" ? TestNoCompute : TestCasters);
  return Skipped() != 0 ? Skipped() : rc;
}
