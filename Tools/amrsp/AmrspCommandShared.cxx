// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspCommandShared.h"

#include "AmrspDriver.h"
#include "AmrspIsolatedRead.h"
#include "AmrspProgress.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

const char* const DefaultDataset = "synthetic:cosmo:grids=200,levels=4,cells=1M,seed=7";

double Seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

int Fail(const std::string& message)
{
  std::cerr << "amrsp: error: " << message << "\n";
  return 1;
}

int Fail(const std::exception& e)
{
  Fail(std::string(e.what()));
  const ReaderFailure* reader = dynamic_cast<const ReaderFailure*>(&e);
  return reader ? reader->ExitCode : 1;
}

const std::vector<std::string> DatasetOptions = { "array", "component", "centering",
  "read-timeout" };
const std::vector<std::string> DatasetFlags = { "allow-partial", "strict", "quiet" };
const std::vector<std::string> AtlasOptions = { "packer", "max-3d-texture-size", "atlas-budget-mb",
  "atlas-page-mib" };
std::vector<std::string> Concat(std::initializer_list<std::vector<std::string>> lists)
{
  std::vector<std::string> all;
  for (const auto& l : lists)
  {
    all.insert(all.end(), l.begin(), l.end());
  }
  return all;
}

const char* const DatasetHelp =
  "DATASET is one of\n"
  "  PATH.hierarchy              an Enzo hierarchy (vtkAMREnzoReader)\n"
  "  PLOTFILE_FOLDER             an AMReX/BoxLib plotfile (vtkAMReXGridReader)\n"
  "  PATH.vthb | PATH.vth        VTK XML AMR (vtkXMLUniformGridAMRReader)\n"
  "  synthetic:pulse             VTK's vtkAMRGaussianPulseSource\n"
  "  synthetic:cosmo[:grids=N,levels=L,cells=C,seed=S]\n"
  "                              the project's cosmology-like generator (N and C accept k/M)\n"
  "Dataset options:\n"
  "  --array NAME                cell array to use (default: the first cell array)\n"
  "  --component I               component of a vector array (default: magnitude)\n"
  "  --centering auto|cell|vertex  auto: cell data cell-centred (nearest cell), point data\n"
  "                              vertex-centred (trilinear); vertex: convert cell data to\n"
  "                              vertices (continuous across grid and level interfaces)\n"
  "  --strict                    (the default) a file that yields fewer blocks than the\n"
  "                              dataset's own files describe is an error naming them\n"
  "  --allow-partial             render the blocks that could be read, with a warning\n"
  "  --read-timeout S            end with an error when VTK's reader is still busy after S\n"
  "                              seconds (default 120; exit code 75)\n"
  "  --quiet                     no progress bar on the terminal (one is drawn on stderr for\n"
  "                              the mappers' build and upload when they take over a second)\n";

const char* const AtlasHelp =
  "Atlas options (packed storage of the grid bricks):\n"
  "  --packer nfdh|best          the paper's next-fit-decreasing-height, or the "
  "guillotine-bestfit\n"
  "                              packer (default best)\n"
  "  --max-3d-texture-size N     per-axis texture limit (default 2048, GL_MAX_3D_TEXTURE_SIZE)\n"
  "  --atlas-budget-mb M         largest atlas in MiB of float texels (default: no limit)\n"
  "  --atlas-page-mib M          GPU methods: largest atlas texture in MiB; a larger atlas is\n"
  "                              split into up to 4 pages (default 1984, below llvmpipe's 2 GiB)\n";

AtlasRequest ParseAtlasRequest(const Arguments& a)
{
  AtlasRequest r;
  try
  {
    r.Algorithm = ParsePacker(a.Get("packer", "best"));
  }
  catch (const std::invalid_argument& e)
  {
    throw UsageError{ e.what() };
  }
  const double size = a.GetNumber("max-3d-texture-size", 2048);
  const double budget = a.GetNumber("atlas-budget-mb", 0);
  if (size < 1 || budget < 0)
  {
    throw UsageError{ "--max-3d-texture-size and --atlas-budget-mb must be positive" };
  }
  r.MaxDims = AtlasLimits(static_cast<int>(size));
  r.MaxBytes = static_cast<std::size_t>(budget * 1024.0 * 1024.0);
  return r;
}

Json AtlasJson(const AtlasLayout& layout)
{
  return Json{ { "packer", layout.PackerName },
    { "dims", { layout.Dims.x, layout.Dims.y, layout.Dims.z } },
    { "used_texels", layout.UsedTexels }, { "total_texels", layout.TotalTexels },
    { "efficiency", layout.Efficiency },
    { "bytes", layout.TotalTexels * static_cast<int64_t>(AtlasTexelBytes) } };
}

