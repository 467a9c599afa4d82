// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspMethods.h"

#include "AmrspAmrResample.h"
#include "AmrspMultipass.h"
#include "AmrspSinglePass.h"
#include "AmrspUniform.h"

#include <ostream>
#include <sstream>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

namespace
{

/// The settings of a single-pass method `spec` ("name" or "name:CASTER[-LOOP]", e.g.
/// "packing:compute-flat"): `r`'s, with the parameter's caster and ray loop.
RenderSettings SinglePassVariant(const std::string& spec, const MethodRequest& r)
{
  RenderSettings s = r.Settings;
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos)
  {
    return s;
  }
  const std::string variant = spec.substr(colon + 1);
  const std::size_t dash = variant.find('-');
  const std::string caster = variant.substr(0, dash);
  const std::string loop = dash == std::string::npos ? "" : variant.substr(dash + 1);
  if (!ParseIn(RayCasterNames, caster.c_str(), s.GpuRayCaster) ||
    (dash != std::string::npos && !ParseIn(RayLoopNames, loop.c_str(), s.GpuRayLoop)))
  {
    throw GpuError("'" + spec + "': a single-pass method's parameter is CASTER[-LOOP], CASTER " +
      WordsOf(RayCasterNames) + " and LOOP " + WordsOf(RayLoopNames) +
      " (e.g. packing:compute-flat)");
  }
  return s;
}

/// A single-pass method's renderer with data storage `storage`.
std::unique_ptr<GpuRenderer> MakeSinglePass(
  const std::string& spec, const MethodRequest& r, DataStorage storage)
{
  return std::unique_ptr<GpuRenderer>(
    new SinglePassRenderer(r.Data, SinglePassVariant(spec, r), r.View, storage, r.Access));
}

std::unique_ptr<GpuRenderer> MakePacking(const std::string& spec, const MethodRequest& r)
{
  return MakeSinglePass(spec, r, DataStorage::PackedAtlas);
}

std::unique_ptr<GpuRenderer> MakeBindless(const std::string& spec, const MethodRequest& r)
{
  // the mapper falls back to the atlas where bindless cannot run; the commands check
  // SinglePassRenderer::StorageUsed() after a frame
  return MakeSinglePass(spec, r, DataStorage::BindlessTextures);
}

std::unique_ptr<GpuRenderer> MakeLinear(const std::string& spec, const MethodRequest& r)
{
  return MakeSinglePass(spec, r, DataStorage::LinearBricks);
}

std::unique_ptr<GpuRenderer> MakeAutoStorage(const std::string& spec, const MethodRequest& r)
{
  return MakeSinglePass(spec, r, DataStorage::Auto);
}

std::unique_ptr<GpuRenderer> MakeMultipass(const std::string&, const MethodRequest& r)
{
  return std::unique_ptr<GpuRenderer>(new MultipassRenderer(r.Data, r.Settings, r.View));
}

/// uniform-gpu: the finest level; uniform-gpu:LEVEL that level.
std::unique_ptr<GpuRenderer> MakeUniform(const std::string& spec, const MethodRequest& r)
{
  const Hierarchy& h = r.Data;
  int level = h.NumberOfLevels() - 1;
  const std::string name = "uniform-gpu";
  if (spec != name)
  {
    const std::string l = spec.substr(name.size() + 1);
    if (l.empty() || l.size() > 3 || l.find_first_not_of("0123456789") != std::string::npos ||
      std::stoi(l) >= h.NumberOfLevels())
    {
      throw GpuError("uniform-gpu level '" + l + "' does not exist (levels 0.." +
        std::to_string(h.NumberOfLevels() - 1) + ")");
    }
    level = std::stoi(l);
  }
  return std::unique_ptr<GpuRenderer>(new UniformGpuRenderer(h, r.Settings, r.View, level));
}

