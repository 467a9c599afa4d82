// SPDX-License-Identifier: BSD-3-Clause
// Every single-pass shader variant through glslangValidator (Debian's glslang-tools), without an
// OpenGL context: the sources are composed as the mapper composes them
// (vtkSinglePassAMRComposeShader, from the .glsl files of Shaders/), the fragment stage's //VTK::
// markers replaced as VTK's shader cache replaces them on a desktop OpenGL 3.2 core context.
//
// The variants: every combination of the caster (fragment, compute), the grid data (packing with
// 1, 2 and 4 atlas pages, bindless direct and waterfall, linear with 1 and 4 pages), the centring
// and the blend mode (5), without features in both ray loops, and in one loop (alternating) with
// every feature the combination allows (log transfer, opaque depth and a reduced image, uniform
// power-of-two refinement, empty-space skipping, smooth cells, ropes, shading and shadows, 13
// levels) and with a second mix of them; then each caster and grid data with each diagnostic
// output (the work counters, the three work counts, the two ablations). 644 variants. The
// composition does not depend on the VTK version: one configuration runs this test
// (docs/testing.md, "Coverage matrix"), once per CI run. Two deviations, both glslang 12's limits
// and said in the output: the bindless waterfall variants are checked as GLSL 4.50, fragment and
// compute (glslang declares GL_ARB_shader_ballot's functions from 4.50 only; Mesa and NVIDIA
// from 1.50, as the spec allows), and the occupancy probe (GL_NV_shader_thread_group, unknown to
// glslang) is not checked here: the GPU profile compiles it on NVIDIA.
//
// A variant that fails prints its defines and glslangValidator's first errors; the test also
// shows that a broken source is rejected (a type error added to the ray's code).
//
// usage: TestShaderVariants SHADER_DIR WORK_DIR
#include "MapperTestHelpers.h"
#include "vtkSinglePassAMRShaderVariant.h"

#include "vtkShaderProgram.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{
using Storage = amrsp::DataStorage;

std::string ReadFile(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error("cannot read " + path);
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The Shaders/ folder's sources, read once.
struct Sources
{
  explicit Sources(const std::string& dir)
  {
    for (std::size_t i = 0; i < Names.size(); ++i)
    {
      Text[i] = ReadFile(dir + "/" + Names[i]);
    }
  }
  vtkSinglePassAMRShaderSources Get() const
  {
    return { Text[0].c_str(), Text[1].c_str(), Text[2].c_str(), Text[3].c_str(), Text[4].c_str(),
      Text[5].c_str(), Text[6].c_str(), Text[7].c_str(), Text[8].c_str(), Text[9].c_str(),
      Text[10].c_str(), Text[11].c_str() };
  }
  static constexpr std::array<const char*, 12> Names = { "SinglePassAMR.frag.glsl",
    "SinglePassAMR.comp.glsl", "SinglePassAMRRay.glsl", "KdTreeLayout.glsl", "RayCommon.glsl",
    "BrickSample.glsl", "StoragePackedAtlas.glsl", "StorageBindless.glsl",
    "StorageLinearBricks.glsl", "SmoothCells.glsl", "Shading.glsl", "RaySteps.glsl" };
  std::array<std::string, 12> Text;
};

/// The source glslangValidator reads: the fragment stage's markers as VTK's shader cache fills
/// them (GLSL 1.50 on a 3.2 core context), GLSL 4.50 for the waterfall (see the top).
std::string StageSource(const vtkSinglePassAMRShaderVariant& v, const std::string& composed)
{
  std::string source = composed;
  if (v.Caster == amrsp::RayCaster::Fragment)
  {
    const bool waterfall = v.Storage == Storage::BindlessTextures && v.Waterfall;
    vtkShaderProgram::Substitute(
      source, "//VTK::System::Dec", waterfall ? "#version 450 core" : "#version 150");
    vtkShaderProgram::Substitute(source, "//VTK::Output::Dec", "out vec4 fragOutput0;");
    vtkShaderProgram::Substitute(source, "gl_FragData[0]", "fragOutput0");
  }
  else if (v.Storage == Storage::BindlessTextures && v.Waterfall)
  {
    vtkShaderProgram::Substitute(source, "#version 430 core", "#version 450 core");
  }
  return source;
}

/// glslangValidator on a batch of files in one process (one start-up instead of one per file;
/// without -l each file is compiled and linked on its own). The output names each file on a line
/// of its own, followed by that file's messages. Returns, per file, its messages when they hold an
/// ERROR, else "". A file the output does not name, or an exit status that disagrees with the
/// messages (non-zero exactly when some file has an ERROR), fails every file of the batch with the
/// whole output.
std::vector<std::string> Validate(const std::vector<std::string>& batch)
{
  std::string command = "glslangValidator";
  for (const std::string& path : batch)
  {
    command += " '" + path + "'";
  }
  command += " 2>&1";
  std::string output;
  int status = -1;
  if (FILE* pipe = popen(command.c_str(), "r"))
  {
    std::array<char, 4096> buffer;
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
    {
      output.append(buffer.data(), n);
    }
    status = pclose(pipe);
  }
  std::vector<std::string> messages(batch.size());
  std::vector<bool> named(batch.size(), false);
  std::size_t current = batch.size();
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);)
  {
    const auto path = std::find(batch.begin(), batch.end(), line);
    if (path != batch.end())
    {
      current = static_cast<std::size_t>(path - batch.begin());
      named[current] = true;
    }
    else if (current < batch.size())
    {
      messages[current] += line + "\n";
    }
  }
  std::vector<std::string> errors(batch.size());
  bool anyError = false;
  bool allNamed = true;
  for (std::size_t i = 0; i < batch.size(); ++i)
  {
    allNamed = allNamed && named[i];
    if (messages[i].find("ERROR") != std::string::npos)
    {
      errors[i] = messages[i];
      anyError = true;
    }
  }
  if (!allNamed || (status != 0) != anyError)
  {
    const std::string why = "glslangValidator (exit status " + std::to_string(status) + ") named " +
      (allNamed ? "every file" : "not every file") + " of its batch, " +
      (anyError ? "with" : "without") + " an ERROR:\n" +
      (output.empty() ? std::string("no output") : output.substr(0, 1500));
    std::fill(errors.begin(), errors.end(), why);
  }
  return errors;
}

