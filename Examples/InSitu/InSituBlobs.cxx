// SPDX-License-Identifier: BSD-3-Clause
// The in-situ example: a BlobSimulation on every MPI rank, each step handed to ParaView Catalyst
// (CatalystAdaptor), whose Python script renders it with "AMR Single-Pass Volume".
//
//   mpiexec -np 2 amrsp_insitu_blobs --steps 6 --output DIR
//       [--script blobs_volume.py] [--plugin SinglePassAMRPlugin.so] [--levels 3]
//       [--base-cells 32] [--regrid 3] [--size 256x256] [--write-data] [--json costs.json]
//
// Rank 0 prints one line per step and, with --json, writes what each step cost: the
// simulation's own work, describing the step to Catalyst, Catalyst's CoProcess (the slowest
// rank's), the values handed over without a copy, and the largest resident memory of a rank.
// --write-data (one rank only) also writes each step's hierarchy as DIR/step_NNNN.vthb and the
// script's view as DIR/view.json, for `amrsp reference --view-json`.
#include "BlobSimulation.h"
#include "CatalystAdaptor.h"
#include "ReferenceHierarchy.h"

#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#ifndef INSITU_DEFAULT_SCRIPT
#define INSITU_DEFAULT_SCRIPT ""
#endif
#ifndef INSITU_DEFAULT_PLUGIN
#define INSITU_DEFAULT_PLUGIN ""
#endif

namespace
{

struct Options
{
  int Steps = 6;
  std::string Script = INSITU_DEFAULT_SCRIPT;
  std::string Plugin = INSITU_DEFAULT_PLUGIN;
  std::string Output = ".";
  std::string Json;
  std::string ImageSize = "256 256";
  bool WriteData = false;
  insitu::SimulationConfig Simulation;
};

Options Parse(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&]() -> std::string
    {
      if (i + 1 >= argc)
      {
        throw std::invalid_argument(a + " needs a value");
      }
      return argv[++i];
    };
    if (a == "--steps")
      o.Steps = std::stoi(value());
    else if (a == "--script")
      o.Script = value();
    else if (a == "--plugin")
      o.Plugin = value();
    else if (a == "--output")
      o.Output = value();
    else if (a == "--json")
      o.Json = value();
    else if (a == "--size")
    {
      std::string size = value();
      const std::size_t x = size.find('x');
      if (x == std::string::npos)
      {
        throw std::invalid_argument("--size takes WxH, e.g. 256x256");
      }
      o.ImageSize = size.substr(0, x) + " " + size.substr(x + 1);
    }
    else if (a == "--write-data")
      o.WriteData = true;
    else if (a == "--levels")
      o.Simulation.Levels = std::stoi(value());
    else if (a == "--base-cells")
      o.Simulation.BaseCells = std::stoi(value());
    else if (a == "--regrid")
      o.Simulation.RegridInterval = std::stoi(value());
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (o.Steps < 1 || o.Script.empty())
  {
    throw std::invalid_argument("--steps must be at least 1 and --script must name a script");
  }
  return o;
}

/// This process's resident memory, in bytes (Linux /proc/self/statm).
long long ResidentBytes()
{
  std::ifstream statm("/proc/self/statm");
  long long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<long long>(sysconf(_SC_PAGESIZE));
}

/// What one step cost, gathered on rank 0.
struct StepRecord
{
  int Step;
  double Time;
  int Levels;
  int Blocks;
  long long Cells;
  bool Regridded;
  double SimulateSeconds;   ///< slowest rank
  double DescribeSeconds;   ///< slowest rank
  double CoProcessSeconds;  ///< slowest rank
  long long BorrowedValues; ///< all ranks
  long long ResidentBytes;  ///< largest rank
};

