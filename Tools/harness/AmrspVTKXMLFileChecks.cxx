// SPDX-License-Identifier: BSD-3-Clause
// The VTK XML AMR checks of AmrspFileChecks.h: the .vthb/.vth/.vtm XML and every .vti piece.
#include "AmrspFileChecks.h"

#include "AmrspDatasetError.h"
#include "AmrspFileCheckTools.h"

#include "vtkNew.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace amrsp
{
namespace harness
{
using namespace filechecks;
namespace fs = std::filesystem;

namespace
{
/// The integer or float values of attribute `name` of the first tag `tag` in `head`; false when
/// the tag or the attribute is missing.
bool XMLAttribute(
  const std::string& head, const std::string& tag, const std::string& name, std::string& value)
{
  const std::size_t at = head.find("<" + tag);
  if (at == std::string::npos)
  {
    return false;
  }
  const std::size_t end = head.find('>', at);
  const std::string element =
    head.substr(at, end == std::string::npos ? std::string::npos : end - at);
  const std::size_t a = element.find(" " + name + "=\"");
  if (a == std::string::npos)
  {
    return false;
  }
  const std::size_t from = a + name.size() + 3;
  const std::size_t to = element.find('"', from);
  value = element.substr(from, to == std::string::npos ? std::string::npos : to - from);
  return true;
}

/// `count` numbers of `value` (the whole list), false otherwise.
template <typename T>
bool Numbers(const std::string& value, std::size_t count, std::vector<T>& out)
{
  std::istringstream in(value);
  out.clear();
  T v;
  while (in >> v)
  {
    out.push_back(v);
  }
  return in.eof() && out.size() == count;
}
} // namespace

std::vector<long long> CheckVTIPiece(const std::string& piece, const std::string& role)
{
  const unsigned long long size = FileSize(piece);
  const std::string damaged = "the piece file " + piece + " (" + role + ") is ";
  if (size == 0)
  {
    throw DatasetError(damaged + "empty");
  }
  // the XML head, before the data: at most 1 MiB
  std::ifstream in(piece, std::ios::binary);
  std::string head(static_cast<std::size_t>(std::min<unsigned long long>(size, 1 << 20)), '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  const std::size_t data = std::min(head.find("<AppendedData"), head.find("</ImageData"));
  if (data != std::string::npos)
  {
    head.resize(data);
  }
  std::string value;
  std::vector<long long> extent;
  if (!XMLAttribute(head, "ImageData", "WholeExtent", value) || !Numbers(value, 6, extent))
  {
    throw DatasetError(damaged +
      "damaged: no ImageData element with a WholeExtent of six "
      "integers (truncated, or another kind of file)");
  }
  for (int a = 0; a < 3; ++a)
  {
    if (extent[2 * a + 1] < extent[2 * a] || extent[2 * a + 1] - extent[2 * a] > (1LL << 24) ||
      std::llabs(extent[2 * a]) > (1LL << 30))
    {
      throw DatasetError(damaged + "damaged: WholeExtent " + value +
        " (expected each upper index not below its lower one, at most 2^24 apart)");
    }
  }
  // each piece's extent inside the whole extent: VTK's reader allocates a piece's arrays from it
  for (std::size_t at = head.find("<Piece"); at != std::string::npos;
       at = head.find("<Piece", at + 1))
  {
    std::vector<long long> pieceExtent;
    std::string pieceValue;
    if (!XMLAttribute(head.substr(at), "Piece", "Extent", pieceValue) ||
      !Numbers(pieceValue, 6, pieceExtent) || pieceExtent[0] < extent[0] ||
      pieceExtent[1] > extent[1] || pieceExtent[2] < extent[2] || pieceExtent[3] > extent[3] ||
      pieceExtent[4] < extent[4] || pieceExtent[5] > extent[5] || pieceExtent[1] < pieceExtent[0] ||
      pieceExtent[3] < pieceExtent[2] || pieceExtent[5] < pieceExtent[4])
    {
      throw DatasetError(damaged + "damaged: a Piece has Extent=\"" + pieceValue +
        "\" (expected six integers inside the WholeExtent " + value + ")");
    }
  }
  std::vector<double> spacing, origin;
  if (XMLAttribute(head, "ImageData", "Spacing", value) &&
    (!Numbers(value, 3, spacing) ||
      !std::all_of(
        spacing.begin(), spacing.end(), [](double s) { return std::isfinite(s) && s > 0.0; })))
  {
    throw DatasetError(damaged + "damaged: Spacing " + value +
      " (expected three finite "
      "positive numbers)");
  }
  if (XMLAttribute(head, "ImageData", "Origin", value) &&
    (!Numbers(value, 3, origin) ||
      !std::all_of(origin.begin(), origin.end(), [](double o) { return std::isfinite(o); })))
  {
    throw DatasetError(damaged + "damaged: Origin " + value + " (expected three finite numbers)");
  }
  // every array's component count: VTK allocates components x tuples before it reads a byte
  for (std::size_t at = head.find("NumberOfComponents=\""); at != std::string::npos;
       at = head.find("NumberOfComponents=\"", at + 1))
  {
    const std::size_t from = at + 20, to = head.find('"', from);
    const std::string n = head.substr(from, to == std::string::npos ? 0 : to - from);
    std::vector<long long> components;
    if (!Numbers(n, 1, components) || components[0] < 1 || components[0] > 64)
    {
      throw DatasetError(damaged + "damaged: NumberOfComponents=\"" + n + "\" (expected 1 to 64)");
    }
  }
  if (head.find("<DataArray") == std::string::npos)
  {
    throw DatasetError(damaged + "damaged or empty: it holds no DataArray");
  }
  return { extent[1] - extent[0], extent[3] - extent[2], extent[5] - extent[4] };
}

ExpectedBlocks CheckVTKXMLAMRFiles(const std::string& path)
{
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(path.c_str());
  if (!parser->Parse() || !parser->GetRootElement())
  {
    throw DatasetError("the VTK XML AMR file " + path +
      " is truncated or damaged: its XML does "
      "not parse");
  }
  vtkXMLDataElement* top = parser->GetRootElement();
  vtkXMLDataElement* root = top->GetNumberOfNestedElements() > 0 ? top->GetNestedElement(0) : top;
  std::map<std::pair<int, int>, std::string> blocks;
  for (int b = 0; b < root->GetNumberOfNestedElements(); ++b)
  {
    vtkXMLDataElement* block = root->GetNestedElement(b);
    int level = 0;
    if (std::string(block->GetName()) != "Block" || !block->GetScalarAttribute("level", level))
    {
      continue;
    }
    const std::string damaged = "the VTK XML AMR file " + path + " is damaged: ";
    if (level < 0 || level >= 64)
    {
      throw DatasetError(
        damaged + "a Block has level=\"" + std::to_string(level) + "\" (expected 0 to 63)");
    }
    double spacing[3];
    if (block->GetAttribute("spacing") &&
      (block->GetVectorAttribute("spacing", 3, spacing) != 3 ||
        !std::all_of(spacing, spacing + 3, [](double s) { return std::isfinite(s) && s > 0.0; })))
    {
      throw DatasetError(damaged + "level " + std::to_string(level) + " has spacing=\"" +
        block->GetAttribute("spacing") + "\" (expected three finite positive numbers)");
    }
    for (int d = 0; d < block->GetNumberOfNestedElements(); ++d)
    {
      vtkXMLDataElement* data = block->GetNestedElement(d);
      int index = 0;
      const char* file = data->GetAttribute("file");
      if (std::string(data->GetName()) != "DataSet" || !data->GetScalarAttribute("index", index))
      {
        continue;
      }
      const std::string block =
        "block " + std::to_string(index) + " of level " + std::to_string(level);
      if (index < 0 || index >= (1 << 20))
      {
        throw DatasetError(damaged + "a DataSet of level " + std::to_string(level) +
          " has index=\"" + std::to_string(index) + "\" (expected 0 to 2^20 - 1)");
      }
      if (blocks.count({ level, index }))
      {
        throw DatasetError(damaged + "two DataSet elements are " + block);
      }
      int box[6] = { 0, 0, 0, 0, 0, 0 };
      const bool hasBox = data->GetAttribute("amr_box") != nullptr;
      if (hasBox &&
        (data->GetVectorAttribute("amr_box", 6, box) != 6 || box[1] < box[0] || box[3] < box[2] ||
          box[5] < box[4] || !std::all_of(box, box + 6, [](int v) { return WithinIndexRange(v); })))
      {
        throw DatasetError(damaged + block + " has amr_box=\"" + data->GetAttribute("amr_box") +
          "\" (expected six integers within +-2^30, each upper index not below its lower one)");
      }
      std::string piece;
      if (file)
      {
        piece = (fs::path(path).parent_path() / file).string();
        std::error_code ec;
        if (!fs::exists(piece, ec))
        {
          throw DatasetError(
            "the piece file " + piece + " of " + block + " in " + path + " is missing");
        }
        const std::vector<long long> cells = CheckVTIPiece(piece, block + " in " + path);
        for (int a = 0; a < 3 && hasBox; ++a)
        {
          // a piece's extent counts points: one more than the box's cells (or 0 on a flat axis)
          const long long boxCells = static_cast<long long>(box[2 * a + 1]) - box[2 * a] + 1;
          if (cells[a] != boxCells && !(cells[a] == 0 && boxCells == 1))
          {
            throw DatasetError("the piece file " + piece + " of " + block + " in " + path +
              " holds " + std::to_string(cells[a]) + " cells on axis " + std::to_string(a) +
              ", its amr_box " + std::to_string(boxCells) + " (a piece of another block?)");
          }
        }
      }
      blocks[{ level, index }] = piece;
    }
  }
  ExpectedBlocks expected;
  for (const auto& b : blocks)
  {
    expected.Files.push_back(b.second);
  }
  return expected;
}
} // namespace harness
} // namespace amrsp
