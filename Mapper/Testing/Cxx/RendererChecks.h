// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Checks the mapper image tests make on a tool renderer (Render(azimuth, ms), LastCamera(),
/// GetRenderer(), NumberOfBuilds()): opaque geometry in front of the volume, and a
/// transfer-function change.

#include "MapperTestHelpers.h"

#include "amrsp/Camera.h"
#include "amrsp/Image.h"
#include "amrsp/ImageDifference.h"
#include "amrsp/RenderSettings.h"

#include "vtkActor.h"
#include "vtkPiecewiseFunction.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace mappertest
{
/// An unlit, opaque square of half-size `half` and grey level `grey` (0 black, 1 white) centred
/// at `centre`, facing `normal`.
inline vtkSmartPointer<vtkActor> OpaqueSquare(const glm::dvec3& centre, const glm::dvec3& normal,
  const glm::dvec3& up, double half, double grey)
{
  const glm::dvec3 n = glm::normalize(normal);
  const glm::dvec3 u = glm::normalize(up - glm::dot(up, n) * n);
  const glm::dvec3 r = glm::cross(u, n);
  const glm::dvec3 o = centre - half * r - half * u;
  const glm::dvec3 p1 = o + 2.0 * half * r;
  const glm::dvec3 p2 = o + 2.0 * half * u;
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(o.x, o.y, o.z);
  plane->SetPoint1(p1.x, p1.y, p1.z);
  plane->SetPoint2(p2.x, p2.y, p2.z);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(grey, grey, grey);
  actor->GetProperty()->SetAmbient(1.0);
  actor->GetProperty()->SetDiffuse(0.0);
  actor->GetProperty()->SetSpecular(0.0);
  actor->GetProperty()->LightingOff();
  return actor;
}

/// The view of an occluder test: the camera of the last frame, the unit vector from its focal
/// point to it, and a size relative to their distance (world units).
struct OccluderView
{
  amrsp::Camera View;
  glm::dvec3 ToCamera{ 0.0 };
  double Half = 0.0; ///< 0.15 x the camera's distance to its focal point

  /// A black square through the focal point facing the camera, 4 Half wide (one per render
  /// window: a mapper's buffers belong to one context).
  vtkSmartPointer<vtkActor> SquareThroughCentre() const
  {
    return OpaqueSquare(View.FocalPoint, ToCamera, View.ViewUp, 2.0 * Half, 0.0);
  }
};

/// Renders `gpu` (a tool renderer: Render(azimuth, ms), LastCamera(), GetRenderer()) plainly and
/// with a white square halfway between the camera and its focal point, and checks that the square
/// covers the central 8 x 8 pixels, where the volume shows, in pure white. Returns the plain image
/// and the view for the next checks.
template <typename Renderer>
amrsp::Image CheckSquareInFrontHides(Renderer& gpu, OccluderView& view)
{
  double ms = 0.0;
  const amrsp::Image plain = gpu.Render(0.0, ms);
  const amrsp::Camera c = gpu.LastCamera();
  view.View = c;
  view.ToCamera = glm::normalize(c.Position - c.FocalPoint);
  const double distance = glm::length(c.Position - c.FocalPoint);
  view.Half = 0.15 * distance;
  vtkSmartPointer<vtkActor> front = OpaqueSquare(
    c.FocalPoint + 0.5 * distance * view.ToCamera, view.ToCamera, c.ViewUp, view.Half * 0.5, 1.0);
  gpu.GetRenderer()->AddActor(front);
  const amrsp::Image hidden = gpu.Render(0.0, ms);
  gpu.GetRenderer()->RemoveActor(front);
  const std::vector<std::uint8_t> rgb = hidden.Rgb8();
  const std::vector<std::uint8_t> rgbPlain = plain.Rgb8();
  const int w = hidden.Width, hh = hidden.Height;
  int white = 0, under = 0, volumeThere = 0;
  for (int j = hh / 2 - 4; j < hh / 2 + 4; ++j)
  {
    for (int i = w / 2 - 4; i < w / 2 + 4; ++i)
    {
      const std::size_t k = 3 * (static_cast<std::size_t>(j) * w + i);
      ++under;
      white += (rgb[k] == 255 && rgb[k + 1] == 255 && rgb[k + 2] == 255) ? 1 : 0;
      volumeThere += (rgbPlain[k] + rgbPlain[k + 1] + rgbPlain[k + 2] > 12) ? 1 : 0;
    }
  }
  Check(volumeThere > under / 2 && white == under,
    "opaque square in front of the volume: " + std::to_string(white) + " of " +
      std::to_string(under) + " central pixels stay pure white");
  return plain;
}
/// Renders `gpu` (its first volume) before and after a change of the opacity function to a ramp
/// over the transfer function of `s`, restores it, and checks that the change shows and that no
/// frame so far rebuilt the data (`frames`: what the message calls them). Returns the image
/// before the change, which the restored function renders again.
template <typename Renderer>
amrsp::Image CheckTransferChangeRebuildsNothing(
  Renderer& gpu, const amrsp::RenderSettings& s, const std::string& frames)
{
  double ms = 0.0;
  vtkVolume* volume = vtkVolume::SafeDownCast(gpu.GetRenderer()->GetVolumes()->GetItemAsObject(0));
  vtkPiecewiseFunction* opacity = volume->GetProperty()->GetScalarOpacity();
  const amrsp::Image before = gpu.Render(0.0, ms);
  vtkNew<vtkPiecewiseFunction> saved;
  saved->DeepCopy(opacity);
  opacity->RemoveAllPoints();
  opacity->AddPoint(s.Transfer.Opacity.front().X, 0.0);
  opacity->AddPoint(s.Transfer.Opacity.back().X, 0.2);
  const amrsp::Image changed = gpu.Render(0.0, ms);
  opacity->DeepCopy(saved);
  Check(amrsp::Rmse(before, changed) > 1.0, "a transfer-function change changes the image");
  Check(gpu.NumberOfBuilds() == 1,
    "data built once over " + frames + " with camera and transfer-function changes (builds: " +
      std::to_string(gpu.NumberOfBuilds()) + ")");
  return before;
}
} // namespace mappertest
