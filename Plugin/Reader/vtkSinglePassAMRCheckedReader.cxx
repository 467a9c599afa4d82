// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRCheckedReader.h"
#include "vtkSinglePassAMRCheckedReaderTransfer.h"

#include "AmrspChildProcess.h"
#include "AmrspFileChecks.h"

#include "vtkAMRBaseReader.h"
#include "vtkAMREnzoReader.h"
#include "vtkAMReXGridReader.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkSinglePassAMRDataModel.h" // the AMR calls of every VTK version
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkXMLUniformGridAMRReader.h"

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

vtkStandardNewMacro(vtkSinglePassAMRCheckedReader);

namespace
{
using amrsp::harness::DatasetError;
namespace fs = std::filesystem;

enum class Format
{
  Enzo,
  AMReX,
  VTKXML
};

/// What a file name is, with the path VTK's reader and the checks take.
struct Dataset
{
  Format Kind;
  std::string Path; ///< Enzo: the .hierarchy; AMReX: the plotfile folder; VTK XML: the file
  std::string What; ///< how messages name the read
  bool ConvertToCGS = false; ///< Enzo: values in CGS units instead of the code's units
};

std::string Lower(std::string s)
{
  for (char& c : s)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return s;
}

Dataset Identify(const std::string& name)
{
  std::error_code ec;
  const fs::path path(name);
  if (!fs::exists(path, ec))
  {
    throw DatasetError("no such file or directory: " + name);
  }
  const std::string ext = Lower(path.extension().string());
  if (fs::is_directory(path, ec) || path.filename() == "Header")
  {
    const fs::path folder = fs::is_directory(path, ec) ? path : path.parent_path();
    if (!fs::exists(folder / "Header", ec))
    {
      throw DatasetError(
        "unknown format: " + name + " is a folder without an AMReX plotfile Header");
    }
    return { Format::AMReX, folder.string(), "the AMReX plotfile " + folder.string() };
  }
  if (ext == ".hierarchy" || ext == ".boundary")
  {
    const std::string hierarchy = fs::path(path).replace_extension(".hierarchy").string();
    return { Format::Enzo, hierarchy, "the Enzo hierarchy " + hierarchy };
  }
  if (ext == ".vthb" || ext == ".vth" || ext == ".vtm")
  {
    return { Format::VTKXML, name, "the VTK XML AMR file " + name };
  }
  throw DatasetError("unknown format: " + name +
    " (expected an Enzo .hierarchy or .boundary, an AMReX plotfile folder or Header, or a "
    ".vthb/.vth file)");
}

bool FileChecksOn()
{
  const char* skip = std::getenv("AMRSP_SKIP_FILE_CHECKS");
  return !(skip && std::string(skip) == "1");
}

/// The simulation time a dump records (Enzo: the parameter file's InitialTime; AMReX: the Header's
/// time line), or NaN when there is none (VTK XML AMR) or it cannot be read. Read by this
/// process from the text headers alone: no VTK reader runs here.
double TimeOf(const Dataset& d)
{
  const double none = std::nan("");
  if (d.Kind == Format::Enzo)
  {
    std::ifstream parameters(fs::path(d.Path).replace_extension("").string());
    std::string line;
    for (int n = 0; n < 10000 && std::getline(parameters, line); ++n)
    {
      std::istringstream words(line);
      std::string key, equals;
      double t = none;
      if (words >> key >> equals >> t && key == "InitialTime" && equals == "=")
      {
        return std::isfinite(t) ? t : none;
      }
    }
    return none;
  }
  if (d.Kind == Format::AMReX)
  {
    // the version line, the number of variables, their names, the dimension, the time
    std::ifstream header((fs::path(d.Path) / "Header").string());
    std::string line;
    long long variables = -1;
    if (!std::getline(header, line) || !(header >> variables) || variables < 0 ||
      variables > 100000)
    {
      return none;
    }
    std::getline(header, line);
    for (long long v = 0; v < variables && std::getline(header, line); ++v)
    {
    }
    int dimension = 0;
    double t = none;
    return header >> dimension >> t && std::isfinite(t) ? t : none;
  }
  return none;
}

/// Enzo and AMReX: every level, every cell array.
void SelectEverything(vtkAMRBaseReader* reader, const Dataset& d)
{
  // every block: under MPI the reader would deal them to the ranks itself, through the global
  // controller, from a forked child (RequestData deals the blocks instead)
  reader->SetController(nullptr);
  reader->SetFileName(d.Path.c_str());
  reader->SetMaxLevel(1000);
  reader->UpdateInformation();
  for (int i = 0; i < reader->GetNumberOfCellArrays(); ++i)
  {
    reader->SetCellArrayStatus(reader->GetCellArrayName(i), 1);
  }
}

/// The checks, then a new VTK reader; throws DatasetError with one line.
vtkSmartPointer<vtkOverlappingAMR> CheckAndRead(const Dataset& d)
{
  amrsp::harness::ExpectedBlocks expected;
  vtkSmartPointer<vtkAlgorithm> reader;
  switch (d.Kind)
  {
    case Format::Enzo:
    {
      expected = FileChecksOn() ? amrsp::harness::CheckEnzoFiles(d.Path) : expected;
      auto enzo = vtkSmartPointer<vtkAMREnzoReader>::New();
      enzo->SetConvertToCGS(d.ConvertToCGS ? 1 : 0);
      SelectEverything(enzo, d);
      reader = enzo;
      break;
    }
    case Format::AMReX:
    {
      expected = FileChecksOn() ? amrsp::harness::CheckAMReXFiles(d.Path) : expected;
      auto amrex = vtkSmartPointer<vtkAMReXGridReader>::New();
      SelectEverything(amrex, d);
      reader = amrex;
      break;
    }
    case Format::VTKXML:
    {
      expected = FileChecksOn() ? amrsp::harness::CheckVTKXMLAMRFiles(d.Path) : expected;
      auto xml = vtkSmartPointer<vtkXMLUniformGridAMRReader>::New();
      xml->SetFileName(d.Path.c_str());
      xml->SetMaximumLevelsToReadByDefault(0); // every level
      reader = xml;
      break;
    }
  }
  reader->Update();
  vtkSmartPointer<vtkOverlappingAMR> amr =
    vtkOverlappingAMR::SafeDownCast(reader->GetOutputDataObject(0));
  const unsigned int blocks = amr ? vtkSinglePassAMRDataModel::NumberOfBlocks(amr) : 0;
  if (blocks == 0)
  {
    throw DatasetError("VTK's reader produced no AMR blocks from " + d.What);
  }
  unsigned int withData = 0;
  for (unsigned int level = 0; level < amr->GetNumberOfLevels(); ++level)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(amr, level); ++i)
    {
      withData += vtkSinglePassAMRDataModel::Block(amr, level, i) != nullptr ? 1 : 0;
    }
  }
  if (expected.Count() > 0 && withData < expected.Count())
  {
    throw DatasetError("VTK's reader read " + std::to_string(withData) + " of the " +
      std::to_string(expected.Count()) + " blocks " + d.What + " describes");
  }
  return amr;
}