const char* const ViewHelp =
  "View options (conventions of VTK's vtkCamera/vtkVolumeProperty; see docs/design.md):\n"
  "  --size WxH                  image size (default 512x512)\n"
  "  --azimuth A --elevation E   degrees, applied after ResetCamera (default 30, 20)\n"
  "  --zoom Z                    vtkCamera::Zoom factor (default 1)\n"
  "  --tf PRESET                 transfer function: default, grey, hot, grey-opaque, sparse\n"
  "  --scale auto|linear|log     scalar mapping; auto = log10 when the data is positive and\n"
  "                              spans more than 3 decades (default auto)\n"
  "  --range all|step|LO:HI      the values the transfer function and the scale rule cover:\n"
  "                              LO:HI as given (in the data's units), step each step's own,\n"
  "                              all (default) a time series' values over all its steps\n"
  "  --unit-distance D           ScalarOpacityUnitDistance in world units (default: diagonal/100)\n"
  "  --sample-factor F           samples per cell of each segment's level = 1/F (default 1)\n"
  "  --reference-sample-factor F step of the reference in finest-cell edges (default 0.5)\n"
  "  --lod PIXELS                level-of-detail threshold in pixels (default 0 = off)\n"
  "  --blend MODE                composite (default), maximum, minimum, average intensity or\n"
  "                              iso (iso-surfaces)\n"
  "  --threads N                 CPU threads (default: all cores)\n"
  "  --opacity-threshold T       early ray termination: a composite ray stops at opacity T\n"
  "                              (default 0.999; 1 = never early)\n"
  "  --empty-space-skipping on|off  skip data nodes whose value range is transparent\n"
  "                              (kD-tree methods, composite; default on; the reference never\n"
  "                              skips)\n"
  "  --ropes on|off              neighbour links of the kD-tree: a ray leaving a leaf through\n"
  "                              one face continues from that face's rope instead of a new\n"
  "                              descent (single pass and cpu-kdtree; default on; same image)\n"
  "  --loop auto|nested|flat     the single-pass shader's loop structure: per segment a descent\n"
  "                              loop then a sample loop, or one loop of single operations; the\n"
  "                              same image (default nested; auto: nested, which measured faster\n"
  "                              on an NVIDIA H200 and on llvmpipe)\n"
  "  --caster auto|fragment|compute  the shader stage that casts the single pass's rays: a\n"
  "                              fragment shader over the volume's box, or a compute shader over\n"
  "                              the image and one composite draw; the same image (default\n"
  "                              auto: compute on a GPU with compute shaders, fragment on a CPU\n"
  "                              driver)\n"
  "  --ablation A                diagnostic, single pass only: none (default), traversal-only\n"
  "                              (no data segment sampled) or sampling-only[:N] (each ray\n"
  "                              samples its first brick N times, default 256, no further\n"
  "                              traversal); locates GPU time, the image is not the volume's\n"
  "  --interpolation nearest|smooth  cell-centred data: nearest cell (default) or the smooth\n"
  "                              dual-cell reconstruction across grids and levels (packing,\n"
  "                              CPU methods and the reference)\n"
  "  --view-json FILE            camera, transfer function and background from a JSON file\n"
  "                              (e.g. written from ParaView; see docs/command-line.md) instead of "
  "the\n"
  "                              conventions above; its transfer function implies --scale linear\n"
  "  --shade on|off              gradient shading, vtkVolumeProperty's defaults (default off)\n"
  "  --iso F[,F...]              with --blend iso: iso-values as fractions of the transfer\n"
  "                              function's range, at most 8 (default 0.5)\n"
  "  --shadows STEP              shadow rays, step in world units (default 0 = off)\n"
  "  --light X,Y,Z               a point light at this world position (default: headlight)\n"
  "  --crop X0,X1,Y0,Y1,Z0,Z1    integrate the rays inside this world box only\n"
  "                              (vtkVolumeMapper's cropping of the central sub-volume)\n";

LoadedDataset Load(const Arguments& a, bool needValues, bool needVTK)
{
  return Load(a, a.Positional.size() > 1 ? a.Positional[1] : DefaultDataset, needValues, needVTK);
}

LoadedDataset Load(const Arguments& a, const std::string& spec, bool needValues, bool needVTK)
{
  SetProgressQuiet(a.Has("quiet"));
  DatasetRequest r;
  r.Spec = spec;
  r.Array = a.Get("array", "");
  r.Component = static_cast<int>(a.GetNumber("component", -1));
  r.Centering = a.Get("centering", "auto");
  r.NeedValues = needValues;
  r.NeedVTK = needVTK;
  if (a.Has("allow-partial") && a.Has("strict"))
  {
    throw UsageError{ "--allow-partial and --strict contradict each other" };
  }
  r.AllowPartial = a.Has("allow-partial");
  r.ReadTimeoutSeconds = a.GetNumber("read-timeout", 120.0);
  if (!(r.ReadTimeoutSeconds > 0.0))
  {
    throw UsageError{ "--read-timeout must be a positive number of seconds" };
  }
  return LoadDataset(r);
}

void WritePng(const Image& img, const std::string& path)
{
  vtkNew<vtkImageData> data;
  data->SetDimensions(img.Width, img.Height, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(img.Width) * img.Height);
  const std::vector<std::uint8_t> bytes = img.Rgb8();
  std::copy(bytes.begin(), bytes.end(), rgb->GetPointer(0));
  data->GetPointData()->SetScalars(rgb);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(data);
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    throw DatasetError("cannot write " + path);
  }
}

Json BoxJson(const glm::dvec3& lo, const glm::dvec3& hi)
{
  return Json::array({ lo.x, hi.x, lo.y, hi.y, lo.z, hi.z });
}

Json TextureJson(const UIntTexture3D& t)
{
  return Json{ { "dims", { t.Dims.x, t.Dims.y, t.Dims.z } }, { "bytes", t.Bytes() } };
}

bool WantsHelp(const Arguments& a)
{
  return a.Has("help");
}

} // namespace tool
} // namespace amrsp
