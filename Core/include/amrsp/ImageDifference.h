// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Image differences measured where the volume is: a frame's background pixels agree whatever
/// the renderer does, so an RMSE over the whole frame shrinks with the volume's share of it.

#include <cstdint>
#include <string>
#include <vector>

namespace amrsp
{

struct Image;

/// The difference of two 8-bit RGB images of one size, counted over the pixels that either
/// image shows as not background (a pixel is background when all three channels are within
/// `BackgroundLevel` of the background colour's; black unless stated).
struct ImageDifference
{
  /// RMSE of the RGB channels (0-255 units) over the covered pixels; 0 when none is covered.
  double Rmse = 0.0;
  /// Share of the covered pixels (0-1) whose largest channel difference exceeds `OffLevels`.
  double OffShare = 0.0;
  /// Covered pixels and all pixels of the frame.
  std::size_t Covered = 0;
  std::size_t Pixels = 0;
  /// Largest channel difference anywhere (0-255).
  int Largest = 0;

  /// The covered share of the frame (0-1).
  double Coverage() const { return Pixels ? static_cast<double>(Covered) / Pixels : 0.0; }
  /// "RMSE 1.23 over 8.2 % of the frame, 0.40 % of those pixels off by more than 8 levels"
  std::string Describe() const;

  static constexpr int OffLevels = 8;
  static constexpr int BackgroundLevel = 2;
};

/// Interleaved 8-bit RGB (Image::Rgb8, a PNG read back) of the same size; throws
/// std::invalid_argument otherwise. `background` is the 8-bit background colour.
ImageDifference CompareRgb8(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b,
  const std::uint8_t background[3] = nullptr);
ImageDifference Compare(const Image& a, const Image& b);

/// Whether the 8-bit RGB pixel `rgb` is covered by the volume: a channel more than
/// ImageDifference::BackgroundLevel from the background colour's (black when null). The one
/// definition of a covered pixel in the image tests (Python: PluginTestKit.covered).
bool IsCovered(const std::uint8_t* rgb, const std::uint8_t* background = nullptr);
/// The share (0-1) of the covered pixels of interleaved 8-bit RGB `rgb8` (0 when empty).
double CoveredShare(
  const std::vector<std::uint8_t>& rgb8, const std::uint8_t* background = nullptr);

} // namespace amrsp
