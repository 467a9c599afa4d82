// SPDX-License-Identifier: BSD-3-Clause
// The Markdown tables of `amrsp bench`: Tables 1 and 2 next to the paper's figures, the
// interleaved rounds and the scaling table.
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspBench.h"

#include <algorithm>
#include <sstream>
#include <string>

namespace amrsp
{
namespace tool
{

using Json = BenchJson;

int PaperDataset(const Json& stats)
{
  const int64_t grids = stats.value("grids", int64_t(0));
  const int levels = stats.value("levels", 0);
  if (grids == 2666 && levels == 4)
  {
    return 1;
  }
  if (grids == 18528 && levels == 4)
  {
    return 2;
  }
  if (grids == 39061 && levels == 13)
  {
    return 3;
  }
  return 0;
}

namespace
{
// The paper's Table 1 (grids, levels, cells, kD nodes, kD data nodes) and Table 2 (GPU memory
// MB as tree + data, preprocessing s, fps on its GTX 680) for datasets 1-3.
struct PaperRow
{
  const char* Cells;
  long long KdNodes, KdDataNodes;
};
const PaperRow PaperTable1[3] = { { "19 × 10^6", 30096, 27249 }, { "33 × 10^6", 178114, 162095 },
  { "140 × 10^6", 368225, 343389 } };
struct PaperTiming
{
  const char* Method;
  const char* Memory[3];
  double Preprocess[3];
  double Fps[3];
};
const PaperTiming PaperTable2[3] = {
  { "multipass", { "71.4", "124.2", "530.3" }, { 1.1, 2.6, 6.8 }, { 4.2, 2.1, 0.8 } },
  { "packing", { "0.5 + 239.3", "2.7 + 310.3", "4.3 + 1000.2" }, { 3.4, 7.5, 8.1 },
    { 3.2, 1.6, 1.2 } },
  { "bindless", { "0.5 + 71.4", "2.8 + 124.2", "6.1 + 530.3" }, { 1.7, 3.2, 7.4 },
    { 2.1, 0.9, 0.4 } },
};

std::string Thousands(long long v)
{
  std::string d = std::to_string(v < 0 ? -v : v), out;
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    if (i > 0 && (d.size() - i) % 3 == 0)
    {
      out += ',';
    }
    out += d[i];
  }
  return (v < 0 ? "-" : "") + out;
}

std::string Mb(double bytes)
{
  return Fixed(bytes / 1.0e6, bytes < 1.0e5 ? 3 : 1);
}

/// Total preprocessing seconds of a method: the sum of its preprocess_s entries that are
/// separate steps (the mapper's build already contains tree, encode and pack).
double PreprocessTotal(const Json& r)
{
  const Json& p = r["preprocess_s"];
  if (p.contains("build"))
  {
    return p["build"].get<double>() + p.value("upload", 0.0);
  }
  double sum = 0.0;
  for (const auto& item : p.items())
  {
    sum += item.value().get<double>();
  }
  return sum;
}

std::string PreprocessDetail(const Json& r)
{
  std::string out;
  for (const auto& item : r["preprocess_s"].items())
  {
    out += (out.empty() ? "" : ", ") + item.key() + " " + Fixed(item.value().get<double>(), 3);
  }
  return out;
}
} // namespace

std::string RoundsMarkdown(const Json& methods)
{
  std::ostringstream md;
  std::size_t rounds = 0;
  for (const auto& item : methods.items())
  {
    if (item.value().contains("rounds_ms_mean"))
    {
      rounds = std::max(rounds, item.value()["rounds_ms_mean"].size());
    }
  }
  if (rounds < 2)
  {
    return "";
  }
  md << "\nInterleaved rounds (" << rounds
     << " orbits per method, the methods' order reversed every round; fps relative to packing = "
        "median over rounds of packing's ms/frame over the method's)\n\n"
     << "| method | ms/frame per round | median | fps relative to packing (min–max) |\n"
     << "|---|---|---|---|\n";
  for (const auto& item : methods.items())
  {
    const Json& r = item.value();
    if (!r.contains("rounds_ms_mean"))
    {
      continue;
    }
    md << "| " << item.key() << " | ";
    bool first = true;
    for (const Json& v : r["rounds_ms_mean"])
    {
      md << (first ? "" : ", ") << Fixed(v.get<double>(), 1);
      first = false;
    }
    md << " | " << Fixed(r["ms_rounds_median"].get<double>(), 1) << " | ";
    if (r.contains("fps_vs_packing"))
    {
      md << Fixed(r["fps_vs_packing"].get<double>(), 2) << " ("
         << Fixed(r["fps_vs_packing_range"][0].get<double>(), 2) << "–"
         << Fixed(r["fps_vs_packing_range"][1].get<double>(), 2) << ")";
    }
    else
    {
      md << "—";
    }
    md << (r.contains("rounds_error") ? " (stopped: " + r["rounds_error"].get<std::string>() + ")"
                                      : "")
       << " |\n";
  }
  return md.str();
}

std::string BenchMarkdown(const Json& bench)
{
  std::ostringstream md;
  const Json& st = bench["statistics"];
  const int paper = PaperDataset(st);
  md << "Dataset `" << bench["dataset"].get<std::string>() << "`, " << bench["image"][0] << "×"
     << bench["image"][1] << ", " << bench["frames"] << "-frame orbit";
  if (bench.contains("device") && !bench["device"].get<std::string>().empty())
  {
    md << ", " << bench["device"].get<std::string>();
  }
  if (bench.contains("backend"))
  {
    md << " through " << bench["backend"].get<std::string>();
  }
  if (bench.contains("vtk_version"))
  {
    md << " (VTK " << bench["vtk_version"].get<std::string>() << ", ParaView "
       << bench["paraview_version"].get<std::string>() << ")";
  }
  md << (paper ? ", the size of the paper's dataset " + std::to_string(paper) +
              " (the hierarchy is the project's synthetic one, not the paper's data)"
               : "")
     << ".\n\n";
  md << "Table 1 (dataset)\n\n"
     << "| | grids | levels | cells | kD nodes | kD data nodes |\n"
     << "|---|---|---|---|---|---|\n"
     << "| this dataset | " << Thousands(st["grids"].get<long long>()) << " | " << st["levels"]
     << " | " << Thousands(st["cells"].get<long long>()) << " | "
     << Thousands(st["kd_nodes"].get<long long>()) << " | "
     << Thousands(st["kd_data_nodes"].get<long long>()) << " |\n";
  if (paper)
  {
    const PaperRow& p = PaperTable1[paper - 1];
    md << "| paper, dataset " << paper << " | " << Thousands(st["grids"].get<long long>()) << " | "
       << st["levels"] << " | " << p.Cells << " | " << Thousands(p.KdNodes) << " | "
       << Thousands(p.KdDataNodes) << " |\n";
  }
  md << "\nTable 2 (per method; GPU memory in MB = 10^6 bytes, tree textures + data; "
        "preprocessing = the mapper's build + upload, or the resampling; RMSE of frame 0 against "
        "the CPU reference, 0-255)\n\n"
     << "| method | GPU memory [MB] | preprocessing [s] | fps | ms/frame (median) | RMSE | "
        "PSNR [dB] |";
  if (paper)
  {
    md << " paper: memory | paper: preprocessing | paper: fps |";
  }
  md << "\n|---|---|---|---|---|---|---|" << (paper ? "---|---|---|" : "") << "\n";
  for (const auto& item : bench["methods"].items())
  {
    const Json& r = item.value();
    const PaperTiming* pt = nullptr;
    for (const PaperTiming& t : PaperTable2)
    {
      if (item.key() == t.Method)
      {
        pt = &t;
      }
    }
    md << "| " << item.key() << " | ";
    if (r.contains("error"))
    {
      md << "cannot run: " << r["error"].get<std::string>() << " | | | | | |";
    }
    else
    {
      const double data = r["gpu_bytes"].get<double>();
      const double tree = r.value("gpu_bytes_tree", 0.0);
      md << (tree > 0 ? Mb(tree) + " + " + Mb(data - tree) : Mb(data)) << " | "
         << Fixed(PreprocessTotal(r), 3) << " (" << PreprocessDetail(r) << ") | "
         << Fixed(r["fps"].get<double>(), 2) << " | " << Fixed(r["ms_median"].get<double>(), 1)
         << " | "
         << (r.contains("rmse")
                ? Fixed(r["rmse"].get<double>(), 3) + " | " + Fixed(r["psnr"].get<double>(), 1)
                : std::string("— | —"))
         << " |";
    }
    if (paper)
    {
      if (pt)
      {
        md << " " << pt->Memory[paper - 1] << " | " << Fixed(pt->Preprocess[paper - 1], 1) << " | "
           << Fixed(pt->Fps[paper - 1], 1) << " |";
      }
      else
      {
        md << " — | — | — |";
      }
    }
    md << "\n";
  }
  if (paper)
  {
    md << "\nThe paper's figures: GTX 680, its own real cosmology data of that size (its image "
          "size is not stated).\n";
  }
  md << RoundsMarkdown(bench["methods"]) << InteractiveMarkdown(bench["methods"]);
  return md.str();
}

std::string ScalingMarkdownHeader(const std::string& size, int frames)
{
  std::ostringstream md;
  md << "Scaling (`synthetic:cosmo`, " << size << ", " << frames << " frames per method)\n\n"
     << "| grids | levels | cells | kD nodes | paper dataset | tree [s] | encode [s] | pack [s] | "
        "method | build [s] | upload [s] | first image [s] | ms/frame (mean) | GPU memory [MB] | "
        "peak RSS [MB] |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  return md.str();
}

std::string ScalingMarkdownRow(const Json& row)
{
  std::ostringstream md;
  if (row.contains("error"))
  {
    md << "| " << row["dataset"].get<std::string>()
       << " | | | | | | | | | cannot run: " << row["error"].get<std::string>() << " | | | | | |\n";
    return md.str();
  }
  const Json& st = row["statistics"];
  const int paper = PaperDataset(st);
  const std::string head = "| " + Thousands(st["grids"].get<long long>()) + " | " +
    st["levels"].dump() + " | " + Thousands(st["cells"].get<long long>()) + " | " +
    Thousands(st["kd_nodes"].get<long long>()) + " | " + (paper ? std::to_string(paper) : "—") +
    " | " + Fixed(st["times_s"]["tree"].get<double>(), 3) + " | " +
    Fixed(st["times_s"]["encode"].get<double>(), 3) + " | " +
    Fixed(st["times_s"]["pack"].get<double>(), 3) + " | ";
  for (const auto& item : row["methods"].items())
  {
    const Json& r = item.value();
    md << head << item.key() << " | ";
    if (r.contains("error"))
    {
      md << "cannot run: " << r["error"].get<std::string>() << " | | | | | |\n";
      continue;
    }
    const Json& p = r["preprocess_s"];
    md << (p.contains("build") ? Fixed(p["build"].get<double>(), 3) : "—") << " | "
       << (p.contains("upload") ? Fixed(p["upload"].get<double>(), 3) : "—") << " | "
       << (r.contains("time_to_first_image_s") ? Fixed(r["time_to_first_image_s"].get<double>(), 3)
                                               : "—")
       << " | " << Fixed(r["ms_mean"].get<double>(), 1) << " | " << Mb(r["gpu_bytes"].get<double>())
       << " | " << (r.contains("peak_rss_bytes") ? Mb(r["peak_rss_bytes"].get<double>()) : "—")
       << " |\n";
  }
  return md.str();
}

std::string ScalingMarkdown(const Json& scaling)
{
  std::string md = ScalingMarkdownHeader(
    scaling["image"][0].dump() + "×" + scaling["image"][1].dump(), scaling["frames"].get<int>());
  for (const Json& row : scaling["rows"])
  {
    md += ScalingMarkdownRow(row);
  }
  return md;
}

} // namespace tool
} // namespace amrsp
