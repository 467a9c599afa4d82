// SPDX-License-Identifier: BSD-3-Clause
// 8-bit images and their RMSE.
#include "amrsp/Image.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace amrsp
{

std::vector<std::uint8_t> Image::Rgb8() const
{
  std::vector<std::uint8_t> out(Pixels.size() * 3);
  for (std::size_t i = 0; i < Pixels.size(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const float v = std::min(1.0f, std::max(0.0f, Pixels[i][c]));
      out[3 * i + c] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  }
  return out;
}

double Rmse8(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    throw std::invalid_argument("images of different sizes cannot be compared");
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    const double d = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

double Rmse(const Image& a, const Image& b)
{
  return Rmse8(a.Rgb8(), b.Rgb8());
}
} // namespace amrsp
