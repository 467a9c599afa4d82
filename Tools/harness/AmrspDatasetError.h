// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The errors of reading a dataset: one line for the user each.

#include <stdexcept>
#include <string>

namespace amrsp
{
namespace harness
{

/// A problem with a dataset (a missing, damaged or unreadable file, a failed read); what() is
/// one line for the user that names the file and what is wrong.
class DatasetError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// A read that ended its child process abnormally (AmrspChildProcess.h): ExitCode is what the
/// tool exits with (70 the reader crashed or aborted, 75 it did not finish in time).
class ReaderFailure : public DatasetError
{
public:
  ReaderFailure(const std::string& message, int exitCode)
    : DatasetError(message)
    , ExitCode(exitCode)
  {
  }
  int ExitCode;
};

} // namespace harness
} // namespace amrsp