void WriteJson(
  const std::string& path, const Options& o, int ranks, const std::vector<StepRecord>& steps)
{
  std::ofstream out(path);
  out << "{\n  \"ranks\": " << ranks << ",\n  \"base_cells\": " << o.Simulation.BaseCells
      << ",\n  \"levels\": " << o.Simulation.Levels
      << ",\n  \"regrid_interval\": " << o.Simulation.RegridInterval << ",\n  \"steps\": [\n";
  for (std::size_t i = 0; i < steps.size(); ++i)
  {
    const StepRecord& s = steps[i];
    out << "    {\"step\": " << s.Step << ", \"time\": " << s.Time << ", \"levels\": " << s.Levels
        << ", \"blocks\": " << s.Blocks << ", \"cells\": " << s.Cells
        << ", \"regridded\": " << (s.Regridded ? "true" : "false")
        << ", \"simulate_s\": " << s.SimulateSeconds << ", \"describe_s\": " << s.DescribeSeconds
        << ", \"coprocess_s\": " << s.CoProcessSeconds
        << ", \"borrowed_values\": " << s.BorrowedValues
        << ", \"resident_bytes\": " << s.ResidentBytes << "}" << (i + 1 < steps.size() ? "," : "")
        << "\n";
  }
  out << "  ]\n}\n";
}

std::string StepFile(const std::string& folder, int step, const char* extension)
{
  char name[64];
  std::snprintf(name, sizeof(name), "/step_%04d.%s", step, extension);
  return folder + name;
}

} // namespace

int main(int argc, char* argv[])
{
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int status = 0;
  try
  {
    const Options o = Parse(argc, argv);
    if (o.WriteData && ranks > 1)
    {
      throw std::invalid_argument("--write-data writes the hierarchy from one rank only");
    }
    insitu::BlobSimulation simulation(o.Simulation, rank, ranks);
    insitu::CatalystAdaptor catalyst(o.Script, o.Plugin,
      { { "OutputDirectory", o.Output }, { "ImageSize", o.ImageSize },
        { "WriteViewJson", o.WriteData ? "1" : "0" } });
    std::vector<StepRecord> records;
    for (int step = 0; step < o.Steps; ++step)
    {
      auto start = std::chrono::steady_clock::now();
      if (step > 0)
      {
        simulation.Step();
      }
      const double simulate =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      insitu::CatalystAdaptor::StepCost cost = catalyst.CoProcess(simulation);
      if (o.WriteData)
      {
        // the test's reference data, written apart from the adaptor (ReferenceHierarchy.h)
        insitu::WriteReferenceHierarchy(simulation, StepFile(o.Output, step, "vthb"));
      }
      double local[3] = { simulate, cost.DescribeSeconds, cost.CoProcessSeconds };
      double slowest[3];
      MPI_Reduce(local, slowest, 3, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
      long long borrowed = cost.BorrowedValues, allBorrowed = 0;
      MPI_Reduce(&borrowed, &allBorrowed, 1, MPI_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
      long long resident = ResidentBytes(), largest = 0;
      MPI_Reduce(&resident, &largest, 1, MPI_LONG_LONG, MPI_MAX, 0, MPI_COMM_WORLD);
      if (rank != 0)
      {
        continue;
      }
      StepRecord r{ step, simulation.Time(), 0, 0, 0, simulation.RegriddedLastStep(), slowest[0],
        slowest[1], slowest[2], allBorrowed, largest };
      for (const insitu::Block& b : simulation.Blocks())
      {
        r.Levels = std::max(r.Levels, b.Level + 1);
        ++r.Blocks;
        r.Cells += static_cast<long long>(b.Cells[0]) * b.Cells[1] * b.Cells[2];
      }
      records.push_back(r);
      std::cout << "step " << step << ": t " << r.Time << ", " << r.Levels << " levels, "
                << r.Blocks << " blocks, " << r.Cells << " cells"
                << (r.Regridded ? " (regridded)" : "") << "; simulate " << r.SimulateSeconds
                << " s, describe " << r.DescribeSeconds << " s, Catalyst " << r.CoProcessSeconds
                << " s, " << r.BorrowedValues << " values borrowed, " << r.ResidentBytes / 1048576
                << " MiB resident" << (cost.Processed ? "" : " (not processed)") << std::endl;
    }
    if (rank == 0 && !o.Json.empty())
    {
      WriteJson(o.Json, o, ranks, records);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "amrsp_insitu_blobs (rank " << rank << "): " << e.what() << std::endl;
    status = 1;
  }
  int worst = 0;
  MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
