// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A point lookup of the data field, as the CPU integrators' rules read it.

#include <glm/glm.hpp>

#include <functional>

namespace amrsp
{

/// Scalar at p (level-0 index units), NaN when absent; sets cellSize (level-0 index units) of the
/// level the value comes from.
using PointLookup = std::function<double(const glm::dvec3& p, glm::dvec3& cellSize)>;

} // namespace amrsp
