// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRFrameBudget.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkVolume.h"

#include "vtkAMRMapperOpenGL.h"

#include <algorithm>
#include <cmath>

//------------------------------------------------------------------------------
amrsp::FrameQuality vtkSinglePassAMRFrameBudget::Begin(
  vtkVolume* vol, const Settings& settings, int width, int height, unsigned long dataTime)
{
  if (width != this->Width || height != this->Height || dataTime != this->DataTime)
  {
    this->Quality.Reset();
    this->Width = width;
    this->Height = height;
    this->DataTime = dataTime;
  }
  this->LastBudget = vol->GetAllocatedRenderTime();
  this->LastInteractive = settings.AutoAdjustSampleDistances && this->LastBudget < 1.0;
  amrsp::FrameQuality quality;
  if (!settings.AutoAdjustSampleDistances)
  {
    quality.ImageSampleDistance = settings.ImageSampleDistance;
  }
  else if (this->LastInteractive)
  {
    amrsp::InteractiveQuality::Limits limits;
    limits.MinimumImageSampleDistance = settings.MinimumImageSampleDistance;
    limits.MaximumImageSampleDistance = settings.MaximumImageSampleDistance;
    limits.AdjustSampleDistance = settings.InteractiveAdjustSampleDistances;
    quality = this->Quality.Choose(this->LastBudget, limits);
  }
  this->LastQuality = quality;
  this->LastSeconds = 0.0;
  this->Start = std::chrono::steady_clock::now();
  return quality;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRFrameBudget::End(const Settings& settings, const amrsp::FrameQuality& quality)
{
  if (!settings.AutoAdjustSampleDistances)
  {
    return;
  }
  glFinish(); // the frame's cost is the GPU's work, not the submission's
  this->LastSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  this->Quality.Record(quality, this->LastSeconds);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRFrameBudget::ReducedSize(int width, int height, double d, int& w, int& h)
{
  w = std::max(1, static_cast<int>(std::ceil(width / d)));
  h = std::max(1, static_cast<int>(std::ceil(height / d)));
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRFrameBudget::DrawRays(
  vtkOpenGLRenderWindow* renWin, bool reduced, const std::function<void()>& draw)
{
  if (!reduced)
  {
    draw();
    return;
  }
  vtkOpenGLState* state = renWin->GetState();
  vtkOpenGLState::ScopedglViewport viewportSaved(state);
  vtkOpenGLState::ScopedglClearColor clearColorSaved(state);
  vtkOpenGLState::ScopedglEnableDisable scissorSaved(state, GL_SCISSOR_TEST);
  this->Image.BeginDrawing(state);
  draw();
  this->Image.EndDrawing();
}
