// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Opaque geometry the mapper tests put into a volume's scene (links VTK::FiltersSources).

#include "amrsp/Hierarchy.h"

#include "vtkActor.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"

namespace mappertest
{

/// An opaque green sphere at the centre of `h`'s root box, of radius 0.3 of its x extent (48 x 48
/// facets), added to `renderer`: it cuts the volume, so the rays must stop at its depth.
inline void AddCentralSphere(vtkRenderer* renderer, const amrsp::Hierarchy& h)
{
  vtkNew<vtkSphereSource> sphere;
  const glm::dvec3 lo = h.Origin, hi = h.WorldHi(h.RootCells(), 0);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  sphere->SetCenter(centre.x, centre.y, centre.z);
  sphere->SetRadius(0.3 * (hi.x - lo.x));
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.2, 0.8, 0.2);
  renderer->AddActor(actor);
}

} // namespace mappertest
