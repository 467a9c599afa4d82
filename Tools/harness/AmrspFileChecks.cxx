// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspFileChecks.h"

#include "AmrspDataset.h"

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
#include <type_traits>

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
  long long NextThisLevel = 0;     // its next grid of the same level (0 = none)
  long long NextNextLevel = 0;     // its first child grid (0 = none)
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
      if (key.find("NextGridThisLevel") != std::string::npos)
      {
        owner.NextThisLevel = target;
      }
      else if (key.find("NextGridNextLevel") != std::string::npos)
      {
        owner.NextNextLevel = target;
      }
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

/// `count` numbers of `type` from the Enzo value `text` (extra ones are ignored); false when
/// there are fewer or one does not parse.
template <typename T>
bool EnzoNumbers(const std::string& text, int count, T* out)
{
  std::istringstream in(text);
  for (int i = 0; i < count; ++i)
  {
    std::string word;
    if (!(in >> word))
    {
      return false;
    }
    std::istringstream number(word);
    number >> out[i];
    if (number.fail() || !number.eof())
    {
      // "nan" and "inf" are doubles a damaged or diverged run can write: kept, checked below
      if (std::is_floating_point<T>::value &&
        (word == "nan" || word == "-nan" || word == "inf" || word == "-inf"))
      {
        out[i] = static_cast<T>(word[0] == '-' ? -HUGE_VAL : HUGE_VAL);
        if (word.find("nan") != std::string::npos)
        {
          out[i] = static_cast<T>(NAN);
        }
        continue;
      }
      return false;
    }
  }
  return true;
}

