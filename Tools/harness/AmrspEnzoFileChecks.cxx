// SPDX-License-Identifier: BSD-3-Clause
// The Enzo checks of AmrspFileChecks.h: the .hierarchy entries, their fields and pointers, the grid
// files.
#include "AmrspFileChecks.h"

#include "AmrspDatasetError.h"
#include "AmrspFileCheckTools.h"

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
} // namespace

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
} // namespace harness
} // namespace amrsp