/// The read in a child process: its AMR comes back through the child's result file
/// (vtkSinglePassAMRCheckedReaderTransfer.h).
void ReadInChild(const Dataset& d, double timeout, vtkOverlappingAMR* output)
{
  const std::string folder =
    d.Kind == Format::AMReX ? d.Path : fs::path(d.Path).parent_path().string();
  const int fd = amrsp::harness::RunInChildProcess("reading " + d.What, timeout,
    "the reader's ReadTimeout", amrsp::harness::ReadMemoryLimit({ folder }),
    [&d](int resultFd)
    { return vtkSinglePassAMRCheckedReaderTransfer::Write(CheckAndRead(d), resultFd); });
  struct stat st;
  void* mapped = MAP_FAILED;
  if (fstat(fd, &st) == 0 && st.st_size > 0)
  {
    mapped = mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_SHARED, fd, 0);
  }
  close(fd);
  vtkSmartPointer<vtkOverlappingAMR> amr;
  if (mapped != MAP_FAILED)
  {
    amr = vtkSinglePassAMRCheckedReaderTransfer::Read(
      static_cast<const char*>(mapped), static_cast<std::size_t>(st.st_size));
    munmap(mapped, static_cast<std::size_t>(st.st_size));
  }
  if (!amr)
  {
    throw DatasetError("the reading process handed back no AMR for " + d.What);
  }
  output->ShallowCopy(amr);
}
} // namespace

vtkSinglePassAMRCheckedReader::vtkSinglePassAMRCheckedReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkSinglePassAMRCheckedReader::~vtkSinglePassAMRCheckedReader()
{
  this->SetFileName(nullptr);
}

int vtkSinglePassAMRCheckedReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // the dump's time, so that a file series plays in simulation time as ParaView's own readers
  // do (without one, ParaView numbers the files 0, 1, ...)
  vtkInformation* info = outputVector->GetInformationObject(0);
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  info->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  double t = std::nan("");
  try
  {
    t = this->FileName ? TimeOf(Identify(this->FileName)) : t;
  }
  catch (const std::exception&)
  {
    // RequestData reports what is wrong with the file
  }
  if (std::isfinite(t))
  {
    const double range[2] = { t, t };
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), &t, 1);
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
}

int vtkSinglePassAMRCheckedReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkOverlappingAMR* output = vtkOverlappingAMR::GetData(outputVector, 0);
  this->LastError.clear();
  try
  {
    if (!this->FileName || !*this->FileName)
    {
      throw DatasetError("no file name set");
    }
    Dataset d = Identify(this->FileName);
    d.ConvertToCGS = this->ConvertToCGS;
    if (this->ReadInChildProcess)
    {
      ReadInChild(d, this->ReadTimeout, output);
    }
    else
    {
      output->ShallowCopy(CheckAndRead(d));
    }
    // in parallel (pvserver, pvbatch under MPI) each rank keeps the blocks of its piece, dealt
    // round-robin over the blocks in level order as VTK's AMR readers deal them; the metadata
    // (every level's boxes) stays whole on every rank
    vtkInformation* info = outputVector->GetInformationObject(0);
    const int pieces = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
      ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES())
      : 1;
    const int piece = info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
      ? info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
      : 0;
    if (pieces > 1)
    {
      unsigned int block = 0;
      for (unsigned int level = 0; level < output->GetNumberOfLevels(); ++level)
      {
        for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(output, level);
             ++i, ++block)
        {
          if (static_cast<int>(block % static_cast<unsigned int>(pieces)) != piece)
          {
            vtkSinglePassAMRDataModel::SetBlock(output, level, i, nullptr);
          }
        }
      }
    }
  }
  catch (const std::exception& e)
  {
    // an empty output and one message; the pipeline goes on (a representation shows nothing)
    this->LastError = e.what();
    output->Initialize();
    vtkErrorMacro(<< this->LastError);
  }
  return 1;
}

void vtkSinglePassAMRCheckedReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "ReadTimeout: " << this->ReadTimeout << "\n";
  os << indent << "ReadInChildProcess: " << this->ReadInChildProcess << "\n";
  os << indent << "ConvertToCGS: " << this->ConvertToCGS << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
}
