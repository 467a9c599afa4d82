// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The images the CPU integrators write and their root-mean-square difference.

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{

/// RGBA float image, row 0 at the bottom. Alpha is the accumulated opacity.
struct Image
{
  int Width = 0;
  int Height = 0;
  std::vector<glm::vec4> Pixels;

  /// 8-bit RGB, rows bottom to top (vtkImageData order).
  std::vector<std::uint8_t> Rgb8() const;
};

/// Root-mean-square difference of the RGB channels in 0-255 units.
double Rmse(const Image& a, const Image& b);
double Rmse8(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b);

} // namespace amrsp
