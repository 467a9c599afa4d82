// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Progress of the core's long loops (the synthetic generation, the CPU integrators' rows) for a
/// caller that shows it: a callback taking the fraction done, from 0 to 1.

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>

namespace amrsp
{

/// Receives the fraction done (0 to 1, never decreasing). Called on one thread at a time, not
/// necessarily the caller's.
using ProgressCallback = std::function<void(double fraction)>;

/// Counts finished items from any thread and reports to `callback` each time the count crosses
/// another hundredth of `total`, one report at a time (a thread that finds a report running
/// skips its own: the next crossing reports the newer count). Finish() reports 1 on the calling
/// thread. Without a callback it only counts.
class ProgressTicker
{
public:
  ProgressTicker(ProgressCallback callback, int64_t total)
    : Callback(std::move(callback))
    , Total(total > 0 ? total : 1)
  {
    if (this->Callback)
    {
      this->Callback(0.0);
    }
  }

  /// `n` more items are done.
  void Done(int64_t n = 1)
  {
    if (!this->Callback)
    {
      return;
    }
    const int64_t before = this->Count.fetch_add(n);
    const int64_t after = before + n;
    if (before * 100 / this->Total == after * 100 / this->Total)
    {
      return;
    }
    std::unique_lock<std::mutex> lock(this->Reporting, std::try_to_lock);
    if (!lock.owns_lock())
    {
      return;
    }
    const double fraction = static_cast<double>(this->Count.load()) / this->Total;
    if (fraction > this->Reported && fraction < 1.0)
    {
      this->Reported = fraction;
      this->Callback(fraction);
    }
  }

  /// All items are done: reports 1.
  void Finish()
  {
    if (this->Callback)
    {
      std::lock_guard<std::mutex> lock(this->Reporting);
      this->Reported = 1.0;
      this->Callback(1.0);
    }
  }

private:
  ProgressCallback Callback;
  int64_t Total;
  std::atomic<int64_t> Count{ 0 };
  std::mutex Reporting;
  double Reported = 0.0; // guarded by Reporting
};

} // namespace amrsp
