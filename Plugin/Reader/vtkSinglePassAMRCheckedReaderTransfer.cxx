// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRCheckedReaderTransfer.h"

#include "AmrspChildProcess.h"

#include "vtkCellData.h"
#include "vtkCharArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkSinglePassAMRDataModel.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace vtkSinglePassAMRCheckedReaderTransfer
{
namespace
{
// Layout: a tag ('R' raw blocks, 'M' the whole AMR marshalled), the marshalled bytes' count
// (uint64) and bytes, then for 'R' every block in level order: its class (uint8: 0 none, 1
// vtkImageData, 2 vtkUniformGrid); when present
// its dimensions (3 x int32), origin and spacing (6 x double), the cell and the point arrays
// (each: count (uint32), then per array the name's length (uint32) and characters, VTK type,
// components (2 x int32), tuples (int64) and the values' bytes).

struct Writer
{
  explicit Writer(int fd)
    : Fd(fd)
  {
  }
  int Fd;
  std::string Buffer; // flushed past 16 MiB: one write per array at most besides
  bool Ok = true;
  void Raw(const void* p, std::size_t n)
  {
    Buffer.append(static_cast<const char*>(p), n);
    if (Buffer.size() > (std::size_t(16) << 20))
    {
      Flush();
    }
  }
  template <typename T>
  void Value(T v)
  {
    Raw(&v, sizeof(v));
  }
  void Large(const void* p, std::size_t n)
  {
    Flush();
    Ok = Ok && amrsp::harness::WriteAll(Fd, p, n);
  }
  void Flush()
  {
    Ok = Ok && amrsp::harness::WriteAll(Fd, Buffer.data(), Buffer.size());
    Buffer.clear();
  }
};

struct Reader
{
  Reader(const char* at, const char* end)
    : At(at)
    , End(end)
  {
  }
  const char* At;
  const char* End;
  bool Ok = true;
  const char* Take(std::size_t n)
  {
    if (!Ok || n > static_cast<std::size_t>(End - At))
    {
      Ok = false;
      return nullptr;
    }
    const char* p = At;
    At += n;
    return p;
  }
  template <typename T>
  T Value()
  {
    T v{};
    const char* p = Take(sizeof(T));
    if (p)
    {
      std::memcpy(&v, p, sizeof(T));
    }
    return v;
  }
};

bool Marshal(vtkDataObject* object, Writer& out)
{
  vtkNew<vtkCharArray> bytes;
  if (!vtkCommunicator::MarshalDataObject(object, bytes))
  {
    return false;
  }
  out.Value(static_cast<uint64_t>(bytes->GetNumberOfValues()));
  out.Large(bytes->GetPointer(0), static_cast<std::size_t>(bytes->GetNumberOfValues()));
  return true;
}

void WriteArrays(vtkFieldData* arrays, Writer& out)
{
  std::vector<vtkDataArray*> numeric;
  for (int i = 0; i < arrays->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = arrays->GetArray(i);
    if (a && a->GetName() && a->HasStandardMemoryLayout())
    {
      numeric.push_back(a);
    }
  }
  out.Value(static_cast<uint32_t>(numeric.size()));
  for (vtkDataArray* a : numeric)
  {
    const std::string name = a->GetName();
    out.Value(static_cast<uint32_t>(name.size()));
    out.Raw(name.data(), name.size());
    out.Value(static_cast<int32_t>(a->GetDataType()));
    out.Value(static_cast<int32_t>(a->GetNumberOfComponents()));
    out.Value(static_cast<int64_t>(a->GetNumberOfTuples()));
    const std::size_t bytes = static_cast<std::size_t>(a->GetNumberOfValues()) *
      static_cast<std::size_t>(a->GetDataTypeSize());
    out.Value(static_cast<uint64_t>(bytes));
    out.Large(a->GetVoidPointer(0), bytes);
  }
}

bool ReadArrays(Reader& in, vtkFieldData* arrays)
{
  const uint32_t count = in.Value<uint32_t>();
  for (uint32_t i = 0; in.Ok && i < count; ++i)
  {
    const uint32_t nameBytes = in.Value<uint32_t>();
    const char* name = in.Take(nameBytes);
    const int32_t type = in.Value<int32_t>();
    const int32_t components = in.Value<int32_t>();
    const int64_t tuples = in.Value<int64_t>();
    const uint64_t bytes = in.Value<uint64_t>();
    const char* values = in.Take(static_cast<std::size_t>(bytes));
    vtkSmartPointer<vtkDataArray> a;
    if (in.Ok && components > 0 && tuples >= 0)
    {
      a = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(type));
    }
    if (!a)
    {
      return false;
    }
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(tuples);
    if (static_cast<uint64_t>(a->GetNumberOfValues()) * a->GetDataTypeSize() != bytes)
    {
      return false;
    }
    std::memcpy(a->GetVoidPointer(0), values, static_cast<std::size_t>(bytes));
    a->SetName(std::string(name, nameBytes).c_str());
    arrays->AddArray(a);
  }
  return in.Ok;
}
} // namespace

