// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspFileChecks.h"

#include "AmrspDataset.h"

#include "vtkNew.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace amrsp
{
namespace harness
{
namespace
{
namespace fs = std::filesystem;

std::string ReadWhole(const fs::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Bytes(unsigned long long n)
{
  std::string digits = std::to_string(n);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3)
  {
    digits.insert(static_cast<std::size_t>(i), ",");
  }
  return digits + (n == 1 ? " byte" : " bytes");
}

unsigned long long FileSize(const fs::path& path)
{
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  return ec ? 0 : static_cast<unsigned long long>(size);
}

/// Little-endian unsigned integer of `n` bytes at `p`.
unsigned long long LittleEndian(const unsigned char* p, int n)
{
  unsigned long long v = 0;
  for (int i = n - 1; i >= 0; --i)
  {
    v = (v << 8) | p[i];
  }
  return v;
}

// ---- Enzo ------------------------------------------------------------------------------------

/// One "Grid = N" entry of an Enzo hierarchy: the keys it holds and where it starts.
struct EnzoEntry
{
  long long Number = 0;
  std::map<std::string, std::string> Values;
  std::vector<long long> Pointers; // grids named by its Pointer: lines (0 = none)
  int PointerLines = 0;
  std::size_t Offset = 0;
};

std::string Trim(const std::string& s)
{
  const std::size_t a = s.find_first_not_of(" \t\r");
  const std::size_t b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}
} // namespace

bool CheckHDF5File(const std::string& path, std::string& why)
{
  static const unsigned char signature[8] = { 0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n' };
  const unsigned long long size = FileSize(path);
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    why = "cannot be opened";
    return false;
  }
  // the superblock sits at 0 or after a user block of 512, 1024, 2048, ... bytes
  for (unsigned long long at = 0; at + 8 <= size; at = at == 0 ? 512 : 2 * at)
  {
    unsigned char head[64] = {};
    in.clear();
    in.seekg(static_cast<std::streamoff>(at));
    in.read(reinterpret_cast<char*>(head), sizeof(head));
    const std::streamsize got = in.gcount();
    if (got < 8 || !std::equal(signature, signature + 8, head))
    {
      continue;
    }
    const int version = head[8];
    int offsets = 0, eofAt = 0;
    if (version == 0 || version == 1)
    {
      offsets = head[13];
      eofAt = (version == 0 ? 24 : 28) + 2 * offsets;
    }
    else if (version == 2 || version == 3)
    {
      offsets = head[9];
      eofAt = 12 + 2 * offsets;
    }
    else
    {
      why = "has an HDF5 superblock of unknown version " + std::to_string(version);
      return false;
    }
    if ((offsets != 4 && offsets != 8) || eofAt + offsets > got)
    {
      why = "has a damaged HDF5 superblock (address size " + std::to_string(offsets) + ")";
      return false;
    }
    const int baseAt = version <= 1 ? eofAt - 2 * offsets : 12;
    const unsigned long long base = LittleEndian(head + baseAt, offsets);
    const unsigned long long end = base + LittleEndian(head + eofAt, offsets);
    if (end > size)
    {
      why = "is truncated: it has " + Bytes(size) + ", its HDF5 superblock says " + Bytes(end);
      return false;
    }
    return true;
  }
  why = "is not an HDF5 file (no HDF5 signature: its first bytes are damaged or it is "
        "another kind of file)";
  return false;
}

namespace
{
/// The grid entries of an Enzo hierarchy's text, each with its keys and the Pointer lines that
/// name it; throws DatasetError naming the line where the numbering or a Pointer line is wrong.
std::vector<EnzoEntry> ParseEnzoEntries(const std::string& text, const std::string& name)
{
  std::vector<EnzoEntry> entries;
  std::size_t at = 0;
  while (at < text.size())
  {
    std::size_t end = text.find('\n', at);
    const bool lastLine = end == std::string::npos;
    const std::string line = Trim(text.substr(at, lastLine ? std::string::npos : end - at));
    const std::size_t lineStart = at;
    at = lastLine ? text.size() : end + 1;
    if (line.empty())
    {
      continue;
    }
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos)
    {
      continue;
    }
    const std::string key = Trim(line.substr(0, eq));
    const std::string value = Trim(line.substr(eq + 1));
    if (key == "Grid")
    {
      EnzoEntry e;
      e.Offset = lineStart;
      try
      {
        e.Number = std::stoll(value);
      }
      catch (const std::exception&)
      {
        throw DatasetError("the Enzo hierarchy " + name + " is damaged: 'Grid = " + value +
          "' at byte " + std::to_string(lineStart) + " is no grid number");
      }
      if (e.Number != static_cast<long long>(entries.size()) + 1)
      {
        throw DatasetError("the Enzo hierarchy " + name + " is damaged: grid " +
          std::to_string(e.Number) + " at byte " + std::to_string(lineStart) + " follows grid " +
          std::to_string(entries.size()) + " (the grids must be numbered 1, 2, 3, ...)");
      }
      entries.push_back(e);
      continue;
    }
    if (entries.empty())
    {
      continue;
    }
    if (key.rfind("Pointer:", 0) == 0)
    {
      // "Pointer: Grid[N]->NextGridThisLevel = M": Enzo writes a grid's pointers where its
      // subtree ends, so they belong to grid N, not to the entry they follow
      const std::size_t open = key.find('['), close = key.find(']');
      long long grid = -1, target = -1;
      try
      {
        grid = std::stoll(key.substr(open + 1, close - open - 1));
        target = std::stoll(value);
      }
      catch (const std::exception&)
      {
      }
      if (open == std::string::npos || close == std::string::npos || grid < 1 ||
        grid > static_cast<long long>(entries.size()))
      {
        throw DatasetError("the Enzo hierarchy " + name + " is damaged: '" + line + "' at byte " +
          std::to_string(lineStart) + " names no grid described before it");
      }
      EnzoEntry& owner = entries[static_cast<std::size_t>(grid - 1)];
      ++owner.PointerLines;
      owner.Pointers.push_back(target);
    }
    else
    {
      entries.back().Values[key] = value;
    }
  }
  return entries;
}

/// Throws DatasetError when there is no entry, when an entry lacks a key or its Pointer lines (a
/// file cut inside it), or when it points past the last grid.
void CheckEnzoEntriesComplete(
  const std::vector<EnzoEntry>& entries, const std::string& name, std::size_t textBytes)
{
  if (entries.empty())
  {
    throw DatasetError("the Enzo hierarchy " + name + " describes no grid ('Grid = 1' missing)");
  }
  // an entry ends with its two Pointer lines; a file cut inside an entry lacks them (or keys)
  static const char* required[] = { "GridDimension", "GridStartIndex", "GridEndIndex",
    "GridLeftEdge", "GridRightEdge", "NumberOfBaryonFields" };
  const long long count = static_cast<long long>(entries.size());
  for (const EnzoEntry& e : entries)
  {
    std::string missing;
    for (const char* key : required)
    {
      if (!e.Values.count(key))
      {
        missing += missing.empty() ? key : std::string(", ") + key;
      }
    }
    if (!missing.empty())
    {
      throw DatasetError("the Enzo hierarchy " + name +
        " is truncated or damaged: the entry of "
        "grid " +
        std::to_string(e.Number) + " (from byte " + std::to_string(e.Offset) + " of " +
        std::to_string(textBytes) + ") lacks " + missing);
    }
    if (e.PointerLines < 2)
    {
      throw DatasetError("the Enzo hierarchy " + name + " is truncated or damaged: the " +
        std::to_string(textBytes) + "-byte file ends before the Pointer lines of grid " +
        std::to_string(e.Number) + " of " + std::to_string(count));
    }
    for (long long p : e.Pointers)
    {
      if (p < 0 || p > count)
      {
        throw DatasetError("the Enzo hierarchy " + name + " is truncated or damaged: grid " +
          std::to_string(e.Number) + " points to grid " + std::to_string(p) + ", but the file " +
          "describes " + std::to_string(count) + " grids");
      }
    }
  }
}

/// Each grid's HDF5 file next to the hierarchy at `path`, checked once per file.
ExpectedBlocks EnzoGridFiles(
  const std::vector<EnzoEntry>& entries, const fs::path& path, const std::string& name)
{
  const long long count = static_cast<long long>(entries.size());
  // each grid's HDF5 file: the hierarchy names it with the path of the machine that wrote it;
  // VTK's reader (and so this check) looks for its file name next to the hierarchy
  ExpectedBlocks expected;
  std::map<std::string, std::string> checked; // file -> problem ("" when fine)
  for (const EnzoEntry& e : entries)
  {
    std::string fields = e.Values.at("NumberOfBaryonFields");
    auto file = e.Values.find("BaryonFileName");
    if (file == e.Values.end())
    {
      if (fields != "0")
      {
        throw DatasetError("the Enzo hierarchy " + name + " is damaged: grid " +
          std::to_string(e.Number) + " has " + fields + " fields but no BaryonFileName");
      }
      expected.Files.push_back("");
      continue;
    }
    const fs::path grid = path.parent_path() / fs::path(file->second).filename();
    const std::string key = grid.string();
    if (!checked.count(key))
    {
      std::string why;
      std::error_code ec;
      if (!fs::exists(grid, ec))
      {
        why = "is missing";
      }
      else
      {
        CheckHDF5File(key, why);
      }
      checked[key] = why;
    }
    if (!checked[key].empty())
    {
      throw DatasetError("the Enzo grid file " + key + " (the data of grid " +
        std::to_string(e.Number) + " of " + std::to_string(count) + " in " + name + ") " +
        checked[key]);
    }
    expected.Files.push_back(key);
  }
  return expected;
}
} // namespace

ExpectedBlocks CheckEnzoFiles(const std::string& hierarchy)
{
  const fs::path path(hierarchy);
  const std::string text = ReadWhole(path);
  const std::string name = hierarchy;
  if (text.empty())
  {
    throw DatasetError("the Enzo hierarchy " + name + " is empty");
  }
  const std::vector<EnzoEntry> entries = ParseEnzoEntries(text, name);
  CheckEnzoEntriesComplete(entries, name, text.size());
  return EnzoGridFiles(entries, path, name);
}

// ---- AMReX -----------------------------------------------------------------------------------

namespace
{
/// Whitespace-separated reading of an AMReX header with a description of what comes next, so
/// that a file that ends early or holds something else says what was expected where.
class HeaderTokens
{
public:
  HeaderTokens(const std::string& text, std::string file)
    : In(text)
    , File(std::move(file))
  {
  }
  template <typename T>
  T Next(const std::string& what)
  {
    T value{};
    if (!(In >> value))
    {
      throw DatasetError("the AMReX file " + File + " is truncated or damaged: it " +
        (In.eof() ? "ends" : "holds something else") + " where " + what + " should be");
    }
    return value;
  }
  /// Skips punctuation characters such as '(' ',' ')' around numbers.
  void Skip(char c, const std::string& what)
  {
    char got = 0;
    if (!(In >> got) || got != c)
    {
      throw DatasetError("the AMReX file " + File + " is truncated or damaged: expected '" +
        std::string(1, c) + "' at " + what);
    }
  }
  /// Integers separated by commas inside parentheses: "(a,b,c)".
  std::vector<long long> Tuple(int n, const std::string& what)
  {
    Skip('(', what);
    std::vector<long long> v;
    for (int i = 0; i < n; ++i)
    {
      v.push_back(Next<long long>(what));
      if (i + 1 < n)
      {
        Skip(',', what);
      }
    }
    Skip(')', what);
    return v;
  }
  /// "((lo) (hi) (type))": the number of cells of the box.
  long long Box(int dim, const std::string& what)
  {
    Skip('(', what);
    const std::vector<long long> lo = Tuple(dim, what), hi = Tuple(dim, what);
    Tuple(dim, what);
    Skip(')', what);
    long long cells = 1;
    for (int a = 0; a < dim; ++a)
    {
      if (hi[a] < lo[a])
      {
        throw DatasetError("the AMReX file " + File + " is damaged: " + what +
          " has an upper corner below its lower corner");
      }
      cells *= hi[a] - lo[a] + 1;
    }
    return cells;
  }

private:
  std::istringstream In;
  std::string File;
};

/// Checks the FAB of `box` at `offset` of `data`: its header line, its real size, and that the
/// file holds its `components` x `cells` reals.
void CheckFabOnDisk(
  const fs::path& data, long long offset, const std::string& box, long long cells, int components)
{
  std::error_code ec;
  const unsigned long long size = FileSize(data);
  if (!fs::exists(data, ec))
  {
    throw DatasetError("the AMReX data file " + data.string() + " (" + box + ") is missing");
  }
  // the FAB's own header line at the offset, then components x cells reals
  std::ifstream in(data, std::ios::binary);
  in.seekg(offset);
  std::string line;
  if (offset < 0 || static_cast<unsigned long long>(offset) >= size || !std::getline(in, line) ||
    line.rfind("FAB ((", 0) != 0)
  {
    throw DatasetError("the AMReX data file " + data.string() +
      " is truncated or damaged: " + "no FAB header at byte " + std::to_string(offset) + " (" +
      box + "; the file has " + Bytes(size) + ")");
  }
  HeaderTokens f(line.substr(3), data.string());
  f.Skip('(', "the FAB header of " + box);
  f.Skip('(', "the FAB header of " + box);
  f.Next<int>("the real format of " + box);
  f.Skip(',', "the real format of " + box);
  f.Skip('(', "the real format of " + box);
  const int bits = f.Next<int>("the real size of " + box);
  if (bits != 32 && bits != 64)
  {
    throw DatasetError("the AMReX data file " + data.string() + " is damaged: " + box +
      " has reals of " + std::to_string(bits) + " bits");
  }
  const unsigned long long need = static_cast<unsigned long long>(offset) + line.size() + 1 +
    static_cast<unsigned long long>(cells) * static_cast<unsigned long long>(components) *
      static_cast<unsigned>(bits / 8);
  if (need > size)
  {
    throw DatasetError("the AMReX data file " + data.string() + " is truncated: " + box +
      " needs bytes up to " + std::to_string(need) + ", the file has " + Bytes(size));
  }
}

/// Checks the multifab header `prefix`_H of `level` (its components, boxes and FABs against the
/// Header's `variables` and `boxes`) and each FAB, adding the FABs' files to `expected`.
void CheckAMReXMultifab(const fs::path& root, const fs::path& headerPath, const std::string& level,
  const std::string& prefix, long long boxes, int variables, int dim, ExpectedBlocks& expected)
{
  // the level's multifab header, e.g. Level_0/Cell_H
  const fs::path cellH = root / (prefix + "_H");
  std::error_code ec;
  if (!fs::exists(cellH, ec))
  {
    throw DatasetError(
      "the AMReX multifab header " + cellH.string() + " of " + level + " is missing");
  }
  HeaderTokens c(ReadWhole(cellH), cellH.string());
  c.Next<int>("the version");
  c.Next<int>("the layout");
  const int components = c.Next<int>("the number of components");
  if (components != variables)
  {
    throw DatasetError("the AMReX multifab header " + cellH.string() + " has " +
      std::to_string(components) + " components, the Header " + headerPath.string() + " lists " +
      std::to_string(variables) + " variables; one of them is damaged");
  }
  c.Next<int>("the number of ghost cells");
  c.Skip('(', "the box list");
  const long long listed = c.Next<long long>("the number of boxes");
  c.Next<int>("the box list's second number");
  if (listed != boxes)
  {
    throw DatasetError("the AMReX multifab header " + cellH.string() + " lists " +
      std::to_string(listed) + " boxes, the Header " + headerPath.string() + " " +
      std::to_string(boxes) + " for " + level + "; one of them is damaged");
  }
  std::vector<long long> cells;
  for (long long b = 0; b < boxes; ++b)
  {
    cells.push_back(c.Box(dim, "box " + std::to_string(b) + " of " + level));
  }
  c.Skip(')', "the end of the box list");
  const long long fabs = c.Next<long long>("the number of FABs on disk");
  if (fabs != boxes)
  {
    throw DatasetError("the AMReX multifab header " + cellH.string() + " names " +
      std::to_string(fabs) + " FABs for " + std::to_string(boxes) + " boxes");
  }
  for (long long b = 0; b < boxes; ++b)
  {
    const std::string box = "box " + std::to_string(b) + " of " + level;
    c.Next<std::string>("'FabOnDisk:' of " + box);
    const fs::path data = cellH.parent_path() / c.Next<std::string>("the file of " + box);
    const long long offset = c.Next<long long>("the offset of " + box);
    CheckFabOnDisk(data, offset, box, cells[static_cast<std::size_t>(b)], components);
    expected.Files.push_back(data.string());
  }
}
} // namespace

ExpectedBlocks CheckAMReXFiles(const std::string& folder)
{
  const fs::path root(folder);
  const fs::path headerPath = root / "Header";
  HeaderTokens h(ReadWhole(headerPath), headerPath.string());
  h.Next<std::string>("the version line");
  const int variables = h.Next<int>("the number of variables");
  if (variables < 1 || variables > 100000)
  {
    throw DatasetError("the AMReX Header " + headerPath.string() +
      " is damaged: " + std::to_string(variables) + " variables");
  }
  std::vector<std::string> names;
  for (int i = 0; i < variables; ++i)
  {
    names.push_back(h.Next<std::string>("variable name " + std::to_string(i + 1)));
  }
  const int dim = h.Next<int>("the dimension");
  if (dim < 1 || dim > 3)
  {
    throw DatasetError(
      "the AMReX Header " + headerPath.string() + " is damaged: dimension " + std::to_string(dim));
  }
  h.Next<double>("the time");
  const int finest = h.Next<int>("the finest level");
  if (finest < 0 || finest > 100)
  {
    throw DatasetError("the AMReX Header " + headerPath.string() + " is damaged: finest level " +
      std::to_string(finest));
  }
  for (int i = 0; i < 2 * dim; ++i)
  {
    h.Next<double>("the problem domain's corners");
  }
  for (int l = 0; l < finest; ++l)
  {
    h.Next<long long>("the refinement ratio of level " + std::to_string(l + 1));
  }
  for (int l = 0; l <= finest; ++l)
  {
    h.Box(dim, "the domain of level " + std::to_string(l));
  }
  for (int l = 0; l <= finest; ++l)
  {
    h.Next<long long>("the step count of level " + std::to_string(l));
  }
  for (int i = 0; i < (finest + 1) * dim; ++i)
  {
    h.Next<double>("the cell sizes");
  }
  h.Next<int>("the coordinate system");
  h.Next<int>("the boundary width");
  ExpectedBlocks expected;
  expected.Variables = names;
  for (int l = 0; l <= finest; ++l)
  {
    const std::string level = "level " + std::to_string(l);
    h.Next<int>(level + "'s number");
    const long long boxes = h.Next<long long>(level + "'s box count");
    if (boxes < 0 || boxes > 100000000)
    {
      throw DatasetError("the AMReX Header " + headerPath.string() + " is damaged: " + level +
        " has " + std::to_string(boxes) + " boxes");
    }
    h.Next<double>(level + "'s time");
    h.Next<long long>(level + "'s step");
    for (long long b = 0; b < boxes * 2 * dim; ++b)
    {
      h.Next<double>("the corners of " + level + "'s boxes");
    }
    const std::string prefix = h.Next<std::string>(level + "'s multifab path");

    CheckAMReXMultifab(root, headerPath, level, prefix, boxes, variables, dim, expected);
  }
  return expected;
}

// ---- VTK XML AMR -----------------------------------------------------------------------------

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
    for (int d = 0; d < block->GetNumberOfNestedElements(); ++d)
    {
      vtkXMLDataElement* data = block->GetNestedElement(d);
      int index = 0;
      const char* file = data->GetAttribute("file");
      if (std::string(data->GetName()) != "DataSet" || !data->GetScalarAttribute("index", index))
      {
        continue;
      }
      std::string piece;
      if (file)
      {
        piece = (fs::path(path).parent_path() / file).string();
        std::error_code ec;
        if (!fs::exists(piece, ec))
        {
          throw DatasetError("the piece file " + piece + " of block " + std::to_string(index) +
            " of level " + std::to_string(level) + " in " + path + " is missing");
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
