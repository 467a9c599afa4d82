// SPDX-License-Identifier: BSD-3-Clause
// The camera's pixel rays and VTK's camera operations.
#include "amrsp/Camera.h"

#include <cmath>

namespace amrsp
{

void Camera::Ray(
  int width, int height, double px, double py, glm::dvec3& origin, glm::dvec3& direction) const
{
  const glm::dvec3 forward = glm::normalize(FocalPoint - Position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, ViewUp));
  const glm::dvec3 up = glm::cross(right, forward);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  const double x = 2.0 * px / width - 1.0;
  const double y = 2.0 * py / height - 1.0;
  if (Parallel)
  {
    origin = Position + x * ParallelScale * aspect * right + y * ParallelScale * up;
    direction = forward;
    return;
  }
  const double h = std::tan(glm::radians(ViewAngle) * 0.5);
  origin = Position;
  direction = glm::normalize(forward + x * h * aspect * right + y * h * up);
}

Camera Camera::ResetTo(const glm::dvec3& lo, const glm::dvec3& hi)
{
  Camera c;
  c.FocalPoint = 0.5 * (lo + hi);
  double radius = 0.5 * glm::length(hi - lo);
  radius = radius > 0.0 ? radius : 1.0;
  const double distance = radius / std::sin(glm::radians(c.ViewAngle) * 0.5);
  c.Position = c.FocalPoint + glm::dvec3(0.0, 0.0, distance);
  c.ViewUp = glm::dvec3(0.0, 1.0, 0.0);
  c.ParallelScale = radius;
  return c;
}

namespace
{
/// Rotation of `v` by `degrees` about the unit `axis` (right-handed, as vtkTransform::RotateWXYZ).
glm::dvec3 Rotate(const glm::dvec3& v, const glm::dvec3& axis, double degrees)
{
  const double a = glm::radians(degrees);
  const glm::dvec3 k = glm::normalize(axis);
  return v * std::cos(a) + glm::cross(k, v) * std::sin(a) +
    k * glm::dot(k, v) * (1.0 - std::cos(a));
}
} // namespace

void Camera::Azimuth(double degrees)
{
  Position = FocalPoint + Rotate(Position - FocalPoint, ViewUp, degrees);
}

void Camera::Elevation(double degrees)
{
  const glm::dvec3 right = glm::normalize(glm::cross(FocalPoint - Position, ViewUp));
  Position = FocalPoint + Rotate(Position - FocalPoint, -right, degrees);
}

void Camera::OrthogonalizeViewUp()
{
  const glm::dvec3 forward = glm::normalize(FocalPoint - Position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, ViewUp));
  ViewUp = glm::cross(right, forward);
}

void Camera::Zoom(double factor)
{
  if (factor <= 0.0)
  {
    return;
  }
  if (Parallel)
  {
    ParallelScale /= factor;
  }
  else
  {
    ViewAngle /= factor;
  }
}
} // namespace amrsp