bool Write(vtkOverlappingAMR* amr, int fd)
{
  Writer out(fd);
  bool images = true;
  const unsigned int levels = amr->GetNumberOfLevels();
  for (unsigned int l = 0; l < levels; ++l)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(amr, l); ++i)
    {
      vtkDataSet* block = vtkSinglePassAMRDataModel::Block(amr, l, i);
      images = images && (!block || vtkImageData::SafeDownCast(block));
    }
  }
  if (!images)
  {
    out.Value('M');
    if (!Marshal(amr, out))
    {
      return false;
    }
    out.Flush();
    return out.Ok;
  }
  out.Value('R');
  vtkNew<vtkOverlappingAMR> structure;
  vtkSinglePassAMRDataModel::CopyStructure(amr, structure);
  if (!Marshal(structure, out))
  {
    return false;
  }
  for (unsigned int l = 0; l < levels; ++l)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(amr, l); ++i)
    {
      vtkImageData* image = vtkImageData::SafeDownCast(vtkSinglePassAMRDataModel::Block(amr, l, i));
      // the block's own class, so that the parent's AMR is what VTK's reader made
      out.Value(static_cast<uint8_t>(!image ? 0 : image->IsA("vtkUniformGrid") ? 2 : 1));
      if (!image)
      {
        continue;
      }
      int dims[3];
      double origin[3], spacing[3];
      image->GetDimensions(dims);
      image->GetOrigin(origin);
      image->GetSpacing(spacing);
      out.Raw(dims, sizeof(dims));
      out.Raw(origin, sizeof(origin));
      out.Raw(spacing, sizeof(spacing));
      WriteArrays(image->GetCellData(), out);
      WriteArrays(image->GetPointData(), out);
    }
  }
  out.Flush();
  return out.Ok;
}

vtkSmartPointer<vtkOverlappingAMR> Read(const char* data, std::size_t bytes)
{
  Reader in(data, data + bytes);
  const char tag = in.Value<char>();
  const uint64_t marshalled = in.Value<uint64_t>();
  const char* structureBytes = in.Take(static_cast<std::size_t>(marshalled));
  if (!in.Ok || (tag != 'R' && tag != 'M'))
  {
    return nullptr;
  }
  vtkNew<vtkCharArray> buffer;
  buffer->SetArray(const_cast<char*>(structureBytes), static_cast<vtkIdType>(marshalled), 1);
  auto amr = vtkSmartPointer<vtkOverlappingAMR>::New();
  if (!vtkCommunicator::UnMarshalDataObject(buffer, amr))
  {
    return nullptr;
  }
  if (tag == 'M')
  {
    return amr;
  }
  for (unsigned int l = 0; l < amr->GetNumberOfLevels(); ++l)
  {
    for (unsigned int i = 0; i < vtkSinglePassAMRDataModel::NumberOfBlocks(amr, l); ++i)
    {
      const uint8_t kind = in.Value<uint8_t>();
      if (kind == 0)
      {
        continue;
      }
      int dims[3];
      double origin[3], spacing[3];
      const char* d = in.Take(sizeof(dims));
      const char* o = in.Take(sizeof(origin));
      const char* s = in.Take(sizeof(spacing));
      if (!in.Ok)
      {
        return nullptr;
      }
      std::memcpy(dims, d, sizeof(dims));
      std::memcpy(origin, o, sizeof(origin));
      std::memcpy(spacing, s, sizeof(spacing));
#ifdef AMRSP_VTK_AMR_DATA_OBJECT
      // VTK 9.6 takes image data or its subclass vtkUniformGrid, whichever the reader made
      vtkSmartPointer<vtkImageData> image = kind == 2
        ? vtkSmartPointer<vtkImageData>(vtkSmartPointer<vtkUniformGrid>::New())
        : vtkSmartPointer<vtkImageData>::New();
#else
      (void)kind; // before 9.6 every AMR block is a vtkUniformGrid
      vtkNew<vtkUniformGrid> image;
#endif
      image->SetDimensions(dims);
      image->SetOrigin(origin);
      image->SetSpacing(spacing);
      if (!ReadArrays(in, image->GetCellData()) || !ReadArrays(in, image->GetPointData()))
      {
        return nullptr;
      }
      vtkSinglePassAMRDataModel::SetBlock(amr, l, i, image);
    }
  }
  return in.Ok ? amr : nullptr;
}
}