/// vtk-amr-resample: the mapper's default sample count; :N N^3 samples; :finest two samples per
/// finest cell edge.
std::unique_ptr<GpuRenderer> MakeAmrResample(const std::string& spec, const MethodRequest& r)
{
  std::string why;
  if (!AmrResampleAvailable(why))
  {
    throw GpuError(why);
  }
#ifdef AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER
  const std::string name = "vtk-amr-resample";
  glm::ivec3 samples(0);
  if (spec == name + ":finest")
  {
    samples = glm::ivec3(-1);
  }
  else if (spec != name)
  {
    const std::string n = spec.substr(name.size() + 1);
    if (n.empty() || n.find_first_not_of("0123456789") != std::string::npos || n.size() > 4 ||
      std::stoi(n) < 2 || std::stoi(n) > 2048)
    {
      throw GpuError("vtk-amr-resample:N needs N in 2..2048 or 'finest', got '" + n + "'");
    }
    samples = glm::ivec3(std::stoi(n));
  }
  return std::unique_ptr<GpuRenderer>(new AmrResampleRenderer(r.Data, r.Settings, r.View, samples));
#else
  (void)spec;
  (void)r;
  return nullptr;
#endif
}

/// `text` split into lines of at most `width` columns (at spaces).
std::vector<std::string> Wrap(const std::string& text, std::size_t width)
{
  std::vector<std::string> lines(1);
  std::istringstream words(text);
  for (std::string word; words >> word;)
  {
    if (!lines.back().empty() && lines.back().size() + 1 + word.size() > width)
    {
      lines.emplace_back();
    }
    lines.back() += (lines.back().empty() ? "" : " ") + word;
  }
  return lines;
}

} // namespace

std::string Method::Syntax() const
{
  return Parameters.empty() ? Name : Name + "[" + Parameters + "]";
}

const std::vector<Method>& Methods()
{
  static const std::vector<Method> methods = {
    { "cpu-kdtree", "", MethodKind::CpuKdTree, false, RenderCommand | BenchCommand,
      { { "cpu-kdtree", "cpu-kdtree",
        "the CPU kD-tree integrator (amrsp::RenderKdTree): the traversal of the encoded tree "
        "textures that mirrors the GLSL shader, sampling the grids" } },
      nullptr },
    { "cpu-packing", "", MethodKind::CpuPacking, false, RenderCommand,
      { { "cpu-packing", "cpu-packing",
        "the same, sampling the packed atlas through the data nodes' offsets, as the packing "
        "shader does" } },
      nullptr },
    { "packing", ":CASTER[-LOOP]", MethodKind::Packing, true, RenderCommand | BenchCommand,
      { { "packing", "packing",
          "vtkSinglePassAMRVolumeMapper, packed atlas (the paper's single pass): one R32F atlas, "
          "offscreen vtkRenderWindow; needs an OpenGL context (under GLX an X display)" },
        { "packing:CASTER[-LOOP]", "",
          "any single-pass method (packing, bindless, linear, auto-storage) with the caster "
          "fragment, compute or auto and the ray loop nested, flat or auto instead of --caster "
          "and --loop, e.g. packing:compute-flat: several variants in one bench run" } },
      &MakePacking },
    { "bindless", ":CASTER[-LOOP]", MethodKind::Bindless, true, RenderCommand | BenchCommand,
      { { "bindless", "bindless",
        "vtkSinglePassAMRVolumeMapper, one texture per grid through bindless handles (needs "
        "GL_ARB_bindless_texture: --driver zink on a CPU); where the context lacks the "
        "extension, render uses the atlas and says so, bench reports an error" } },
      &MakeBindless },
    { "linear", ":CASTER[-LOOP]", MethodKind::Linear, true, RenderCommand | BenchCommand,
      { { "linear", "linear",
        "vtkSinglePassAMRVolumeMapper, the bricks back to back in 2D R32F textures (no packing; "
        "faster on CPU drivers such as llvmpipe); same display needs as packing" } },
      &MakeLinear },
    { "auto-storage", ":CASTER[-LOOP]", MethodKind::AutoStorage, true, RenderCommand | BenchCommand,
      { { "auto-storage", "", // not in bench's default list: it repeats one of the storages
        "vtkSinglePassAMRVolumeMapper with the data storage its AUTO_STORAGE takes in this "
        "context (the plugin's default Method): bindless where the GPU has it, else packing or, "
        "on CPU drivers and large data, linear; the result names the storage" } },
      &MakeAutoStorage },
    { "multipass", "", MethodKind::Multipass, true, RenderCommand | BenchCommand,
      { { "multipass", "multipass",
        "vtkMultiPassAMRVolumeMapper: one draw per kD-tree data node (paper §6), the paper's "
        "multi-pass baseline: the kD-tree ordered on the CPU, the draws blended front to back; "
        "same atlas and display needs as packing" } },
      &MakeMultipass },
    { "uniform-gpu", ":LEVEL", MethodKind::UniformGpu, true, BenchCommand,
      { { "uniform-gpu[:LEVEL]", "uniform-gpu",
        "vtkGPUVolumeRayCastMapper on one uniform resampling at the finest level (or LEVEL)" } },
      &MakeUniform },
    { "vtk-amr-resample", ":N|:finest", MethodKind::AmrResample, true, BenchCommand,
      { { "vtk-amr-resample[:N]", "vtk-amr-resample",
          "VTK's vtkAMRVolumeMapper (ParaView's VTK only) at its default 128^3 samples (or "
          "N^3)" },
        { "vtk-amr-resample:finest", "vtk-amr-resample:finest",
          "vtkAMRVolumeMapper at two samples per finest cell edge (where that fits)" } },
      &MakeAmrResample },
  };
  return methods;
}

