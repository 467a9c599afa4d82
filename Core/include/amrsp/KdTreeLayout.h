// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// C++ view of the kD-tree texture layout. The layout itself lives in Shaders/KdTreeLayout.glsl,
/// which the GLSL raycaster includes verbatim; this header supplies the few GLSL names that file
/// uses so that the very same text compiles as C++.

#include <glm/glm.hpp>

#include <cstdint>

namespace amrsp
{
namespace layout
{
using uint = std::uint32_t;
using glm::ivec3;
using glm::uvec2;
using glm::uvec4;
#define AMRSP_FN inline
#include "KdTreeLayout.glsl"
#undef AMRSP_FN

/// Largest values each field can hold.
constexpr uint MaxLevel = (1u << AMRSP_LEVEL_BITS) - 1u;
constexpr uint MaxNodes = 1u << AMRSP_CHILD_BITS;
constexpr uint MaxSplit = (1u << AMRSP_SPLIT_BITS) - 1u;
constexpr uint MaxDataNodes = (1u << AMRSP_DATA_BITS) - 1u; // index 0 is reserved
constexpr uint MaxBricks = 1u << AMRSP_DN_BRICK_BITS;
constexpr uint MaxAtlasPages = 1u << AMRSP_DN_PAGE_BITS;
constexpr uint MaxOffsetX = (1u << AMRSP_DN_OFFSET_X_BITS) - 1u;
constexpr uint MaxOffsetY = (1u << AMRSP_DN_OFFSET_Y_BITS) - 1u;
constexpr uint MaxOffsetZ = (1u << AMRSP_DN_OFFSET_Z_BITS) - 1u;
} // namespace layout
} // namespace amrsp
