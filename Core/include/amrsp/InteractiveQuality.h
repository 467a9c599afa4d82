// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The frame-time budget of interactive frames: which image sample distance (pixels between
/// rays, per axis) and sample-distance scale (multiplies every level's step along the ray) an
/// interactive frame uses so that it fits the seconds allocated to it.
///
/// The cost model: a frame drawn at image sample distance d with sample-distance scale s costs
///   CostFraction(d, s) = (RayShare + (1 - RayShare) / s) / d^2
/// of a full frame, rays falling with the pixel count and, of each ray's cost, the share
/// (1 - RayShare) that is the samples falling with s (RayShare: the kD-tree walk and set-up per
/// ray). The model is only used to scale between rungs: every quality drawn keeps its own
/// measured seconds (the mean of the previous measurement and the new one), and a quality not
/// measured yet is predicted from the measured quality of the nearest cost fraction, scaled by
/// the ratio of their fractions. Fixed costs the model leaves out (the reduced image's
/// composite, the frame's end) thus show in the measured rungs and move the choice one rung
/// coarser, step by step, until the frame fits.
///
/// The rungs go coarser step by step (d = 1, 1.5, 2, 3, 4, 6, 8, 12, 16, each within
/// [MinimumImageSampleDistance, MaximumImageSampleDistance]); an interactive frame takes the
/// finest rung predicted to fit its budget, or the coarsest. With AdjustSampleDistance the
/// sample distance grows with the image sample distance (s = d, as VTK's GPU ray cast mapper
/// scales its sample distance by its reduction factor), else s = 1. Still frames are always full
/// quality (d = s = 1) and only feed the estimate.

#include <map>
#include <utility>

namespace amrsp
{

/// How one frame samples: d and s of the file comment. Full quality is {1, 1}.
struct FrameQuality
{
  double ImageSampleDistance = 1.0;
  double SampleDistanceScale = 1.0;
  bool IsFull() const
  {
    return this->ImageSampleDistance == 1.0 && this->SampleDistanceScale == 1.0;
  }
};

class InteractiveQuality
{
public:
  struct Limits
  {
    double MinimumImageSampleDistance = 1.0;
    double MaximumImageSampleDistance = 10.0;
    bool AdjustSampleDistance = true;
  };

  /// The share of a ray's cost that does not fall with the sample distance (the model above).
  static constexpr double RayShare = 0.3;

  /// The quality for an interactive frame with `budgetSeconds` allocated. Without a
  /// measurement yet, the coarsest rung within the limits.
  FrameQuality Choose(double budgetSeconds, const Limits& limits) const;

  /// The seconds a frame of quality `q` is predicted to take: its own measurement, else scaled
  /// from the nearest measured quality (0 without any measurement).
  double Predict(const FrameQuality& q) const;

  /// Feeds the measured seconds of a frame drawn with quality `q` into its measurement.
  void Record(const FrameQuality& q, double seconds);

  /// Forgets the measurements (new data, new size of the image).
  void Reset() { this->Measured.clear(); }

  /// The predicted seconds of a full-quality frame (0 without any measurement).
  double GetFullSeconds() const { return this->Predict(FrameQuality()); }

  /// The fraction of a full frame's cost that quality `q` costs in the model.
  static double CostFraction(const FrameQuality& q);

private:
  /// Measured seconds per quality drawn, keyed by (image sample distance, scale).
  std::map<std::pair<double, double>, double> Measured;
};

} // namespace amrsp
