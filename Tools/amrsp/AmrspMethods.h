// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The rendering methods of the amrsp tool, in one registry: what `render --method` and
/// `bench --methods` accept, what their help texts list, and how a GPU method's renderer is made.
/// A method is a name, optionally followed by ":PARAMETER" (uniform-gpu:LEVEL,
/// vtk-amr-resample:N); the CPU methods are run by the commands on the core's integrators.

#include "AmrspGpuRenderer.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/RenderSettings.h"

#include "amrsp/DataStorage.h"

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

/// The commands a method is offered by (bit flags).
enum MethodCommands : unsigned
{
  RenderCommand = 1u,
  BenchCommand = 2u
};

/// What the commands need to tell the methods apart.
enum class MethodKind
{
  CpuKdTree,   ///< amrsp::RenderKdTree on the grids
  CpuPacking,  ///< amrsp::RenderKdTree through the packed atlas
  Packing,     ///< vtkSinglePassAMRVolumeMapper with the packed atlas
  Bindless,    ///< vtkSinglePassAMRVolumeMapper with one texture per brick
  Linear,      ///< vtkSinglePassAMRVolumeMapper with the bricks back to back in 2D pages
  AutoStorage, ///< vtkSinglePassAMRVolumeMapper with the storage its AUTO_STORAGE takes
  Multipass,   ///< vtkMultiPassAMRVolumeMapper
  UniformGpu,  ///< vtkGPUVolumeRayCastMapper on a uniform resampling
  AmrResample  ///< VTK's vtkAMRVolumeMapper
};

/// What a GPU method's renderer is made from.
struct MethodRequest
{
  const Hierarchy& Data;
  const RenderSettings& Settings;
  ViewAngles View;
  /// vtkSinglePassAMRVolumeMapper's bindless access.
  amrsp::BindlessAccess Access = amrsp::BindlessAccess::Auto;
};

/// One line of a method's help: how it is written and what it does.
struct MethodForm
{
  std::string Syntax; ///< "uniform-gpu[:LEVEL]", "vtk-amr-resample:finest"
  /// The method as written in the default list of `bench --methods` (empty: not in it).
  std::string Spec;
  std::string Description; ///< one line
};

struct Method
{
  std::string Name;       ///< "packing"; with a parameter the name before ':'
  std::string Parameters; ///< "" (none), ":LEVEL", ":N|:finest"
  MethodKind Kind;
  bool NeedsGpu;     ///< renders through an OpenGL context (GpuRenderer)
  unsigned Commands; ///< MethodCommands
  std::vector<MethodForm> Forms;
  /// The renderer of a GPU method for `spec` (the name and its parameter); nullptr for the CPU
  /// methods. Throws GpuError when it cannot render here or the parameter is bad.
  std::unique_ptr<GpuRenderer> (*Make)(const std::string& spec, const MethodRequest& r);

  /// "uniform-gpu[:LEVEL]": the name with its parameters, as lists show it.
  std::string Syntax() const;
  bool IsKdTreeMapper() const
  {
    return Kind == MethodKind::Packing || Kind == MethodKind::Bindless ||
      Kind == MethodKind::Linear || Kind == MethodKind::AutoStorage ||
      Kind == MethodKind::Multipass;
  }
};

/// Every method, in the order the help texts and the error messages list them.
const std::vector<Method>& Methods();

/// The method `spec` names ("name" or, where it takes one, "name:parameter") among those of
/// `command`; nullptr when there is none.
const Method* FindMethod(const std::string& spec, unsigned command);

/// The methods of `command` as a list "cpu-kdtree, cpu-packing, ..." (parameters shown).
std::string MethodList(unsigned command);

/// The methods `amrsp bench` runs when --methods is not given, comma-separated.
std::string DefaultBenchMethods();

/// The help lines of the methods of `command`: "  SYNTAX   description", wrapped at 100 columns.
void PrintMethodHelp(std::ostream& out, unsigned command);

/// The renderer of the GPU method `spec` of `command`; throws GpuError for a CPU method or an
/// unknown one.
std::unique_ptr<GpuRenderer> MakeGpuRenderer(
  const std::string& spec, unsigned command, const MethodRequest& r);

} // namespace tool
} // namespace amrsp