/// Every variant of the test (see the top).
std::vector<vtkSinglePassAMRShaderVariant> Variants()
{
  std::vector<vtkSinglePassAMRShaderVariant> grid;
  for (amrsp::RayCaster caster : { amrsp::RayCaster::Fragment, amrsp::RayCaster::Compute })
  {
    const auto add = [&](Storage storage, int pages, bool waterfall)
    {
      vtkSinglePassAMRShaderVariant v;
      v.Caster = caster;
      v.Storage = storage;
      v.AtlasPages = storage == Storage::PackedAtlas ? pages : 1;
      v.LinearPages = storage == Storage::LinearBricks ? pages : 1;
      v.Waterfall = waterfall;
      grid.push_back(v);
    };
    add(Storage::PackedAtlas, 1, false);
    add(Storage::PackedAtlas, 2, false);
    add(Storage::PackedAtlas, 4, false);
    add(Storage::BindlessTextures, 1, false);
    add(Storage::BindlessTextures, 1, true);
    add(Storage::LinearBricks, 1, false);
    add(Storage::LinearBricks, 4, false);
  }
  std::vector<vtkSinglePassAMRShaderVariant> all;
  for (const vtkSinglePassAMRShaderVariant& base : grid)
  {
    for (bool vertex : { false, true })
    {
      for (int blend = 0; blend <= 4; ++blend)
      {
        // both loops over the blend modes and centrings: each loop meets each of them twice
        for (bool flat : { (blend + vertex) % 2 == 0 })
        {
          vtkSinglePassAMRShaderVariant v = base;
          v.VertexCentred = vertex;
          v.Blend = static_cast<amrsp::BlendMode>(blend);
          v.FlatLoop = flat;
          v.LevelCount = 3;
          all.push_back(v); // no feature
          vtkSinglePassAMRShaderVariant otherLoop = v;
          otherLoop.FlatLoop = !flat;
          all.push_back(otherLoop);
          const bool lit = blend == 0 || blend == 4;
          vtkSinglePassAMRShaderVariant every = v;
          every.LevelCount = 13;
          every.LogTransfer = true;
          every.UseDepth = true;
          every.ReducedImage = true;
          every.PowerOfTwoRefinement = true;
          every.UniformRefinementLog2 = 1;
          every.SkipEmpty = blend == 0;
          every.SmoothCells = !vertex;
          every.Ropes = true;
          every.Shade = lit;
          every.Shadows = lit;
          all.push_back(every);
          vtkSinglePassAMRShaderVariant mix = v;
          mix.LevelCount = 1;
          mix.UseDepth = true;
          mix.PowerOfTwoRefinement = true;
          mix.Ropes = true;
          mix.Shade = lit && !flat;
          mix.Shadows = lit && flat;
          mix.SmoothCells = !vertex && flat;
          all.push_back(mix);
        }
      }
    }
    for (int diagnostic = 0; diagnostic < 6; ++diagnostic)
    {
      vtkSinglePassAMRShaderVariant v = base;
      v.LevelCount = 4;
      v.PowerOfTwoRefinement = true;
      v.UniformRefinementLog2 = 1;
      v.Ropes = true;
      v.SkipEmpty = true;
      v.AccelerationCounts = diagnostic == 0;
      v.LoopCount = diagnostic >= 1 && diagnostic <= 3 ? diagnostic : 0;
      v.Ablation = diagnostic >= 4 ? diagnostic - 3 : 0;
      all.push_back(v);
    }
  }
  return all;
}

