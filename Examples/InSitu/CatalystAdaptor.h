// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file CatalystAdaptor.h
 * @brief Hands a BlobSimulation's steps to ParaView Catalyst through the adaptor API every
 * ParaView from 5.11 on provides (vtkCPProcessor), as a vtkOverlappingAMR.
 *
 * The vtkOverlappingAMR of a step holds every block's box (all ranks know the whole hierarchy)
 * and, on each rank, the image data of the blocks that rank owns. Their cell arrays borrow the
 * simulation's values (vtkFloatArray::SetArray without ownership): nothing is copied, and the
 * arrays must not outlive the step, which Catalyst's pipelines do not need.
 */
#ifndef CatalystAdaptor_h
#define CatalystAdaptor_h

#include "vtkSmartPointer.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkDataObject;
class vtkOverlappingAMR;

namespace insitu
{

class BlobSimulation;

class CatalystAdaptor
{
public:
  /// Settings for the script: each reaches it with every step as a one-value string array of
  /// the data description's user data (name, value).
  using Settings = std::vector<std::pair<std::string, std::string>>;

  /// Initialises Catalyst on MPI_COMM_WORLD, loads the plugin (a path; empty: none) and the
  /// Catalyst Python script. Throws std::runtime_error naming what failed.
  CatalystAdaptor(const std::string& script, const std::string& plugin, const Settings& settings);
  ~CatalystAdaptor();

  /// What handing one step over cost this rank, in seconds: building the vtkOverlappingAMR
  /// (boxes and borrowed arrays), and Catalyst's CoProcess (the script: the representation's
  /// build, upload and the render).
  struct StepCost
  {
    bool Processed = false; ///< false when no pipeline asked for this step
    double DescribeSeconds = 0.0;
    double CoProcessSeconds = 0.0;
    /// Values of the object Catalyst received whose arrays are the simulation's own memory (read
    /// back from that object and compared with the blocks' addresses: a copy anywhere between
    /// the simulation and Catalyst is not counted).
    long long BorrowedValues = 0;
  };

  /// Hands the simulation's current step to Catalyst where a pipeline wants it.
  StepCost CoProcess(BlobSimulation& simulation);

  /// The simulation's current step as a vtkOverlappingAMR: every block's box, and image data
  /// for the blocks this rank owns, whose cell array "density" borrows the simulation's values.
  static vtkSmartPointer<vtkOverlappingAMR> Describe(BlobSimulation& simulation);

  /// The values of `handed`'s "density" arrays that are exactly one of the simulation's blocks'
  /// memory (same address and length).
  static long long CountSimulationValues(vtkDataObject* handed, const BlobSimulation& simulation);

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

} // namespace insitu

#endif
