// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `amrsp bench --counters`: the "work" object of every GPU method that renders the kD-tree: the
/// cost model of amrsp/WorkCounters.h, counted by the CPU mirror of the shader for frame 0 of the
/// orbit, and for the single-pass methods the GPU's own counts of the same frame beside it.

#include "AmrspJson.h"

#include "AmrspGpuRenderer.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/RenderSettings.h"
#include "amrsp/WorkCounters.h"

#include <map>
#include <memory>
#include <string>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

class BenchWork
{
public:
  /// The frame `s` (frame 0 of the orbit) of `h`; both must outlive this object. Nothing is
  /// counted until a method asks.
  BenchWork(const Hierarchy& h, const RenderSettings& s);
  ~BenchWork();

  /// The work of single-pass renderer `gpu` after its orbit, for the storage it rendered with:
  /// the CPU mirror's figures and, under "gpu", the shader's own totals of segments, descent
  /// steps and samples for the same frame and whether they agree with the mirror's (within 1 %
  /// and 2 per million rays: rays at the edges of nodes may fall differently).
  nlohmann::ordered_json SinglePass(GpuRenderer& gpu);
  /// The multi-pass baseline's work (from the mirror's traversal; no GPU counts).
  nlohmann::ordered_json Multipass();

private:
  const EncodedKdTree& Tree();
  const Hierarchy& H;
  RenderSettings S;
  std::unique_ptr<EncodedKdTree> Encoded;
  std::map<DataStorage, WorkSummary> SinglePassByStorage; // the mirror's, per storage
};

/// A WorkSummary as the JSON fields of a "work" object.
nlohmann::ordered_json WorkJson(const WorkSummary& w);

} // namespace tool
} // namespace amrsp