int Run(const std::string& shaderDir, const std::string& work)
{
  if (std::system("glslangValidator --version >/dev/null 2>&1") != 0)
  {
    return mappertest::SkipOrFail(
      "glslangValidator is not installed (Debian's glslang-tools; scripts/install-deps.sh)");
  }
  std::filesystem::remove_all(work); // no variant of an earlier run
  std::filesystem::create_directories(work);
  const Sources files(shaderDir);
  const vtkSinglePassAMRShaderSources sources = files.Get();
  const std::string version = "#version 430 core\n"; // the mapper's on OpenGL 4.3
  const std::vector<vtkSinglePassAMRShaderVariant> variants = Variants();
  // write every variant, then run the validator on them on every core
  std::vector<std::string> paths(variants.size()), errors(variants.size());
  for (std::size_t i = 0; i < variants.size(); ++i)
  {
    const vtkSinglePassAMRShaderVariant& v = variants[i];
    const bool compute = v.Caster == amrsp::RayCaster::Compute;
    paths[i] = work + "/variant-" + std::to_string(i) + (compute ? ".comp" : ".frag");
    std::ofstream(paths[i]) << StageSource(
      v, vtkSinglePassAMRComposeShader(v, sources, version, nullptr));
  }
  // batches of 16 files, taken in turn by one worker per core
  constexpr std::size_t batchSize = 16;
  std::atomic<std::size_t> next{ 0 };
  std::vector<std::thread> workers;
  for (unsigned w = 0; w < std::max(1u, std::thread::hardware_concurrency()); ++w)
  {
    workers.emplace_back(
      [&]
      {
        for (std::size_t first; (first = batchSize * next++) < paths.size();)
        {
          const std::size_t end = std::min(paths.size(), first + batchSize);
          const std::vector<std::string> batch(paths.begin() + first, paths.begin() + end);
          const std::vector<std::string> batchErrors = Validate(batch);
          std::copy(batchErrors.begin(), batchErrors.end(), errors.begin() + first);
        }
      });
  }
  for (std::thread& worker : workers)
  {
    worker.join();
  }
  int failed = 0;
  const int checked = static_cast<int>(variants.size());
  for (std::size_t i = 0; i < variants.size(); ++i)
  {
    if (!errors[i].empty() && ++failed <= 5)
    {
      std::cout << "  FAILED  " << paths[i] << ":\n"
                << variants[i].Defines() << errors[i].substr(0, 1500) << "\n";
    }
  }
  mappertest::Check(failed == 0,
    std::to_string(checked - failed) + " of " + std::to_string(checked) +
      " variants compile (glslangValidator); not checked here: the occupancy probe "
      "(GL_NV_shader_thread_group is unknown to glslang), compiled on NVIDIA by the GPU "
      "profile; the bindless waterfall checked as GLSL 4.50 (glslang 12 declares "
      "GL_ARB_shader_ballot from 4.50)");
  // the check rejects a broken source: a type error in the ray's code
  vtkSinglePassAMRShaderVariant broken = variants.front();
  std::string ray = files.Text[2];
  vtkShaderProgram::Substitute(ray, "  result = vec4(0.0);\n", "  result = 0.0;\n", false);
  vtkSinglePassAMRShaderSources brokenSources = sources;
  brokenSources.Ray = ray.c_str();
  const std::string brokenPath = work + "/broken.frag";
  std::ofstream(brokenPath) << StageSource(
    broken, vtkSinglePassAMRComposeShader(broken, brokenSources, version, nullptr));
  // in a batch between two good variants: the error is the broken file's alone
  const std::vector<std::string> mixed = Validate({ paths.front(), brokenPath, paths.back() });
  const std::string& brokenErrors = mixed[1];
  mappertest::Check(!brokenErrors.empty() && mixed[0].empty() && mixed[2].empty(),
    "a ray source with a type error (vec4 = float) is rejected, and in a batch between two good "
    "variants only it is: " +
      brokenErrors.substr(0, brokenErrors.find('\n', brokenErrors.find("ERROR"))));
  std::cout << (mappertest::Failures() == 0
                   ? "PASSED"
                   : "FAILED: " + std::to_string(mappertest::Failures()) + " check(s)")
            << "\n";
  return mappertest::Failures() == 0 ? 0 : 1;
}

} // namespace

int main(int argc, char* argv[])
{
  if (argc != 3)
  {
    std::cerr << "usage: TestShaderVariants SHADER_DIR WORK_DIR\n";
    return 2;
  }
  try
  {
    return Run(argv[1], argv[2]);
  }
  catch (const std::exception& e)
  {
    std::cout << "FAILED: " << e.what() << "\n";
    return 1;
  }
}