/// The fields of every grid entry VTK's reader trusts: the rank, the dimensions, the active
/// index range inside them, the edges (finite, right above left), the cell width they make
/// (finite, positive), and the refinement between a grid and its parent (a whole ratio of at
/// least 2). VTK's reader asserts (an inverted index range), loops (a NaN edge) or divides by
/// zero on them. Throws DatasetError naming the grid, the field, the value and what was expected.
void CheckEnzoGridFields(const std::vector<EnzoEntry>& entries, const std::string& name)
{
  const auto bad = [&name](const EnzoEntry& e, const std::string& field, const std::string& value,
                     const std::string& expected)
  {
    return DatasetError("the Enzo hierarchy " + name + " is damaged: grid " +
      std::to_string(e.Number) + " has " + field + " = " + value + " (expected " + expected + ")");
  };
  std::vector<double> width(entries.size() * 3, 0.0);
  std::vector<int> rankOf(entries.size(), 3);
  for (std::size_t g = 0; g < entries.size(); ++g)
  {
    const EnzoEntry& e = entries[g];
    int rank = 3;
    const auto r = e.Values.find("GridRank");
    if (r != e.Values.end() && (!EnzoNumbers(r->second, 1, &rank) || rank < 1 || rank > 3))
    {
      throw bad(e, "GridRank", r->second, "1, 2 or 3");
    }
    rankOf[g] = rank;
    long long dim[3], start[3], end[3];
    double left[3], right[3];
    const auto get = [&](const char* key, auto* out)
    {
      const std::string& value = e.Values.at(key);
      if (!EnzoNumbers(value, rank, out))
      {
        throw bad(e, key, value, std::to_string(rank) + " numbers");
      }
    };
    get("GridDimension", dim);
    get("GridStartIndex", start);
    get("GridEndIndex", end);
    get("GridLeftEdge", left);
    get("GridRightEdge", right);
    for (int a = 0; a < rank; ++a)
    {
      const std::string axis = " on axis " + std::to_string(a);
      if (dim[a] < 1 || dim[a] > (1LL << 24))
      {
        throw bad(
          e, "GridDimension", e.Values.at("GridDimension"), "1 to 16777216 cells per axis" + axis);
      }
      if (start[a] < 0 || start[a] >= dim[a])
      {
        throw bad(
          e, "GridStartIndex", e.Values.at("GridStartIndex"), "0 to GridDimension - 1" + axis);
      }
      if (end[a] < start[a] || end[a] >= dim[a])
      {
        throw bad(e, "GridEndIndex", e.Values.at("GridEndIndex"),
          "GridStartIndex to GridDimension - 1" + axis);
      }
      if (!std::isfinite(left[a]) || !std::isfinite(right[a]) || !(right[a] > left[a]))
      {
        throw bad(e, "GridLeftEdge, GridRightEdge",
          e.Values.at("GridLeftEdge") + ", " + e.Values.at("GridRightEdge"),
          "finite edges, the right one above the left one" + axis);
      }
      width[3 * g + a] = (right[a] - left[a]) / static_cast<double>(end[a] - start[a] + 1);
      if (!std::isfinite(width[3 * g + a]) || !(width[3 * g + a] > 0.0))
      {
        throw bad(e, "cell width", std::to_string(width[3 * g + a]), "finite and positive" + axis);
      }
    }
  }
  // the levels, from grid 1 along the pointers: a grid's first child (NextGridNextLevel) and
  // that child's siblings (NextGridThisLevel) are one level deeper and refine it by a whole ratio
  // of at least 2
  std::vector<int> level(entries.size(), -1);
  std::vector<std::size_t> parent(entries.size(), 0);
  std::vector<std::size_t> todo = { 0 };
  level[0] = 0;
  while (!todo.empty())
  {
    const std::size_t g = todo.back();
    todo.pop_back();
    const EnzoEntry& e = entries[g];
    const auto reach = [&](long long target, int targetLevel, std::size_t targetParent)
    {
      if (target <= 0 || target > static_cast<long long>(entries.size()))
      {
        return;
      }
      const std::size_t t = static_cast<std::size_t>(target - 1);
      if (level[t] >= 0)
      {
        return;
      }
      if (targetLevel > 64)
      {
        throw DatasetError("the Enzo hierarchy " + name + " is damaged: its grids nest " +
          std::to_string(targetLevel) + " levels deep (expected at most 64)");
      }
      level[t] = targetLevel;
      parent[t] = targetParent;
      todo.push_back(t);
    };
    reach(e.NextThisLevel, level[g], parent[g]);
    reach(e.NextNextLevel, level[g] + 1, g);
  }
  for (std::size_t c = 0; c < entries.size(); ++c)
  {
    if (level[c] <= 0)
    {
      continue;
    }
    const std::size_t g = parent[c];
    for (int a = 0; a < std::min(rankOf[g], rankOf[c]); ++a)
    {
      const double ratio = width[3 * g + a] / width[3 * c + a];
      const double whole = std::round(ratio);
      if (!(whole >= 2.0) || std::abs(ratio - whole) > 1e-3 * whole)
      {
        throw bad(entries[c], "a cell width", std::to_string(width[3 * c + a]),
          "its parent grid " + std::to_string(entries[g].Number) + "'s " +
            std::to_string(width[3 * g + a]) + " divided by a whole refinement ratio of at " +
            "least 2 on axis " + std::to_string(a) + "; the ratio is " + std::to_string(ratio));
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
  CheckEnzoGridFields(entries, name);
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
  /// "((lo) (hi) (type))": the box's cells per axis (upper corner not below the lower one, at
  /// most 2^31 per axis).
  std::vector<long long> BoxExtent(
    int dim, const std::string& what, std::vector<long long>* lower = nullptr)
  {
    Skip('(', what);
    const std::vector<long long> lo = Tuple(dim, what), hi = Tuple(dim, what);
    Tuple(dim, what);
    Skip(')', what);
    std::vector<long long> extent;
    for (int a = 0; a < dim; ++a)
    {
      if (hi[a] < lo[a] || hi[a] - lo[a] >= (1LL << 31) || std::llabs(lo[a]) >= (1LL << 40))
      {
        throw DatasetError("the AMReX file " + File + " is damaged: " + what + " is " +
          std::to_string(lo[a]) + " to " + std::to_string(hi[a]) + " on axis " + std::to_string(a) +
          " (expected an upper corner not below the lower one)");
      }
      extent.push_back(hi[a] - lo[a] + 1);
    }
    if (lower)
    {
      *lower = lo;
    }
    return extent;
  }
  /// The same box's number of cells.
  long long Box(int dim, const std::string& what)
  {
    long long cells = 1;
    for (long long e : BoxExtent(dim, what))
    {
      cells *= e;
    }
    return cells;
  }

private:
  std::istringstream In;
  std::string File;
};

/// A multifab box: its lower corner and cells per axis (AMReX's Cell_H).
struct FabBox
{
  std::vector<long long> Lo;
  std::vector<long long> Extent;
  long long Cells() const
  {
    long long n = 1;
    for (long long e : this->Extent)
    {
      n *= e;
    }
    return n;
  }
};

/// Checks the FAB of `box` (named `name`) at `offset` of `data`: its header line (the real
/// format one of IEEE's float or double, the byte order ascending or descending, the box the
/// multifab header's, its `components`), and that the file holds its components x cells reals. A
/// garbled format or byte order makes VTK's reader return values such as 4e21 without a word.
void CheckFabOnDisk(const fs::path& data, long long offset, const std::string& name,
  const FabBox& box, int components, int dim)
{
  std::error_code ec;
  const unsigned long long size = FileSize(data);
  if (!fs::exists(data, ec))
  {
    throw DatasetError("the AMReX data file " + data.string() + " (" + name + ") is missing");
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
      name + "; the file has " + Bytes(size) + ")");
  }
  const std::string damaged = "the AMReX data file " + data.string() +
    " is damaged: the FAB header of " + name + " ('" + line.substr(0, 120) + "') ";
  HeaderTokens f(line.substr(3), data.string());
  const std::string where = "the FAB header of " + name;
  f.Skip('(', where);
  f.Skip('(', where);
  const int bytes = f.Next<int>("the real size of " + name);
  f.Skip(',', where);
  f.Skip('(', where);
  std::vector<long long> format;
  for (int i = 0; i < 8; ++i)
  {
    format.push_back(f.Next<long long>("the real format of " + name));
  }
  f.Skip(')', where);
  f.Skip(')', where);
  f.Skip(',', where);
  f.Skip('(', where);
  const int orderBytes = f.Next<int>("the byte order of " + name);
  f.Skip(',', where);
  f.Skip('(', where);
  std::vector<int> order;
  for (int i = 0; i < orderBytes && i < 16; ++i)
  {
    order.push_back(f.Next<int>("the byte order of " + name));
  }
  f.Skip(')', where);
  f.Skip(')', where);
  f.Skip(')', where);
  const std::vector<long long> ieeeDouble = { 64, 11, 52, 0, 1, 12, 0, 1023 };
  const std::vector<long long> ieeeFloat = { 32, 8, 23, 0, 1, 9, 0, 127 };
  if (!((bytes == 8 && format == ieeeDouble) || (bytes == 4 && format == ieeeFloat)))
  {
    throw DatasetError(damaged +
      "names no IEEE float or double format (expected (8, (64 11 52 0 "
      "1 12 0 1023)) or (4, (32 8 23 0 1 9 0 127)))");
  }
  bool ascending = orderBytes == bytes, descending = orderBytes == bytes;
  for (int i = 0; ascending && i < orderBytes; ++i)
  {
    ascending = order[static_cast<std::size_t>(i)] == i + 1;
  }
  for (int i = 0; descending && i < orderBytes; ++i)
  {
    descending = order[static_cast<std::size_t>(i)] == orderBytes - i;
  }
  if (!ascending && !descending)
  {
    throw DatasetError(damaged + "has a byte order that is neither big- nor little-endian");
  }
  std::vector<long long> lo;
  const std::vector<long long> extent = f.BoxExtent(dim, where, &lo);
  const int fabComponents = f.Next<int>("the component count of " + name);
  if (lo != box.Lo || extent != box.Extent)
  {
    throw DatasetError(damaged + "describes another box than the multifab header's");
  }
  if (fabComponents != components)
  {
    throw DatasetError(damaged + "has " + std::to_string(fabComponents) +
      " components (the multifab header: " + std::to_string(components) + ")");
  }
  const unsigned long long need = static_cast<unsigned long long>(offset) + line.size() + 1 +
    static_cast<unsigned long long>(box.Cells()) * static_cast<unsigned long long>(components) *
      static_cast<unsigned>(bytes);
  if (need > size)
  {
    throw DatasetError("the AMReX data file " + data.string() + " is truncated: " + name +
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
  std::vector<FabBox> fabBoxes;
  for (long long b = 0; b < boxes; ++b)
  {
    FabBox box;
    box.Extent = c.BoxExtent(dim, "box " + std::to_string(b) + " of " + level, &box.Lo);
    fabBoxes.push_back(box);
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
    CheckFabOnDisk(data, offset, box, fabBoxes[static_cast<std::size_t>(b)], components, dim);
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
  const std::string damaged = "the AMReX Header " + headerPath.string() + " is damaged: ";
  double corner[6];
  for (int i = 0; i < 2 * dim; ++i)
  {
    corner[i] = h.Next<double>("the problem domain's corners");
  }
  for (int a = 0; a < dim; ++a)
  {
    if (!std::isfinite(corner[a]) || !std::isfinite(corner[dim + a]) ||
      !(corner[dim + a] > corner[a]))
    {
      throw DatasetError(damaged + "the problem domain on axis " + std::to_string(a) + " is " +
        std::to_string(corner[a]) + " to " + std::to_string(corner[dim + a]) +
        " (expected finite corners, the upper above the lower)");
    }
  }
  std::vector<long long> ratio(static_cast<std::size_t>(finest) + 1, 1);
  for (int l = 0; l < finest; ++l)
  {
    ratio[l + 1] = h.Next<long long>("the refinement ratio of level " + std::to_string(l + 1));
    if (ratio[l + 1] < 2 || ratio[l + 1] > 64)
    {
      throw DatasetError(damaged + "the refinement ratio of level " + std::to_string(l + 1) +
        " is " + std::to_string(ratio[l + 1]) + " (expected 2 to 64)");
    }
  }
  std::vector<std::vector<long long>> extent;
  for (int l = 0; l <= finest; ++l)
  {
    const std::string what = "the domain of level " + std::to_string(l);
    try
    {
      extent.push_back(h.BoxExtent(dim, what));
    }
    catch (const DatasetError& e)
    {
      // one refinement ratio too many or too few shifts everything after it
      throw DatasetError(std::string(e.what()) + " (after " + std::to_string(finest) +
        " refinement ratios for finest level " + std::to_string(finest) +
        ": one too many or too few shifts what follows)");
    }
    for (int a = 0; a < dim && l > 0; ++a)
    {
      const long long expected = extent[l - 1][a] * ratio[l];
      if (extent[l][a] != expected)
      {
        throw DatasetError(damaged + what + " is " + std::to_string(extent[l][a]) +
          " cells on axis " + std::to_string(a) + ", level " + std::to_string(l - 1) +
          "'s domain refined by " + std::to_string(ratio[l]) + " is " + std::to_string(expected));
      }
    }
  }
  for (int l = 0; l <= finest; ++l)
  {
    h.Next<long long>("the step count of level " + std::to_string(l));
  }
  for (int l = 0; l <= finest; ++l)
  {
    for (int a = 0; a < dim; ++a)
    {
      const double size = h.Next<double>("the cell sizes");
      const double expected = (corner[dim + a] - corner[a]) / static_cast<double>(extent[l][a]);
      if (!std::isfinite(size) || !(size > 0.0) || std::abs(size - expected) > 1e-3 * expected)
      {
        throw DatasetError(damaged + "the cell size of level " + std::to_string(l) + " on axis " +
          std::to_string(a) + " is " + std::to_string(size) +
          " (expected the domain over its cells, " + std::to_string(expected) + ")");
      }
    }
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
      const double c = h.Next<double>("the corners of " + level + "'s boxes");
      if (!std::isfinite(c))
      {
        throw DatasetError(damaged + "a corner of " + level + "'s boxes is " + std::to_string(c) +
          " (expected a finite position)");
      }
    }
    const std::string prefix = h.Next<std::string>(level + "'s multifab path");

    CheckAMReXMultifab(root, headerPath, level, prefix, boxes, variables, dim, expected);
  }
  return expected;
}

// ---- VTK XML AMR -----------------------------------------------------------------------------

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
