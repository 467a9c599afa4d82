// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The step's hierarchy for the test's CPU reference (TestInSitu.py), built apart from the Catalyst
// adaptor: from the simulation's block list and its analytic field, with arrays of their own, so
// that a defect in CatalystAdaptor::Describe (a box, an origin, a level, a copy) reaches the
// rendered image but not the reference.
#include <string>

namespace insitu
{
class BlobSimulation;

/// Writes the simulation's current step (one rank owning every block) as a VTK XML AMR file.
void WriteReferenceHierarchy(const BlobSimulation& simulation, const std::string& path);
} // namespace insitu
