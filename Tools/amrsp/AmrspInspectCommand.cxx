// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspCommandShared.h"

#include "AmrspSinglePass.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/Invariants.h"
#include "amrsp/KdTree.h"
#include "amrsp/VertexData.h"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

namespace
{
/// The layout of every packer for `extents` (inspect --compare-packers), with its seconds.
Json CompareBrickPackers(const std::vector<glm::ivec3>& extents, const AtlasRequest& request)
{
  Json byPacker = Json::object();
  for (Packer p : { Packer::NextFitDecreasingHeight, Packer::Best })
  {
    try
    {
      const AtlasLayout layout = PackBricks(
        extents, p, request.MaxDims, static_cast<int64_t>(request.MaxBytes / AtlasTexelBytes));
      byPacker[PackerName(p)] = AtlasJson(layout);
      byPacker[PackerName(p)]["seconds"] = layout.Seconds;
    }
    catch (const PackingError& e)
    {
      byPacker[PackerName(p)] = Json{ { "error", e.what() } };
    }
  }
  return byPacker;
}

/// The paper's Table 2 "GPU memory" in bytes: tree textures + grid data, for either storage
/// (packing: null when `atlas` could not be packed).
Json GpuBytesJson(
  const EncodedKdTree& enc, const std::vector<glm::ivec3>& extents, const Json& atlas)
{
  const std::size_t treeBytes = KdTreeTextureBytes(enc.Tree, enc.DataNodes);
  std::size_t brickBytes = 0;
  for (const glm::ivec3& e : extents)
  {
    brickBytes += static_cast<std::size_t>(e.x) * e.y * e.z * AtlasTexelBytes;
  }
  Json memory;
  memory["tree"] = treeBytes;
  if (atlas.contains("total_texels"))
  {
    memory["packing"] = treeBytes + atlas["total_texels"].get<std::size_t>() * AtlasTexelBytes;
  }
  else
  {
    memory["packing"] = nullptr;
  }
  memory["bindless"] = treeBytes + brickBytes + HandleTextureBytes(extents.size());
  return memory;
}

/// inspect's text form of its JSON object `j`.
void PrintInspectText(
  const Json& j, const LoadedDataset& d, const KdTreeStatistics& st, const InvariantReport& inv)
{
  const Hierarchy& h = d.Data;
  const Json& times = j["times_s"];
  const double kdSeconds = times["kdtree"], encodeSeconds = times["encode"],
               packSeconds = times["pack"];
  const Json& atlas = j["atlas"];
  std::cout << "dataset      " << d.Spec << " (" << d.Format << "), array "
            << (h.ArrayName.empty() ? "-" : h.ArrayName) << "\n"
            << "levels       " << h.NumberOfLevels() << "\n"
            << "grids        " << h.Grids.size() << " per level " << j["grids_per_level"].dump()
            << "\n"
            << "cells        " << h.TotalCells() << "\n"
            << "bounds       " << j["bounds"].dump() << "\n"
            << "kD nodes     " << st.Nodes << " (data nodes " << st.DataNodes << "; types a "
            << st.Refined << ", b " << st.Leaves << ", c " << st.Mixed << ", empty " << st.Empty
            << "; depth " << st.Depth << ")\n"
            << "textures     tree " << j["tree_texture"].dump() << ", data nodes "
            << j["data_nodes_texture"].dump() << "\n"
            << "atlas        " << atlas.dump() << "\n"
            << "GPU memory   " << j["gpu_bytes"].dump()
            << " (bytes: tree textures + grid data, per storage)\n"
            << "times (s)    load " << d.LoadSeconds << ", kD-tree " << kdSeconds << ", encode "
            << encodeSeconds << ", pack " << packSeconds << "\n"
            << "invariants   " << (inv.Ok ? "ok" : "FAILED") << "\n";
  for (const std::string& f : inv.Failures)
  {
    std::cout << "  " << f << "\n";
  }
}

} // namespace

