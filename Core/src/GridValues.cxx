// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/Hierarchy.h"

#include <algorithm>
#include <utility>

namespace amrsp
{

GridValues::GridValues(std::vector<float> values)
  : Owned(std::make_shared<std::vector<float>>(std::move(values)))
{
}

GridValues::GridValues(std::size_t count, float value)
  : Owned(std::make_shared<std::vector<float>>(count, value))
{
}

GridValues::GridValues(std::initializer_list<float> values)
  : Owned(std::make_shared<std::vector<float>>(values))
{
}

GridValues GridValues::Borrow(
  const float* values, std::size_t count, std::shared_ptr<const void> owner)
{
  GridValues v;
  v.Borrowed = values;
  v.Count = count;
  v.Owner = std::move(owner);
  return v;
}

std::vector<float>& GridValues::Writable()
{
  if (!this->Owned || this->Owned.use_count() > 1)
  {
    const GridValues& current = *this; // read through the const accessors (no recursion)
    this->Owned = std::make_shared<std::vector<float>>(current.begin(), current.end());
    this->Borrowed = nullptr;
    this->Count = 0;
    this->Owner.reset();
  }
  return *this->Owned;
}

bool GridValues::operator==(const GridValues& o) const
{
  return this->size() == o.size() && std::equal(this->begin(), this->end(), o.begin());
}

} // namespace amrsp