const Method* FindMethod(const std::string& spec, unsigned command)
{
  for (const Method& m : Methods())
  {
    if (!(m.Commands & command))
    {
      continue;
    }
    if (spec == m.Name ||
      (!m.Parameters.empty() && spec.compare(0, m.Name.size() + 1, m.Name + ":") == 0))
    {
      return &m;
    }
  }
  return nullptr;
}

std::string MethodList(unsigned command)
{
  std::string list;
  for (const Method& m : Methods())
  {
    if (m.Commands & command)
    {
      list += (list.empty() ? "" : ", ") + m.Syntax();
    }
  }
  return list;
}

std::string DefaultBenchMethods()
{
  std::string list;
  for (const Method& m : Methods())
  {
    if (!(m.Commands & BenchCommand))
    {
      continue;
    }
    for (const MethodForm& f : m.Forms)
    {
      if (!f.Spec.empty())
      {
        list += (list.empty() ? "" : ",") + f.Spec;
      }
    }
  }
  return list;
}

void PrintMethodHelp(std::ostream& out, unsigned command)
{
  const std::size_t column = 27; // as the option lists: 2 spaces, the syntax padded to 25
  for (const Method& m : Methods())
  {
    if (!(m.Commands & command))
    {
      continue;
    }
    for (const MethodForm& f : m.Forms)
    {
      std::string head = "  " + f.Syntax;
      head += head.size() < column ? std::string(column - head.size(), ' ') : " ";
      bool first = true;
      for (const std::string& line : Wrap(f.Description, 100 - column))
      {
        out << (first ? head : std::string(column, ' ')) << line << "\n";
        first = false;
      }
    }
  }
}

std::unique_ptr<GpuRenderer> MakeGpuRenderer(
  const std::string& spec, unsigned command, const MethodRequest& r)
{
  const Method* m = FindMethod(spec, command);
  if (!m || !m->Make)
  {
    throw GpuError("'" + spec + "' is not a GPU method");
  }
  return m->Make(spec, r);
}

} // namespace tool
} // namespace amrsp
