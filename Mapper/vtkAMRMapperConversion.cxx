// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperConversion.h"

#include "amrsp/RefinedCells.h"
#include "amrsp/VertexData.h"

#include "vtkAMRBox.h"
#include "vtkAbstractMapper.h" // VTK_GET_ARRAY_BY_NAME, VTK_GET_ARRAY_BY_ID
#include "vtkCellData.h"
#include "vtkDataSetAttributes.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStructuredData.h"
#include "vtkRectilinearGrid.h"
#include "vtkSinglePassAMRDataModel.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <utility>

namespace
{
namespace model = vtkSinglePassAMRDataModel;

vtkDataSet* FirstBlock(vtkOverlappingAMR* amr)
{
  for (unsigned int l = 0; l < amr->GetNumberOfLevels(); ++l)
  {
    for (unsigned int i = 0; i < model::NumberOfBlocks(amr, l); ++i)
    {
      if (vtkDataSet* g = model::Block(amr, l, i))
      {
        return g;
      }
    }
  }
  return nullptr;
}

// Values lent to VTK arrays by ToOverlappingAMR, by data pointer: each entry keeps its floats
// alive until every VTK array sharing that buffer is gone (VTK then calls ReturnLentValues
// once per lending array, shallow copies included, since they share the array's buffer).
std::mutex LentMutex;
std::map<const void*, std::pair<amrsp::GridValues, int>>& LentValues()
{
  static std::map<const void*, std::pair<amrsp::GridValues, int>> lent;
  return lent;
}

void ReturnLentValues(void* data)
{
  std::lock_guard<std::mutex> lock(LentMutex);
  auto& lent = LentValues();
  auto it = lent.find(data);
  if (it != lent.end() && --it->second.second == 0)
  {
    lent.erase(it);
  }
}

/// A vtkFloatArray over `values` without copying them; VTK never writes or frees the floats.
void LendValues(const amrsp::GridValues& values, vtkFloatArray* array)
{
  float* data = const_cast<float*>(values.data());
  {
    std::lock_guard<std::mutex> lock(LentMutex);
    auto& entry = LentValues()[data];
    entry.first = values;
    ++entry.second;
  }
  array->SetArray(
    data, static_cast<vtkIdType>(values.size()), 0, vtkFloatArray::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(&ReturnLentValues);
}

/// The values of a one-component float array without ghost layers, borrowed (no copy): the
/// array is held until the last copy of the returned values is gone.
amrsp::GridValues BorrowValues(vtkFloatArray* array)
{
  array->Register(nullptr);
  std::shared_ptr<const void> owner(array,
    [](const void* a) { static_cast<vtkFloatArray*>(const_cast<void*>(a))->UnRegister(nullptr); });
  return amrsp::GridValues::Borrow(
    array->GetPointer(0), static_cast<std::size_t>(array->GetNumberOfTuples()), std::move(owner));
}

std::string Join(const std::vector<std::string>& names)
{
  std::string s;
  for (const std::string& n : names)
  {
    s += (s.empty() ? "" : ", ") + n;
  }
  return s.empty() ? "none" : s;
}

/// "block I of level L", as the conversion's messages name a block.
std::string BlockName(unsigned int level, unsigned int index)
{
  return "block " + std::to_string(index) + " of level " + std::to_string(level);
}

/// The origin, the level-0 spacing and the per-level refinement ratios of `amr` into `out`;
/// false with `error` for a non-positive spacing or a non-integer ratio.
bool ReadLevels(vtkOverlappingAMR* amr, amrsp::Hierarchy& out, std::string& error)
{
  const unsigned int levels = amr->GetNumberOfLevels();
  const double* origin = amr->GetOrigin();
  out.Origin = glm::dvec3(origin[0], origin[1], origin[2]);
  if (!std::isfinite(origin[0]) || !std::isfinite(origin[1]) || !std::isfinite(origin[2]))
  {
    std::ostringstream m;
    m << "the AMR hierarchy's origin (" << origin[0] << ", " << origin[1] << ", " << origin[2]
      << ") is not finite";
    error = m.str();
    return false;
  }
  std::vector<glm::dvec3> spacing(levels);
  for (unsigned int l = 0; l < levels; ++l)
  {
    double s[3];
    amr->GetSpacing(l, s);
    spacing[l] = glm::dvec3(s[0], s[1], s[2]);
    if (!std::isfinite(s[0]) || !std::isfinite(s[1]) || !std::isfinite(s[2]))
    {
      std::ostringstream m;
      m << "level " << l << " has a spacing that is not finite (" << s[0] << ", " << s[1] << ", "
        << s[2] << ")";
      error = m.str();
      return false;
    }
    if (!(s[0] > 0.0 && s[1] > 0.0 && s[2] > 0.0))
    {
      std::ostringstream m;
      m << "level " << l << " has a non-positive spacing (" << s[0] << ", " << s[1] << ", " << s[2]
        << "); volume rendering needs 3D data";
      error = m.str();
      return false;
    }
  }
  out.Spacing0 = spacing[0];
  out.RefinementRatio.assign(1, glm::ivec3(1));
  for (unsigned int l = 1; l < levels; ++l)
  {
    glm::ivec3 r;
    for (int a = 0; a < 3; ++a)
    {
      const double q = spacing[l - 1][a] / spacing[l][a];
      r[a] = static_cast<int>(std::lround(q));
      if (r[a] < 1 || std::abs(q - r[a]) > 1e-3 * q)
      {
        std::ostringstream m;
        m << "unsupported refinement: level " << l << " refines level " << l - 1 << " by " << q
          << " along axis " << a << " (an integer ratio >= 1 is required)";
        error = m.str();
        return false;
      }
    }
    // a declared ratio (VTK keeps it apart from the spacings) must be the spacings' ratio
    if (r.x == r.y && r.y == r.z && model::HasRefinementRatio(amr))
    {
      const int declared = amr->GetRefinementRatio(l - 1);
      if (declared > 0 && declared != r.x)
      {
        std::ostringstream m;
        m << "the AMR hierarchy contradicts itself: level " << l << " refines level " << l - 1
          << " by " << r.x << " (their spacings), its refinement ratio says " << declared;
        error = m.str();
        return false;
      }
    }
    out.RefinementRatio.push_back(r);
  }
  return true;
}

/// The array to render: by name (cell arrays first, then point arrays), or the first cell
/// array, or the first point array when there is no cell array. `points` says which kind.
bool ChooseArray(vtkOverlappingAMR* amr, const vtkAMRMapperConversion::ArraySelection& selection,
  std::string& name, bool& points, std::string& error)
{
  name = selection.Name;
  const std::vector<std::string> cellArrays = vtkAMRMapperConversion::ArrayNames(amr, false);
  const std::vector<std::string> pointArrays = vtkAMRMapperConversion::ArrayNames(amr, true);
  const auto has = [](const std::vector<std::string>& v, const std::string& n)
  { return std::find(v.begin(), v.end(), n) != v.end(); };
  points = false;
  if (name.empty())
  {
    if (cellArrays.empty() && pointArrays.empty() && selection.CopyValues)
    {
      error = "the AMR blocks have no cell or point array to render";
      return false;
    }
    points = cellArrays.empty() && !pointArrays.empty();
    name = !cellArrays.empty() ? cellArrays.front()
                               : (pointArrays.empty() ? std::string() : pointArrays.front());
  }
  else if (!has(cellArrays, name))
  {
    if (!has(pointArrays, name))
    {
      std::vector<std::string> all = cellArrays;
      for (const std::string& p : pointArrays)
      {
        all.push_back(p + " (point data)");
      }
      error = "no cell array named '" + name + "' (available: " + Join(all) + ")";
      return false;
    }
    points = true;
  }
  return true;
}

/// A rectilinear block (VTK 9.6) is rendered when its coordinates step by its level's spacing
/// on every axis; false with `error` naming the block otherwise. Image data always passes.
bool RequireUniformSpacing(vtkOverlappingAMR* amr, unsigned int level, vtkDataSet* block,
  const std::string& blockName, std::string& error)
{
  vtkRectilinearGrid* grid = vtkRectilinearGrid::SafeDownCast(block);
  if (!grid)
  {
    return true;
  }
  double spacing[3];
  amr->GetSpacing(level, spacing);
  vtkDataArray* coordinates[3] = { grid->GetXCoordinates(), grid->GetYCoordinates(),
    grid->GetZCoordinates() };
  for (int a = 0; a < 3; ++a)
  {
    vtkDataArray* c = coordinates[a];
    const vtkIdType n = c ? c->GetNumberOfTuples() : 0;
    for (vtkIdType k = 1; k < n; ++k)
    {
      const double step = c->GetComponent(k, 0) - c->GetComponent(k - 1, 0);
      if (std::abs(step - spacing[a]) > 1e-6 * spacing[a])
      {
        std::ostringstream m;
        m << blockName << " is a rectilinear grid whose "
          << "xyz"[a] << " coordinates are not "
          << "evenly spaced by its level's spacing " << spacing[a] << " (step " << k << ": " << step
          << "); only rectilinear blocks of uniform spacing can be rendered";
        error = m.str();
        return false;
      }
    }
  }
  return true;
}

/// The values of grid `g` from its block: the block's own floats where they are one float
/// component without ghost layers, otherwise the box's cells (or vertices) converted to floats
/// (`component`, or the magnitude when it is out of range). False with `error` when the block or
/// its array is missing or its dimensions do not match the box.
bool ReadBlockValues(vtkDataSet* block, const amrsp::Grid& g, const std::string& blockName,
  const std::string& name, bool points, int component, amrsp::GridValues& values,
  std::string& error)
{
  if (!block)
  {
    error = blockName + " has no data loaded";
    return false;
  }
  int dims[3];
  if (!model::BlockDimensions(block, dims))
  {
    error = blockName + " is a " + block->GetClassName() +
      "; AMR blocks must be image data or rectilinear grids";
    return false;
  }
  vtkDataArray* arr = points ? block->GetPointData()->GetArray(name.c_str())
                             : block->GetCellData()->GetArray(name.c_str());
  if (!arr)
  {
    error = blockName + " lacks the " + (points ? "point" : "cell") + " array '" + name + "'";
    return false;
  }
  // blocks may carry ghost layers around the box: keep the box's cells (or vertices) only
  const glm::i64vec3 extent = g.Cells.Extent() + glm::i64vec3(points ? 1 : 0);
  glm::i64vec3 cellDims, ghost;
  for (int a = 0; a < 3; ++a)
  {
    cellDims[a] = points ? dims[a] : std::max(1, dims[a] - 1);
    ghost[a] = (cellDims[a] - extent[a]) / 2;
    if (cellDims[a] < extent[a] || (cellDims[a] - extent[a]) % 2 != 0)
    {
      error = blockName + " has dimensions that do not match its AMR box";
      return false;
    }
  }
  const int components = arr->GetNumberOfComponents();
  const int used = components == 1 ? 0 : (component < components ? component : -1);
  vtkFloatArray* fast = vtkFloatArray::SafeDownCast(arr);
  const std::size_t count = static_cast<std::size_t>(extent.x * extent.y * extent.z);
  if (fast && components == 1 && ghost == glm::i64vec3(0) &&
    static_cast<std::size_t>(fast->GetNumberOfTuples()) == count)
  {
    values = BorrowValues(fast); // the block's own floats, in the core's order
    return true;
  }
  values = amrsp::GridValues(count);
  float* written = values.data();
  std::size_t k = 0;
  for (int64_t z = 0; z < extent.z; ++z)
  {
    for (int64_t y = 0; y < extent.y; ++y)
    {
      for (int64_t x = 0; x < extent.x; ++x, ++k)
      {
        const vtkIdType c = ((z + ghost.z) * cellDims.y + (y + ghost.y)) * cellDims.x + x + ghost.x;
        if (fast && components == 1)
        {
          written[k] = fast->GetValue(c);
        }
        else if (used >= 0)
        {
          written[k] = static_cast<float>(arr->GetComponent(c, used));
        }
        else
        {
          double sum = 0.0;
          for (int q = 0; q < components; ++q)
          {
            const double v = arr->GetComponent(c, q);
            sum += v * v;
          }
          written[k] = static_cast<float>(std::sqrt(sum));
        }
      }
    }
  }
  return true;
}
} // namespace

std::vector<std::string> vtkAMRMapperConversion::CellArrayNames(vtkOverlappingAMR* amr)
{
  return ArrayNames(amr, false);
}

std::vector<std::string> vtkAMRMapperConversion::ArrayNames(vtkOverlappingAMR* amr, bool points)
{
  std::vector<std::string> names;
  if (vtkDataSet* g = FirstBlock(amr))
  {
    vtkDataSetAttributes* cd = points ? static_cast<vtkDataSetAttributes*>(g->GetPointData())
                                      : static_cast<vtkDataSetAttributes*>(g->GetCellData());
    for (int a = 0; a < cd->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* arr = cd->GetArray(a);
      if (arr && arr->GetName() &&
        std::string(arr->GetName()) != vtkDataSetAttributes::GhostArrayName())
      {
        names.emplace_back(arr->GetName());
      }
    }
  }
  return names;
}

bool vtkAMRMapperConversion::FromOverlappingAMR(vtkOverlappingAMR* amr,
  const ArraySelection& selection, amrsp::Hierarchy& out, std::string& error)
{
  out = amrsp::Hierarchy();
  if (!amr || amr->GetNumberOfLevels() == 0 || model::NumberOfBlocks(amr) == 0)
  {
    error = "the AMR hierarchy has no blocks";
    return false;
  }
  bool points = false;
  if (!ReadLevels(amr, out, error) || !ChooseArray(amr, selection, out.ArrayName, points, error))
  {
    return false;
  }
  out.VertexCentred = points;
  // one allocation each (a growing vector would hold up to twice the blocks' bytes)
  out.Grids.reserve(model::NumberOfBlocks(amr));
  if (selection.CopyValues)
  {
    out.Values.reserve(model::NumberOfBlocks(amr));
  }
  for (unsigned int l = 0; l < amr->GetNumberOfLevels(); ++l)
  {
    for (unsigned int i = 0; i < model::NumberOfBlocks(amr, l); ++i)
    {
      const vtkAMRBox& box = amr->GetAMRBox(l, i);
      if (box.IsInvalid())
      {
        continue;
      }
      const int* lo = box.GetLoCorner();
      const int* hi = box.GetHiCorner();
      amrsp::Grid g;
      g.Level = static_cast<int>(l);
      g.SourceId = static_cast<int64_t>(model::AbsoluteBlockIndex(amr, l, i));
      for (int a = 0; a < 3; ++a)
      {
        if (hi[a] < lo[a])
        {
          error = BlockName(l, i) + " is flat; volume rendering needs 3D data";
          return false;
        }
        if (std::llabs(static_cast<long long>(lo[a])) >= (1LL << 30) ||
          std::llabs(static_cast<long long>(hi[a])) >= (1LL << 30))
        {
          error = BlockName(l, i) + " has an AMR box beyond 2^30 cells of its level (" +
            std::to_string(lo[a]) + " to " + std::to_string(hi[a]) + " on axis " +
            std::to_string(a) + ")";
          return false;
        }
        g.Cells.Lo[a] = lo[a];
        g.Cells.Hi[a] = static_cast<int64_t>(hi[a]) + 1;
      }
      out.Grids.push_back(g);
      if (!selection.CopyValues)
      {
        continue;
      }
      amrsp::GridValues values;
      vtkDataSet* block = model::Block(amr, l, i);
      if (!RequireUniformSpacing(amr, l, block, BlockName(l, i), error) ||
        !ReadBlockValues(
          block, g, BlockName(l, i), out.ArrayName, points, selection.Component, values, error))
      {
        return false;
      }
      out.Values.push_back(std::move(values));
    }
  }
  if (out.Grids.empty())
  {
    error = "the AMR hierarchy has no blocks";
    return false;
  }
  if (out.VertexCentred && selection.CopyValues)
  {
    amrsp::MakeVertexDataContinuous(out);
  }
  return true;
}

void vtkAMRMapperConversion::ToOverlappingAMR(
  const amrsp::Hierarchy& h, vtkOverlappingAMR* out, bool blanking)
{
  const int levels = h.NumberOfLevels();
  std::vector<int> blocksPerLevel(static_cast<std::size_t>(levels), 0);
  for (const amrsp::Grid& g : h.Grids)
  {
    ++blocksPerLevel[g.Level];
  }
  model::Initialize(out, blocksPerLevel);
  const double origin[3] = { h.Origin.x, h.Origin.y, h.Origin.z };
  out->SetOrigin(origin);
  out->SetGridDescription(model::XYZGrid);
  for (int l = 0; l < levels; ++l)
  {
    const glm::dvec3 s = h.Spacing0 * h.CellSize(l);
    const double spacing[3] = { s.x, s.y, s.z };
    out->SetSpacing(l, spacing);
    // vtkOverlappingAMR keeps one isotropic ratio per level: the one to the next finer level
    out->SetRefinementRatio(l, l + 1 < levels ? h.RefinementRatio[l + 1].x : 2);
  }
  // Blanking as vtkAMRUtilities::BlankCells writes it (REFINEDCELL in vtkGhostType), computed
  // from the boxes: BlankCells' parent-child search bins each level's whole index space and
  // runs out of memory on deep, sparse hierarchies (13 levels: tens of GB).
  const std::vector<std::vector<amrsp::Box>> refined =
    blanking ? amrsp::RefinedRegions(h) : std::vector<std::vector<amrsp::Box>>();
  std::vector<int> next(static_cast<std::size_t>(levels), 0);
  for (std::size_t gi = 0; gi < h.Grids.size(); ++gi)
  {
    const amrsp::Grid& g = h.Grids[gi];
    const int index = next[g.Level]++;
    const int lo[3] = { static_cast<int>(g.Cells.Lo.x), static_cast<int>(g.Cells.Lo.y),
      static_cast<int>(g.Cells.Lo.z) };
    const int hi[3] = { static_cast<int>(g.Cells.Hi.x) - 1, static_cast<int>(g.Cells.Hi.y) - 1,
      static_cast<int>(g.Cells.Hi.z) - 1 };
    const vtkAMRBox box(lo, hi);
    out->SetAMRBox(g.Level, index, box);

    const glm::dvec3 spacing = h.Spacing0 * h.CellSize(g.Level);
    const glm::dvec3 corner = h.Origin + glm::dvec3(g.Cells.Lo) * spacing;
    vtkNew<vtkUniformGrid> grid;
    grid->SetOrigin(corner.x, corner.y, corner.z);
    grid->SetSpacing(spacing.x, spacing.y, spacing.z);
    const glm::i64vec3 e = g.Cells.Extent();
    grid->SetDimensions(
      static_cast<int>(e.x) + 1, static_cast<int>(e.y) + 1, static_cast<int>(e.z) + 1);
    if (h.HasValues())
    {
      vtkNew<vtkFloatArray> values;
      values->SetName(h.ArrayName.empty() ? "values" : h.ArrayName.c_str());
      LendValues(h.Values[gi], values);
      if (h.VertexCentred)
      {
        grid->GetPointData()->AddArray(values);
      }
      else
      {
        grid->GetCellData()->AddArray(values);
      }
    }
    if (!blanking)
    {
      out->SetDataSet(g.Level, index, grid);
      continue;
    }
    const std::vector<unsigned char> mask = amrsp::RefinedCellMask(g.Cells, refined[gi]);
    vtkNew<vtkUnsignedCharArray> ghosts;
    ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
    ghosts->SetNumberOfTuples(static_cast<vtkIdType>(mask.size()));
    for (std::size_t c = 0; c < mask.size(); ++c)
    {
      ghosts->SetValue(static_cast<vtkIdType>(c), mask[c] ? vtkDataSetAttributes::REFINEDCELL : 0);
    }
    grid->GetCellData()->AddArray(ghosts);
    out->SetDataSet(g.Level, index, grid);
  }
}

//------------------------------------------------------------------------------
std::string vtkAMRMapperConversion::RequestedArray(
  vtkOverlappingAMR* amr, int accessMode, const char* name, int id)
{
  if (accessMode == VTK_GET_ARRAY_BY_NAME && name && *name)
  {
    return name;
  }
  if (accessMode == VTK_GET_ARRAY_BY_ID && id >= 0)
  {
    const std::vector<std::string> names = CellArrayNames(amr);
    if (static_cast<std::size_t>(id) < names.size())
    {
      return names[static_cast<std::size_t>(id)];
    }
  }
  return std::string();
}
