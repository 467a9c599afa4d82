// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRFrameBudget
 * @brief   the single-pass mapper's interactive frames: their quality, reduced image and timing
 *
 * Private to the module. A frame is interactive when AutoAdjustSampleDistances is on and the
 * volume has less than one second allocated to it (vtkRenderer splits 1 / DesiredUpdateRate of
 * the render window among its props; ParaView asks 5 frames a second while the camera moves and
 * 0.002 for still renders, VTK's interactor 15 and 0.0001). An interactive frame takes the
 * quality amrsp::InteractiveQuality predicts to fit the allocated time; a still frame is drawn at
 * full quality (image sample distance 1, the mapper's own sample distance), exactly as without
 * this class. With AutoAdjustSampleDistances off, every frame uses ImageSampleDistance.
 *
 * A frame whose image sample distance d exceeds 1 casts its rays into an offscreen image of
 * ceil(W / d) x ceil(H / d) pixels (W x H the viewport) that is then magnified bilinearly over
 * the viewport. With AutoAdjustSampleDistances on, every frame's seconds (from Begin to the
 * glFinish in End) feed the estimate.
 */
#ifndef vtkSinglePassAMRFrameBudget_h
#define vtkSinglePassAMRFrameBudget_h

#include "amrsp/InteractiveQuality.h"

#include "vtkAMRMapperOffscreenImage.h"

#include <chrono>
#include <functional>

class vtkOpenGLRenderWindow;
class vtkVolume;

class vtkSinglePassAMRFrameBudget
{
public:
  /// The mapper's settings (VTK's names and meanings).
  struct Settings
  {
    bool AutoAdjustSampleDistances = true;
    double ImageSampleDistance = 1.0;
    double MinimumImageSampleDistance = 1.0;
    double MaximumImageSampleDistance = 10.0;
    bool InteractiveAdjustSampleDistances = true;
  };

  /// The quality of the frame about to be drawn into a `width` x `height` viewport; starts its
  /// clock. A change of the viewport's size or of `dataTime` (a new build) forgets the estimate.
  amrsp::FrameQuality Begin(
    vtkVolume* vol, const Settings& settings, int width, int height, unsigned long dataTime);

  /// Ends the frame drawn with `quality`: with AutoAdjustSampleDistances on, waits for it
  /// (glFinish) and feeds its seconds into the estimate.
  void End(const Settings& settings, const amrsp::FrameQuality& quality);

  /// Runs `draw` (the rays' draw call): into the viewport, or into Image (cleared, its viewport
  /// and no scissor test, all restored afterwards) when `reduced`.
  void DrawRays(vtkOpenGLRenderWindow* renWin, bool reduced, const std::function<void()>& draw);

  /// The reduced image's size for a viewport of `width` x `height` at image sample distance `d`.
  static void ReducedSize(int width, int height, double d, int& w, int& h);

  /// The offscreen image the rays of a reduced frame go into.
  vtkAMRMapperOffscreenImage Image;

  // what the last frame did
  bool LastInteractive = false;
  amrsp::FrameQuality LastQuality;
  double LastSeconds = 0.0; // measured (AutoAdjustSampleDistances on), else 0
  double LastBudget = 0.0;  // the volume's allocated render time

  const amrsp::InteractiveQuality& GetQuality() const { return this->Quality; }

private:
  amrsp::InteractiveQuality Quality;
  std::chrono::steady_clock::time_point Start;
  int Width = 0;
  int Height = 0;
  unsigned long DataTime = 0;
};

#endif
