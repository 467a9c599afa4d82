// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspDataset.h"

#include "AmrspFileChecks.h"
#include "AmrspIsolatedRead.h"
#include "AmrspProgress.h"

#include "amrsp/SyntheticCosmo.h"
#include "amrsp/TextCase.h"
#include "amrsp/VertexData.h"
#include "vtkAMRMapperConversion.h"

#include "vtkAMRBaseReader.h"
#include "vtkAMREnzoReader.h"
#include "vtkAMRGaussianPulseSource.h"
#include "vtkAMReXGridReader.h"
#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkPointData.h"
#include "vtkSinglePassAMRCosmoSource.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"
#include "vtkAMRBox.h"
#include "vtkAMRUtilities.h"
#include "vtkSinglePassAMRDataModel.h"
#include "vtkImageData.h"
#include "vtkUniformGrid.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLUniformGridAMRReader.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <new>
#include <set>
#include <sstream>
#include <thread>
#include <unistd.h>

namespace amrsp
{
namespace harness
{
namespace
{

/// Collects VTK's error and warning text instead of printing it, so that a failing reader
/// becomes one line of ours that quotes the reader's first message.
class CollectingOutputWindow : public vtkOutputWindow
{
public:
  static CollectingOutputWindow* New();
  vtkTypeMacro(CollectingOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override
  {
    if (text && First.empty())
    {
      std::string t(text);
      // VTK prefixes "ERROR: In file, line N\nclass (address): message": keep the message
      const std::size_t colon = t.find("): ");
      First = colon != std::string::npos ? t.substr(colon + 3) : t;
      while (!First.empty() && (First.back() == '\n' || First.back() == ' '))
      {
        First.pop_back();
      }
      for (char& c : First)
      {
        c = c == '\n' ? ' ' : c;
      }
    }
  }
  std::string First;
};
vtkStandardNewMacro(CollectingOutputWindow);

/// Installs the collector for the lifetime of this object.
class CaptureVTKMessages
{
public:
  CaptureVTKMessages()
    : Previous(vtkOutputWindow::GetInstance())
  {
    vtkOutputWindow::SetInstance(Collector);
  }
  ~CaptureVTKMessages() { vtkOutputWindow::SetInstance(Previous); }
  std::string First() const { return Collector->First; }

private:
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkNew<CollectingOutputWindow> Collector;
};

/// For a read in this process (AMRSP_READ_IN_PROCESS=1; a reading child of ReadInChildProcess
/// has its parent for this, and the guard stands aside there): while alive, the readers' own
/// diagnostics (HDF5's error stack, vtkLogger warnings) written straight to file descriptor 2 go
/// to a temporary file instead of the user's terminal, a crash inside a reader ends the process
/// with one line that names the reader and the file instead of a bare segmentation fault (exit
/// code 70), and a reader still busy after `timeoutSeconds` ends it with one line too (exit code
/// 75): some of VTK's readers loop forever on damaged files.
class ReaderGuard
{
public:
  explicit ReaderGuard(const std::string& what, double timeoutSeconds = 120.0)
  {
    if (InReadingChild())
    {
      return; // the parent process bounds the reading child's time, memory and signals
    }
    Active = true;
    std::snprintf(TimeoutMessage, sizeof(TimeoutMessage),
      "amrsp: error: %s did not finish within %g s: VTK's reader is stuck on this file (a "
      "damaged or unusual file the reader loops on; --read-timeout changes the limit)\n",
      what.c_str(), timeoutSeconds);
    Watchdog = std::thread(
      [this, timeoutSeconds]
      {
        std::unique_lock<std::mutex> lock(Mutex);
        if (!Finished.wait_for(
              lock, std::chrono::duration<double>(timeoutSeconds), [this] { return Done; }))
        {
          const int fd = SavedStderr >= 0 ? SavedStderr : 2;
          const ssize_t ignored = write(fd, TimeoutMessage, std::strlen(TimeoutMessage));
          (void)ignored;
          _exit(75);
        }
      });
    std::snprintf(Message, sizeof(Message),
      "amrsp: error: %s crashed inside VTK's reader (a reader bug, not ours)\n", what.c_str());
    std::fflush(stderr);
    SavedStderr = dup(2);
    Sink = std::tmpfile();
    if (Sink)
    {
      dup2(fileno(Sink), 2);
    }
    SetProgressDescriptor(SavedStderr); // the progress bar stays on the terminal
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = &ReaderGuard::OnCrash;
    for (int i = 0; i < 4; ++i)
    {
      sigaction(Signals[i], &action, &Previous[i]);
    }
  }
  ~ReaderGuard()
  {
    if (!Active)
    {
      return;
    }
    {
      std::lock_guard<std::mutex> lock(Mutex);
      Done = true;
    }
    Finished.notify_all();
    Watchdog.join();
    for (int i = 0; i < 4; ++i)
    {
      sigaction(Signals[i], &Previous[i], nullptr);
    }
    std::fflush(stderr);
    SetProgressDescriptor(2);
    if (SavedStderr >= 0)
    {
      dup2(SavedStderr, 2);
      close(SavedStderr);
      SavedStderr = -1;
    }
    if (Sink)
    {
      std::fclose(Sink);
    }
  }
  ReaderGuard(const ReaderGuard&) = delete;
  ReaderGuard& operator=(const ReaderGuard&) = delete;

private:
  static void OnCrash(int)
  {
    const int fd = SavedStderr >= 0 ? SavedStderr : 2;
    const ssize_t ignored = write(fd, Message, std::strlen(Message));
    (void)ignored;
    _exit(70);
  }
  static constexpr int Signals[4] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL };
  static char Message[1024];
  static int SavedStderr;
  std::FILE* Sink = nullptr;
  struct sigaction Previous[4];
  char TimeoutMessage[1024];
  std::mutex Mutex;
  std::condition_variable Finished;
  bool Done = false;
  std::thread Watchdog;
  bool Active = false;
};
char ReaderGuard::Message[1024];
int ReaderGuard::SavedStderr = -1;
constexpr int ReaderGuard::Signals[4];

/// Files of the old vtkHierarchicalBoxDataSet XML format (version 0.1, e.g. converted Chombo
/// output). VTK's vtkXMLUniformGridAMRReader crashes on them (VTK 9.1/9.2), so they are read here:
/// one .vti file per block, `amr_box` = inclusive cell ranges "x0 x1 y0 y1 z0 z1" per level.
bool IsHierarchicalBoxV01(const std::string& path)
{
  std::ifstream in(path);
  std::string head(512, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  return head.find("type=\"vtkHierarchicalBoxDataSet\"") != std::string::npos &&
    head.find("version=\"0.1\"") != std::string::npos;
}

vtkSmartPointer<vtkOverlappingAMR> ReadHierarchicalBoxV01(const std::string& path)
{
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(path.c_str());
  if (!parser->Parse() || !parser->GetRootElement())
  {
    throw DatasetError("cannot parse the XML of " + path);
  }
  vtkXMLDataElement* root =
    parser->GetRootElement()->FindNestedElementWithName("vtkHierarchicalBoxDataSet");
  if (!root)
  {
    throw DatasetError(path + " has no vtkHierarchicalBoxDataSet element");
  }
  struct Block
  {
    int Level, Index, Box[6];
    std::string File;
  };
  std::vector<Block> blocks;
  std::map<int, int> ratioOfLevel;
  for (int i = 0; i < root->GetNumberOfNestedElements(); ++i)
  {
    vtkXMLDataElement* e = root->GetNestedElement(i);
    const std::string damaged = "the VTK XML AMR file " + path + " is damaged: ";
    if (std::strcmp(e->GetName(), "RefinementRatio") == 0)
    {
      int level = 0, ratio = 2;
      e->GetScalarAttribute("level", level);
      e->GetScalarAttribute("refinement", ratio);
      if (level < 0 || level >= 64 || ratio < 2 || ratio > 64)
      {
        throw DatasetError(damaged + "a RefinementRatio has level=\"" + std::to_string(level) +
          "\" refinement=\"" + std::to_string(ratio) +
          "\" (expected a level 0 to 63 and a ratio 2 to 64)");
      }
      ratioOfLevel[level] = ratio;
    }
    else if (std::strcmp(e->GetName(), "DataSet") == 0)
    {
      Block b{};
      if (!e->GetScalarAttribute("group", b.Level) || !e->GetScalarAttribute("dataset", b.Index) ||
        e->GetVectorAttribute("amr_box", 6, b.Box) != 6 || !e->GetAttribute("file"))
      {
        throw DatasetError(path + ": a DataSet element lacks group, dataset, amr_box or file");
      }
      const std::string block =
        "block " + std::to_string(b.Index) + " of level " + std::to_string(b.Level);
      if (b.Level < 0 || b.Level >= 64 || b.Index < 0 || b.Index >= (1 << 20))
      {
        throw DatasetError(damaged + "a DataSet has group=\"" + std::to_string(b.Level) +
          "\" dataset=\"" + std::to_string(b.Index) +
          "\" (expected a group 0 to 63 and a dataset 0 to 2^20 - 1)");
      }
      for (int a = 0; a < 3; ++a)
      {
        if (b.Box[2 * a + 1] < b.Box[2 * a] || !WithinIndexRange(b.Box[2 * a]) ||
          !WithinIndexRange(b.Box[2 * a + 1]))
        {
          throw DatasetError(damaged + block + " has amr_box=\"" + e->GetAttribute("amr_box") +
            "\" (expected indices within +-2^30, each upper one not below its lower one)");
        }
      }
      b.File = e->GetAttribute("file");
      for (const Block& other : blocks)
      {
        if (other.Level == b.Level && other.Index == b.Index)
        {
          throw DatasetError(damaged + "two DataSet elements are " + block);
        }
      }
      blocks.push_back(b);
    }
  }
  if (blocks.empty())
  {
    throw DatasetError("the AMR hierarchy has no blocks (" + path + ")");
  }
  // every piece before VTK's image reader allocates for it (AmrspFileChecks.h), matching its box
  for (const Block& b : blocks)
  {
    const std::string file = (std::filesystem::path(path).parent_path() / b.File).string();
    const std::string block =
      "block " + std::to_string(b.Index) + " of level " + std::to_string(b.Level) + " in " + path;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
    {
      throw DatasetError("the piece file " + file + " of " + block + " is missing");
    }
    const std::vector<long long> cells = CheckVTIPiece(file, block);
    for (int a = 0; a < 3; ++a)
    {
      const long long boxCells = static_cast<long long>(b.Box[2 * a + 1]) - b.Box[2 * a] + 1;
      if (cells[a] != boxCells && !(cells[a] == 0 && boxCells == 1))
      {
        throw DatasetError("the piece file " + file + " of " + block + " holds " +
          std::to_string(cells[a]) + " cells on axis " + std::to_string(a) + ", its amr_box " +
          std::to_string(boxCells) + " (a piece of another block?)");
      }
    }
  }
  int levels = 0;
  for (const Block& b : blocks)
  {
    levels = std::max(levels, b.Level + 1);
  }
  std::vector<int> perLevel(static_cast<std::size_t>(levels), 0);
  for (const Block& b : blocks)
  {
    perLevel[b.Level] = std::max(perLevel[b.Level], b.Index + 1);
  }
  auto amr = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkSinglePassAMRDataModel::Initialize(amr, perLevel);
  amr->SetGridDescription(vtkSinglePassAMRDataModel::XYZGrid);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::vector<bool> levelSet(static_cast<std::size_t>(levels), false);
  std::size_t blocksRead = 0;
  for (const Block& b : blocks)
  {
    ReportProgress("reading", path, static_cast<double>(blocksRead++) / blocks.size());
    vtkNew<vtkXMLImageDataReader> reader;
    const std::string file = (folder / b.File).string();
    reader->SetFileName(file.c_str());
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    if (!image || image->GetNumberOfPoints() == 0)
    {
      throw DatasetError("cannot read block file " + file);
    }
    double spacing[3], origin[3];
    image->GetSpacing(spacing);
    image->GetOrigin(origin);
    const int lo[3] = { b.Box[0], b.Box[2], b.Box[4] };
    const int hi[3] = { b.Box[1], b.Box[3], b.Box[5] };
    if (!levelSet[b.Level])
    {
      amr->SetSpacing(b.Level, spacing);
      levelSet[b.Level] = true;
      if (b.Level == 0)
      {
        const double global[3] = { origin[0] - lo[0] * spacing[0], origin[1] - lo[1] * spacing[1],
          origin[2] - lo[2] * spacing[2] };
        amr->SetOrigin(global);
      }
    }
    amr->SetAMRBox(b.Level, b.Index, vtkAMRBox(lo, hi));
    vtkNew<vtkUniformGrid> grid;
    grid->ShallowCopy(image);
    amr->SetDataSet(b.Level, b.Index, grid);
  }
  for (int l = 0; l < levels; ++l)
  {
    amr->SetRefinementRatio(l, ratioOfLevel.count(l) ? ratioOfLevel[l] : 2);
  }
  ReportProgress("reading", path, 1.0);
  vtkAMRUtilities::BlankCells(amr);
  return amr;
}

vtkSmartPointer<vtkOverlappingAMR> RunAlgorithm(
  vtkAlgorithm* algorithm, const std::string& what, CaptureVTKMessages& capture)
{
  // the reader's ProgressEvents on the terminal's progress bar (AmrspProgress.h)
  vtkNew<vtkCallbackCommand> progress;
  progress->SetClientData(const_cast<std::string*>(&what));
  progress->SetCallback(
    [](vtkObject* caller, unsigned long, void* what, void*)
    {
      ReportProgress("reading", *static_cast<std::string*>(what),
        std::min(static_cast<vtkAlgorithm*>(caller)->GetProgress(), 0.999));
    });
  algorithm->AddObserver(vtkCommand::ProgressEvent, progress);
  ReportProgress("reading", what, 0.0); // starts the step's clock: some readers report nothing
  algorithm->Update();
  algorithm->RemoveObserver(progress);
  ReportProgress("reading", what, 1.0);
  auto* amr = vtkOverlappingAMR::SafeDownCast(algorithm->GetOutputDataObject(0));
  if (!amr || amr->GetNumberOfLevels() == 0 || vtkSinglePassAMRDataModel::NumberOfBlocks(amr) == 0)
  {
    const std::string why = capture.First();
    throw DatasetError(what + (why.empty() ? " produced no AMR blocks" : " failed: " + why));
  }
  return amr;
}

/// Enzo and AMReX readers share vtkAMRBaseReader: enable only the requested cell array.
std::string SelectReaderArray(vtkAMRBaseReader* reader, const DatasetRequest& request,
  const std::string& what, CaptureVTKMessages& capture, const ExpectedBlocks& expected)
{
  const std::vector<std::string>& listed = expected.Variables;
  reader->SetMaxLevel(1000);
  reader->UpdateInformation();
  const int n = reader->GetNumberOfCellArrays();
  if (n == 0)
  {
    const std::string why = capture.First();
    std::string variables;
    for (const std::string& v : listed)
    {
      variables += (variables.empty() ? "" : ", ") + v;
    }
    // the reader takes the array names from the first block's file (Enzo: grid 1's HDF5 file)
    const std::string first = expected.Files.empty() ? std::string() : expected.Files.front();
    const std::string where = first.empty() || first == request.Spec
      ? std::string()
      : " (VTK's reader looks for them in " + first + ", the first grid's file)";
    throw DatasetError(what +
      (listed.empty() ? (why.empty() ? " has no cell arrays" + where : " failed: " + why + where)
                      : ": VTK's reader finds no cell arrays although the files list " +
            std::to_string(listed.size()) + " variables (" + variables + ")" +
            (why.empty() ? std::string() : "; the reader said: " + why)));
  }
  std::string names;
  bool found = false;
  for (int i = 0; i < n; ++i)
  {
    const std::string name = reader->GetCellArrayName(i);
    names += (i ? ", " : "") + name;
    found = found || name == request.Array;
  }
  if (!request.Array.empty() && !found)
  {
    throw DatasetError(
      "no cell array named '" + request.Array + "' in " + what + " (available: " + names + ")");
  }
  for (int i = 0; i < n; ++i)
  {
    reader->SetCellArrayStatus(reader->GetCellArrayName(i), 0);
  }
  const std::string chosen = request.Array.empty() ? reader->GetCellArrayName(0) : request.Array;
  reader->SetCellArrayStatus(chosen.c_str(), 1);
  return chosen;
}

/// AMRSP_SKIP_FILE_CHECKS=1 hands the files to VTK's readers unchecked: the damage test uses it
/// to show that the reader watchdog ends a reader that loops.
bool FileChecksOn()
{
  const char* skip = std::getenv("AMRSP_SKIP_FILE_CHECKS");
  return !(skip && std::string(skip) == "1");
}

/// `requested`, or the array the conversion renders by default (vtkAMRMapperConversion: the
/// first cell array, else the first point array; never vtkGhostType).
std::string FirstArrayName(vtkOverlappingAMR* amr, const std::string& requested)
{
  if (!requested.empty())
  {
    return requested;
  }
  for (bool points : { false, true })
  {
    const std::vector<std::string> names = vtkAMRMapperConversion::ArrayNames(amr, points);
    if (!names.empty())
    {
      return names.front();
    }
  }
  return "";
}

/// The blocks of `amr` that hold `array` (cell or point data) against those the files describe:
/// fewer is an error naming the files of the missing blocks, or, with AllowPartial, a warning.
void CheckBlocksRead(vtkOverlappingAMR* amr, const ExpectedBlocks& expected,
  const std::string& array, const std::string& what, const std::string& capturedMessage,
  bool allowPartial, bool exactOrder)
{
  std::size_t read = 0, flat = 0;
  std::set<std::string> missingFiles;
  for (unsigned int l = 0; l < amr->GetNumberOfLevels(); ++l)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(amr, l); ++i, ++flat)
    {
      vtkDataSet* grid = vtkSinglePassAMRDataModel::Block(amr, l, i);
      const bool has = grid &&
        (grid->GetCellData()->GetAbstractArray(array.c_str()) ||
          grid->GetPointData()->GetAbstractArray(array.c_str()));
      read += has ? 1 : 0;
      if (!has && exactOrder && flat < expected.Files.size())
      {
        missingFiles.insert(expected.Files[flat]);
      }
    }
  }
  if (read >= expected.Count())
  {
    return;
  }
  if (!exactOrder)
  {
    missingFiles.insert(expected.Files.begin(), expected.Files.end());
  }
  missingFiles.erase("");
  std::string files;
  int listed = 0;
  for (const std::string& f : missingFiles)
  {
    if (listed++ == 3)
    {
      files += ", ...";
      break;
    }
    files += (files.empty() ? "" : ", ") + f;
  }
  const std::string message = "read " + std::to_string(read) + " of the " +
    std::to_string(expected.Count()) + " blocks " + what + " describes with '" + array + "'" +
    (files.empty() ? std::string() : " (the others are in " + files + ")") +
    (capturedMessage.empty() ? std::string() : "; the reader said: " + capturedMessage);
  if (!allowPartial)
  {
    throw DatasetError(message + "; --allow-partial renders what was read");
  }
  std::fprintf(stderr, "amrsp: warning: %s; rendering them (--allow-partial)\n", message.c_str());
}

} // namespace

namespace
{
/// Applies DatasetRequest::Centering to loaded values.
void ApplyCentering(const DatasetRequest& request, LoadedDataset& out)
{
  if (request.Centering == "auto" || !out.Data.HasValues())
  {
    return;
  }
  if (request.Centering == "vertex")
  {
    if (!out.Data.VertexCentred)
    {
      ConvertCellsToVertices(out.Data);
    }
    return;
  }
  if (request.Centering == "cell")
  {
    if (out.Data.VertexCentred)
    {
      throw DatasetError("'" + out.Data.ArrayName +
        "' is point data: it can only be rendered vertex-centred (--centering vertex or auto)");
    }
    return;
  }
  throw DatasetError("--centering must be auto, cell or vertex");
}
} // namespace

LoadedDataset LoadDataset(const DatasetRequest& request)
{
  LoadedDataset out = LoadDatasetAsStored(request);
  ApplyCentering(request, out);
  return out;
}

namespace
{
/// synthetic:cosmo[:PARAMETERS]: the generator's hierarchy (values only when asked for), and its
/// vtkOverlappingAMR when request.NeedVTK.
void GenerateSyntheticCosmo(const DatasetRequest& request, LoadedDataset& out)
{
  const std::string& spec = request.Spec;
  out.Format = "synthetic:cosmo";
  std::string params;
  if (spec.size() > 15)
  {
    if (spec[15] != ':')
    {
      throw DatasetError("unknown dataset '" + spec +
        "' (expected synthetic:cosmo[:grids=N,levels=L,cells=C,seed=S])");
    }
    params = spec.substr(16);
  }
  CosmoParameters p;
  try
  {
    p = ParseCosmoParameters(params);
  }
  catch (const std::exception& e)
  {
    throw DatasetError(std::string("bad synthetic:cosmo parameters: ") + e.what());
  }
  if (!request.Array.empty() && request.Array != "Density")
  {
    throw DatasetError(
      "no cell array named '" + request.Array + "' in synthetic:cosmo (available: Density)");
  }
  p.GenerateValues = request.NeedValues || request.NeedVTK;
  try
  {
    out.Data =
      GenerateCosmo(p, [spec](double fraction) { ReportProgress("generation", spec, fraction); });
  }
  catch (const std::exception& e)
  {
    throw DatasetError(std::string("cannot generate synthetic:cosmo: ") + e.what());
  }
  if (request.NeedVTK)
  {
    out.Amr = vtkSmartPointer<vtkOverlappingAMR>::New();
    vtkAMRMapperConversion::ToOverlappingAMR(out.Data, out.Amr);
  }
}

/// Reads request.Spec with `reader` (`what` names the dataset in messages) into out.Amr: the
/// array selection, the read, and the blocks read against `expected` (the file checks' blocks;
/// `inFileOrder`: whether the reader keeps the files' block order, as CheckBlocksRead).
void ReadWithAMRReader(vtkAMRBaseReader* reader, const std::string& what,
  const ExpectedBlocks& expected, bool inFileOrder, const DatasetRequest& request,
  CaptureVTKMessages& capture, LoadedDataset& out)
{
  reader->SetFileName(request.Spec.c_str());
  const std::string array = SelectReaderArray(reader, request, what, capture, expected);
  out.Amr = RunAlgorithm(reader, "reading " + what, capture);
  CheckBlocksRead(
    out.Amr, expected, array, what, capture.First(), request.AllowPartial, inFileOrder);
}

/// A dataset file or folder (Enzo, AMReX, VTK XML AMR) read with VTK's reader into out.Amr, after
/// the checks of the files the dataset's own metadata names.
void ReadDatasetFile(const DatasetRequest& request, CaptureVTKMessages& capture, LoadedDataset& out)
{
  const std::string& spec = request.Spec;
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path path(spec);
  if (!fs::exists(path, ec))
  {
    throw DatasetError("no such file or directory: " + spec);
  }
  const std::string ext = LowerAscii(path.extension().string());
  if (fs::is_directory(path, ec))
  {
    if (!fs::exists(path / "Header", ec))
    {
      throw DatasetError(
        "unknown format: " + spec + " is a folder without an AMReX plotfile Header");
    }
    out.Format = "amrex";
    ReaderGuard guard("reading the AMReX plotfile " + spec, request.ReadTimeoutSeconds);
    const ExpectedBlocks expected = FileChecksOn() ? CheckAMReXFiles(spec) : ExpectedBlocks();
    vtkNew<vtkAMReXGridReader> reader;
    ReadWithAMRReader(reader, "the AMReX plotfile " + spec, expected, true, request, capture, out);
  }
  else if (ext == ".hierarchy")
  {
    out.Format = "enzo";
    ReaderGuard guard("reading the Enzo hierarchy " + spec, request.ReadTimeoutSeconds);
    const ExpectedBlocks expected = FileChecksOn() ? CheckEnzoFiles(spec) : ExpectedBlocks();
    vtkNew<vtkAMREnzoReader> reader;
    // VTK's reader orders Enzo grids by level, not as the hierarchy lists them: the missing
    // blocks' files are named as the set of grid files
    ReadWithAMRReader(reader, "the Enzo hierarchy " + spec, expected, false, request, capture, out);
  }
  else if ((ext == ".vthb" || ext == ".vth" || ext == ".vtm") && IsHierarchicalBoxV01(spec) &&
    !std::getenv("AMRSP_USE_VTK_XML_AMR_READER")) // the variable exists to test the crash guard
  {
    out.Format = "vtk-xml-hierarchical-box-0.1";
    ReaderGuard guard("reading " + spec, request.ReadTimeoutSeconds);
    out.Amr = ReadHierarchicalBoxV01(spec);
  }
  else if (ext == ".vthb" || ext == ".vth" || ext == ".vtm")
  {
    out.Format = "vtk-xml-amr";
    ReaderGuard guard("reading the VTK XML AMR file " + spec, request.ReadTimeoutSeconds);
    ExpectedBlocks expected;
    try
    {
      expected = FileChecksOn() ? CheckVTKXMLAMRFiles(spec) : ExpectedBlocks();
    }
    catch (const DatasetError& e)
    {
      const std::string why = capture.First(); // the XML parser's own message
      throw DatasetError(std::string(e.what()) + (why.empty() ? "" : " (" + why + ")"));
    }
    vtkNew<vtkXMLUniformGridAMRReader> reader;
    reader->SetFileName(spec.c_str());
    reader->SetMaximumLevelsToReadByDefault(0); // all levels
    out.Amr = RunAlgorithm(reader, "reading the VTK XML AMR file " + spec, capture);
    CheckBlocksRead(out.Amr, expected, FirstArrayName(out.Amr, request.Array),
      "the VTK XML AMR file " + spec, capture.First(), request.AllowPartial, true);
  }
  else
  {
    throw DatasetError("unknown format: " + spec +
      " (expected an Enzo .hierarchy, an AMReX plotfile folder, a .vthb/.vth file, "
      "synthetic:pulse or synthetic:cosmo)");
  }
}

/// The hierarchy of out.Amr with the request's array and component (vtkAMRMapperConversion).
void ConvertSelected(const DatasetRequest& request, LoadedDataset& out)
{
  vtkAMRMapperConversion::ArraySelection selection;
  selection.Name = request.Array;
  if (selection.Name.empty() && out.Format == "synthetic:pulse")
  {
    selection.Name = "Gaussian-Pulse"; // its first array is the 3-component "Centroid"
  }
  selection.Component = request.Component;
  selection.CopyValues = request.NeedValues;
  std::string error;
  if (!vtkAMRMapperConversion::FromOverlappingAMR(out.Amr, selection, out.Data, error))
  {
    throw DatasetError(error + " (" + request.Spec + ")");
  }
  if (!request.NeedValues)
  {
    out.Data.Values.clear();
  }
}

/// How messages name the read of the file or folder `spec`.
std::string ReadingWhat(const std::string& spec)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string ext = LowerAscii(fs::path(spec).extension().string());
  if (fs::is_directory(spec, ec))
  {
    return "reading the AMReX plotfile " + spec;
  }
  if (ext == ".hierarchy")
  {
    return "reading the Enzo hierarchy " + spec;
  }
  if (ext == ".vthb" || ext == ".vth" || ext == ".vtm")
  {
    return "reading the VTK XML AMR file " + spec;
  }
  return "reading " + spec;
}

/// A dataset file or folder read in a child process (AmrspIsolatedRead.h): the file checks, VTK's
/// reader and the conversion run there; the hierarchy comes back, and out.Amr is made from it
/// when asked for.
void ReadIsolated(const DatasetRequest& request, LoadedDataset& out)
{
  namespace fs = std::filesystem;
  const std::string& spec = request.Spec;
  std::error_code ec;
  if (!fs::exists(spec, ec))
  {
    throw DatasetError("no such file or directory: " + spec);
  }
  // the address space the child may use: from the dataset's folder (a hierarchy's grid files, a
  // plotfile's levels, a .vthb's pieces lie there)
  const std::string folder =
    fs::is_directory(spec, ec) ? spec : fs::absolute(spec, ec).parent_path().string();
  const IsolatedResult r =
    ReadInChildProcess(ReadingWhat(spec), request.ReadTimeoutSeconds, ReadMemoryLimit({ folder }),
      [&request]
      {
        LoadedDataset child;
        child.Spec = request.Spec;
        CaptureVTKMessages capture;
        ReadDatasetFile(request, capture, child);
        ConvertSelected(request, child);
        return IsolatedResult{ std::move(child.Data), child.Format };
      });
  out.Data = r.Data;
  out.Format = r.Format;
  if (request.NeedVTK)
  {
    out.Amr = vtkSmartPointer<vtkOverlappingAMR>::New();
    vtkAMRMapperConversion::ToOverlappingAMR(out.Data, out.Amr);
  }
}

LoadedDataset LoadStored(const DatasetRequest& request)
{
  const auto start = std::chrono::steady_clock::now();
  LoadedDataset out;
  out.Spec = request.Spec;
  const std::string& spec = request.Spec;

  if (spec.rfind("synthetic:cosmo", 0) == 0)
  {
    GenerateSyntheticCosmo(request, out);
  }
  else if (spec == "synthetic:pulse")
  {
    out.Format = "synthetic:pulse";
    CaptureVTKMessages capture;
    vtkNew<vtkAMRGaussianPulseSource> pulse;
    pulse->SetDimension(3);
    pulse->SetNumberOfLevels(2);
    pulse->SetRefinementRatio(2);
    out.Amr = RunAlgorithm(pulse, "vtkAMRGaussianPulseSource", capture);
    ConvertSelected(request, out);
  }
  else if (spec.rfind("synthetic:", 0) == 0)
  {
    throw DatasetError("unknown synthetic dataset '" + spec +
      "' (known: synthetic:pulse, synthetic:cosmo[:grids=N,levels=L,cells=C,seed=S])");
  }
  else
  {
    ReadIsolated(request, out);
  }
  out.LoadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}
} // namespace

LoadedDataset LoadDatasetAsStored(const DatasetRequest& request)
{
  try
  {
    return LoadStored(request);
  }
  catch (const std::bad_alloc&)
  {
    // the checks of AmrspFileChecks.h test sizes against the files; a reader may still read one
    // that no check knows of
    throw DatasetError("ran out of memory reading " + request.Spec +
      ": the data is larger than this machine's memory, or a size in a damaged file is wrong");
  }
}

} // namespace harness
} // namespace amrsp
