// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRCheckedReader
 * @brief   reads an Enzo run, an AMReX plotfile or a VTK XML AMR file without letting a damaged
 *          file or VTK's reader take the process down
 *
 * Each read (1) checks the headers the file's own metadata names, before any VTK reader opens
 * them (Enzo .hierarchy and grid files, AMReX Header, Cell_H and FAB headers, VTK XML AMR levels,
 * boxes and pieces: Tools/harness/AmrspFileChecks.h), then (2) runs a new VTK reader
 * (vtkAMREnzoReader, vtkAMReXGridReader or vtkXMLUniformGridAMRReader, every level and every cell
 * array) in a child process bounded in time (ReadTimeout) and address space, which hands the AMR
 * back through shared memory (vtkSinglePassAMRCheckedReaderTransfer.h).
 *
 * A damaged file, a reader that aborts, crashes, loops or asks for more memory than the files
 * can hold ends in one error (vtkErrorMacro; LastError keeps it) that names the file and what
 * is wrong, and an empty output: never in a signal or a hang of this process. Every file gets a
 * reader of its own, so that a series whose levels change reads (ParaView's file series calls
 * SetFileName between steps; a reused vtkAMREnzoReader aborts when a later dump has more
 * levels), and a reader's leaked file descriptors end with its child.
 *
 * In parallel each piece (rank) keeps every level's boxes and the data of the blocks dealt to
 * it round-robin in level order, as VTK's AMR readers deal them; every rank reads the files.
 *
 * The output's time (TIME_STEPS) is the dump's: an Enzo parameter file's InitialTime, an AMReX
 * Header's time; VTK XML AMR files have none.
 *
 * FileName: an Enzo .hierarchy (or its .boundary), an AMReX plotfile folder or its Header, a
 * .vthb/.vth file. ReadInChildProcess off reads in this process, after the same checks (for
 * debuggers; a reader's abort or hang is then this process's). The environment variable
 * AMRSP_SKIP_FILE_CHECKS=1 skips the checks (the tests use it to reach the child's guard).
 */
#ifndef vtkSinglePassAMRCheckedReader_h
#define vtkSinglePassAMRCheckedReader_h

#include "vtkOverlappingAMRAlgorithm.h"
#include "vtkSinglePassAMRReaderModule.h" // for export macro

#include <string> // for ivar

class VTKSINGLEPASSAMRREADER_EXPORT vtkSinglePassAMRCheckedReader
  : public vtkOverlappingAMRAlgorithm
{
public:
  static vtkSinglePassAMRCheckedReader* New();
  vtkTypeMacro(vtkSinglePassAMRCheckedReader, vtkOverlappingAMRAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file (or AMReX plotfile folder) to read.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  ///@{
  /// Seconds VTK's reader may take on one file before its child process is stopped (default
  /// 120, at least 1).
  vtkSetClampMacro(ReadTimeout, double, 1.0, 1.0e6);
  vtkGetMacro(ReadTimeout, double);
  ///@}

  ///@{
  /// Whether VTK's reader runs in a bounded child process (default on).
  vtkSetMacro(ReadInChildProcess, bool);
  vtkGetMacro(ReadInChildProcess, bool);
  vtkBooleanMacro(ReadInChildProcess, bool);
  ///@}

  ///@{
  /// Enzo: values in CGS units (on) or in the simulation's code units (off, the default, as
  /// ParaView's own Enzo reader; VTK's vtkAMREnzoReader and amrsp convert by default).
  vtkSetMacro(ConvertToCGS, bool);
  vtkGetMacro(ConvertToCGS, bool);
  vtkBooleanMacro(ConvertToCGS, bool);
  ///@}

  /// The one-line message of the last read that failed; empty after a read that succeeded.
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkSinglePassAMRCheckedReader();
  ~vtkSinglePassAMRCheckedReader() override;

  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  char* FileName = nullptr;
  double ReadTimeout = 120.0;
  bool ReadInChildProcess = true;
  bool ConvertToCGS = false;
  std::string LastError;

private:
  vtkSinglePassAMRCheckedReader(const vtkSinglePassAMRCheckedReader&) = delete;
  void operator=(const vtkSinglePassAMRCheckedReader&) = delete;
};

#endif
