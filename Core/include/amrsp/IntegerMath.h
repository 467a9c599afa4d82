// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Integer division rounded toward minus and plus infinity, for any signs of the operands (C++'s
/// `/` rounds toward zero). Used wherever a box of one level is expressed in the cells of a
/// coarser level, where box corners may be negative.

#include <cstdint>

namespace amrsp
{

/// floor(a / b) for b != 0.
constexpr int64_t FloorDiv(int64_t a, int64_t b)
{
  const int64_t q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}

/// ceil(a / b) for b != 0.
constexpr int64_t CeilDiv(int64_t a, int64_t b)
{
  const int64_t q = a / b;
  return (a % b != 0 && ((a < 0) == (b < 0))) ? q + 1 : q;
}

} // namespace amrsp
