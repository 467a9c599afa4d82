// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRKdTreeVolumeMapper.h"
#include "vtkSinglePassAMRDataModel.h"

#include "vtkAMRMapperConversion.h"
#include "vtkAMRMapperContextCapabilities.h"

#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOverlappingAMR.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <chrono>

//------------------------------------------------------------------------------
vtkAMRKdTreeVolumeMapper::vtkAMRKdTreeVolumeMapper() = default;

//------------------------------------------------------------------------------
vtkAMRKdTreeVolumeMapper::~vtkAMRKdTreeVolumeMapper() = default;

//------------------------------------------------------------------------------
void vtkAMRKdTreeVolumeMapper::BeginProgressPhase(int phase, const char* text)
{
  this->ProgressPhase = phase;
  this->SetProgressText(text);
  this->UpdateProgress(0.0);
}

//------------------------------------------------------------------------------
int vtkAMRKdTreeVolumeMapper::FillInputPortInformation(int vtkNotUsed(port), vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkOverlappingAMR");
  return 1;
}

//------------------------------------------------------------------------------
void vtkAMRKdTreeVolumeMapper::SetInputData(vtkOverlappingAMR* input)
{
  this->SetInputDataInternal(0, input);
}

void vtkAMRKdTreeVolumeMapper::SetInputData(vtkImageData*)
{
  vtkErrorMacro(<< this->GetClassName() << " renders vtkOverlappingAMR only");
}

void vtkAMRKdTreeVolumeMapper::SetInputData(vtkDataSet*)
{
  vtkErrorMacro(<< this->GetClassName() << " renders vtkOverlappingAMR only");
}

void vtkAMRKdTreeVolumeMapper::SetInputData(vtkRectilinearGrid*)
{
  vtkErrorMacro(<< this->GetClassName() << " renders vtkOverlappingAMR only");
}

//------------------------------------------------------------------------------
vtkOverlappingAMR* vtkAMRKdTreeVolumeMapper::GetAMRInput()
{
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return nullptr;
  }
  return vtkOverlappingAMR::SafeDownCast(this->GetInputDataObject(0, 0));
}

//------------------------------------------------------------------------------
double* vtkAMRKdTreeVolumeMapper::GetBounds()
{
  vtkMath::UninitializeBounds(this->Bounds);
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    return this->Bounds;
  }
  this->Update();
  vtkOverlappingAMR* amr = this->GetAMRInput();
  // An AMR without metadata or blocks (e.g. the empty placeholder a ParaView view's producer
  // holds until it delivers data) has no bounds; it is not built, so the textures of the last
  // real input stay valid and no build is counted.
  if (!amr || !vtkSinglePassAMRDataModel::HasMetaData(amr) ||
    vtkSinglePassAMRDataModel::NumberOfBlocks(amr) == 0)
  {
    return this->Bounds;
  }
  if (this->EnsureBuilt(amr))
  {
    this->GetBuiltBounds(this->Bounds);
    return this->Bounds;
  }
  // the conversion failed (Render reports why): the AMR's own overall bounds
  amr->GetBounds(this->Bounds);
  return this->Bounds;
}

void vtkAMRKdTreeVolumeMapper::GetBounds(double bounds[6])
{
  const double* b = this->GetBounds();
  std::copy(b, b + 6, bounds);
}

//------------------------------------------------------------------------------
bool vtkAMRKdTreeVolumeMapper::IsRenderSupported(vtkRenderWindow* window, std::string* why)
{
  return vtkAMRMapperContextCapabilities::IsRenderSupported(window, why);
}

//------------------------------------------------------------------------------
bool vtkAMRKdTreeVolumeMapper::EnsureBuilt(vtkOverlappingAMR* amr)
{
  const std::string array = vtkAMRMapperConversion::RequestedArray(
    amr, this->ArrayAccessMode, this->ArrayName, this->ArrayId);
  const bool sameSettings = this->BuiltArray == array &&
    this->BuiltComponent == this->ArrayComponent &&
    this->BuiltPackLimit == this->MaximumAtlasSize &&
    this->BuiltPageBytes == this->MaximumAtlasPageBytes &&
    this->BuiltPacked == this->BuildPacksBricks();
  if (!this->Built || this->BuiltInput != amr || this->BuiltInputMTime != amr->GetMTime() ||
    !sameSettings)
  {
    // only the input changed since a build that succeeded: its structure may be kept
    const bool mayRefresh = this->Built && this->DataValid && sameSettings;
    this->BuiltInput = amr;
    this->BuiltInputMTime = amr->GetMTime();
    this->BuiltArray = array;
    this->BuiltComponent = this->ArrayComponent;
    this->BuiltPackLimit = this->MaximumAtlasSize;
    this->BuiltPageBytes = this->MaximumAtlasPageBytes;
    this->RunBuild(amr, mayRefresh);
  }
  return this->DataValid;
}

