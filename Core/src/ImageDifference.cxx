// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/ImageDifference.h"

#include "amrsp/Image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace amrsp
{

std::string ImageDifference::Describe() const
{
  char text[200];
  std::snprintf(text, sizeof(text),
    "RMSE %.2f over the %.1f %% of the frame the volume covers, %.2f %% of those pixels off by "
    "more than %d levels",
    Rmse, 100.0 * Coverage(), 100.0 * OffShare, OffLevels);
  return text;
}

bool IsCovered(const std::uint8_t* rgb, const std::uint8_t* background)
{
  static const std::uint8_t black[3] = { 0, 0, 0 };
  const std::uint8_t* bg = background ? background : black;
  for (int c = 0; c < 3; ++c)
  {
    if (std::abs(static_cast<int>(rgb[c]) - static_cast<int>(bg[c])) >
      ImageDifference::BackgroundLevel)
    {
      return true;
    }
  }
  return false;
}

double CoveredShare(const std::vector<std::uint8_t>& rgb8, const std::uint8_t* background)
{
  std::size_t covered = 0;
  for (std::size_t i = 0; i + 2 < rgb8.size(); i += 3)
  {
    covered += IsCovered(&rgb8[i], background) ? 1 : 0;
  }
  return rgb8.size() < 3 ? 0.0
                         : static_cast<double>(covered) / static_cast<double>(rgb8.size() / 3);
}

ImageDifference CompareRgb8(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
  const std::uint8_t background[3])
{
  if (a.size() != b.size() || a.empty() || a.size() % 3 != 0)
  {
    throw std::invalid_argument("images of different sizes cannot be compared");
  }
  auto isBackground = [background](const std::uint8_t* p) { return !IsCovered(p, background); };
  ImageDifference d;
  d.Pixels = a.size() / 3;
  double sum = 0.0;
  std::size_t off = 0;
  for (std::size_t i = 0; i < a.size(); i += 3)
  {
    int largest = 0;
    double squares = 0.0;
    for (int c = 0; c < 3; ++c)
    {
      const int delta = static_cast<int>(a[i + c]) - static_cast<int>(b[i + c]);
      largest = std::max(largest, std::abs(delta));
      squares += static_cast<double>(delta) * delta;
    }
    d.Largest = std::max(d.Largest, largest);
    if (isBackground(&a[i]) && isBackground(&b[i]))
    {
      continue;
    }
    ++d.Covered;
    sum += squares;
    off += largest > ImageDifference::OffLevels ? 1 : 0;
  }
  if (d.Covered > 0)
  {
    d.Rmse = std::sqrt(sum / (3.0 * static_cast<double>(d.Covered)));
    d.OffShare = static_cast<double>(off) / static_cast<double>(d.Covered);
  }
  return d;
}

ImageDifference Compare(const Image& a, const Image& b)
{
  return CompareRgb8(a.Rgb8(), b.Rgb8());
}

} // namespace amrsp
