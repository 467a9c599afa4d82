// SPDX-License-Identifier: BSD-3-Clause
// The AMReX checks of AmrspFileChecks.h: the Header, each level's Cell_H and every FAB on disk.
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
} // namespace harness
} // namespace amrsp