//------------------------------------------------------------------------------
bool vtkAMRKdTreeVolumeMapper::Rebuild(vtkOverlappingAMR* amr)
{
  return this->RunBuild(amr);
}

//------------------------------------------------------------------------------
bool vtkAMRKdTreeVolumeMapper::RunBuild(vtkOverlappingAMR* amr, bool mayRefresh)
{
  const auto t0 = std::chrono::steady_clock::now();
  this->Built = true;
  this->BuiltPacked = this->BuildPacksBricks();
  this->DataValid = false;
  this->BuildError.clear();
  ++this->NumberOfBuilds;
  std::string error;
  bool refreshed = false;
  const bool ok = this->BuildData(amr, this->BuiltArray, mayRefresh, refreshed, error);
  this->LastBuildRefreshed = ok && refreshed;
  this->NumberOfValueRefreshes += this->LastBuildRefreshed ? 1 : 0;
  if (!ok)
  {
    this->BuildError = error.empty() ? "the AMR input could not be prepared for rendering" : error;
    return false;
  }
  this->DataValid = true;
  this->BuildTime.Modified();
  this->BuildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

//------------------------------------------------------------------------------
vtkOverlappingAMR* vtkAMRKdTreeVolumeMapper::BeginFrame(
  vtkRenderer* ren, vtkOpenGLRenderWindow*& renWin)
{
  this->PreviousError = this->LastError;
  this->LastError.clear();
  renWin = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!renWin)
  {
    this->ReportError(std::string(this->GetClassName()) + " needs an OpenGL render window");
    return nullptr;
  }
  vtkOverlappingAMR* amr = nullptr;
  if (this->GetNumberOfInputConnections(0) < 1)
  {
    this->ReportError("no input: set a vtkOverlappingAMR with SetInputData or SetInputConnection");
  }
  else
  {
    this->Update();
    amr = this->GetAMRInput();
    if (!amr)
    {
      vtkDataObject* given = this->GetInputDataObject(0, 0);
      this->ReportError(std::string("the input is ") +
        (given ? std::string("a ") + given->GetClassName() : std::string("empty")) +
        ", not a vtkOverlappingAMR (levels of blocks with their boxes, spacing and refinement "
        "ratios)");
    }
  }
  if (!amr)
  {
    renWin = nullptr;
  }
  return amr;
}

//------------------------------------------------------------------------------
void vtkAMRKdTreeVolumeMapper::ReportError(const std::string& message)
{
  if (message != this->PreviousError)
  {
    vtkErrorMacro(<< message);
  }
  this->LastError = message;
}

//------------------------------------------------------------------------------
void vtkAMRKdTreeVolumeMapper::WarnOnce(const std::string& message)
{
  if (this->Warned.insert(message).second)
  {
    vtkWarningMacro(<< message);
  }
}

//------------------------------------------------------------------------------
const char* vtkAMRKdTreeVolumeMapper::GetLastError()
{
  return this->LastError.c_str();
}

int vtkAMRKdTreeVolumeMapper::GetNumberOfValueRefreshes()
{
  return this->NumberOfValueRefreshes;
}

//------------------------------------------------------------------------------
bool vtkAMRKdTreeVolumeMapper::GetLastBuildRefreshedValues()
{
  return this->LastBuildRefreshed;
}

//------------------------------------------------------------------------------
double vtkAMRKdTreeVolumeMapper::GetLastBuildSeconds()
{
  return this->BuildSeconds;
}

double vtkAMRKdTreeVolumeMapper::GetLastUploadSeconds()
{
  return this->UploadSeconds;
}

int vtkAMRKdTreeVolumeMapper::GetNumberOfBuilds()
{
  return this->NumberOfBuilds;
}

//------------------------------------------------------------------------------
void vtkAMRKdTreeVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ArrayComponent: " << this->ArrayComponent << "\n";
  os << indent << "SampleDistanceFactor: " << this->SampleDistanceFactor << "\n";
  os << indent << "MaximumAtlasSize: " << this->MaximumAtlasSize << "\n";
  os << indent << "MaximumAtlasPageBytes: " << this->MaximumAtlasPageBytes << "\n";
  os << indent << "UseDepthBuffer: " << (this->UseDepthBuffer ? "on" : "off") << "\n";
  os << indent << "NumberOfBuilds: " << this->NumberOfBuilds << "\n";
  os << indent << "LastError: " << (this->LastError.empty() ? "(none)" : this->LastError) << "\n";
}