int RunInspect(int argc, char** argv)
{
  const char* help =
    "usage: amrsp inspect [DATASET] [--json] [--array NAME] [--packer P] [--compare-packers]\n"
    "Loads the hierarchy, builds and encodes the kD-tree, checks its invariants, packs the\n"
    "bricks (layout only, no data copied) and prints the statistics (with --json: one JSON\n"
    "object; docs/command-line.md lists the fields). --compare-packers adds the layout of every "
    "packer.\n";
  try
  {
    const Arguments a = ParseArguments(argc, argv, 1, Concat({ DatasetOptions, AtlasOptions }),
      Concat({ DatasetFlags, { "json", "compare-packers" } }));
    if (WantsHelp(a))
    {
      std::cout << help << AtlasHelp << DatasetHelp;
      return 0;
    }
    const AtlasRequest atlasRequest = ParseAtlasRequest(a);
    LoadedDataset d = Load(a, false, false);
    const Hierarchy& h = d.Data;

    auto t0 = Clock::now();
    const KdTree tree = BuildKdTree(h);
    const double kdSeconds = Seconds(t0);
    t0 = Clock::now();
    const EncodedKdTree enc = EncodeKdTree(h, tree);
    const double encodeSeconds = Seconds(t0);
    const InvariantReport inv = CheckKdTree(h, tree, &enc);
    const KdTreeStatistics st = tree.Statistics();
    const bool vertexBricks = h.VertexCentred || a.Get("centering", "auto") == "vertex";
    const std::vector<glm::ivec3> extents = BrickExtents(h, vertexBricks);
    Json atlas, byPacker = Json::object();
    double packSeconds = 0.0;
    try
    {
      const AtlasLayout layout = PackBricks(extents, atlasRequest.Algorithm, atlasRequest.MaxDims,
        static_cast<int64_t>(atlasRequest.MaxBytes / AtlasTexelBytes));
      atlas = AtlasJson(layout);
      packSeconds = layout.Seconds;
    }
    catch (const PackingError& e)
    {
      atlas = Json{ { "error", e.what() } };
    }
    if (a.Has("compare-packers"))
    {
      byPacker = CompareBrickPackers(extents, atlasRequest);
    }

    std::vector<int64_t> perLevel(static_cast<std::size_t>(h.NumberOfLevels()), 0);
    for (const Grid& g : h.Grids)
    {
      ++perLevel[g.Level];
    }
    Json ratios = Json::array();
    for (int l = 1; l < h.NumberOfLevels(); ++l)
    {
      const glm::ivec3 r = h.RefinementRatio[l];
      ratios.push_back({ r.x, r.y, r.z });
    }
    glm::dvec3 lo, hi;
    Bounds(h, lo, hi);
    Json j;
    j["dataset"] = d.Spec;
    j["format"] = d.Format;
    j["array"] = h.ArrayName;
    j["levels"] = h.NumberOfLevels();
    j["grids"] = h.Grids.size();
    j["grids_per_level"] = perLevel;
    j["cells"] = h.TotalCells();
    j["bounds"] = BoxJson(lo, hi);
    j["origin"] = { h.Origin.x, h.Origin.y, h.Origin.z };
    j["spacing0"] = { h.Spacing0.x, h.Spacing0.y, h.Spacing0.z };
    j["refinement_ratios"] = ratios;
    j["kd_nodes"] = st.Nodes;
    j["kd_data_nodes"] = st.DataNodes;
    j["node_types"] = { { "a", st.Refined }, { "b", st.Leaves }, { "c", st.Mixed },
      { "empty", st.Empty } };
    j["kd_depth"] = st.Depth;
    j["tree_texture"] = TextureJson(enc.Tree);
    j["data_nodes_texture"] = TextureJson(enc.DataNodes);
    j["centering"] = vertexBricks ? "vertex" : "cell";
    j["atlas"] = atlas;
    j["gpu_bytes"] = GpuBytesJson(enc, extents, atlas);
    if (a.Has("compare-packers"))
    {
      j["atlas_by_packer"] = byPacker;
    }
    j["times_s"] = { { "load", d.LoadSeconds }, { "kdtree", kdSeconds },
      { "encode", encodeSeconds }, { "pack", packSeconds } };
    j["invariants"] = { { "ok", inv.Ok }, { "failure_count", inv.FailureCount },
      { "failures", inv.Failures } };

    if (a.Has("json"))
    {
      std::cout << j.dump(2) << "\n";
    }
    else
    {
      PrintInspectText(j, d, st, inv);
    }
    return inv.Ok ? 0 : 3;
  }
  catch (const UsageError& e)
  {
    return Fail(e.Message + " (see amrsp inspect --help)");
  }
  catch (const std::exception& e)
  {
    return Fail(e);
  }
}
} // namespace tool
} // namespace amrsp
