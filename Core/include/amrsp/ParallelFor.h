// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The core's one way to run a loop on several threads. Worker 0 runs on the calling thread,
/// workers 1..n-1 on threads started for the call; every call returns after all of them have
/// finished. An exception thrown by a loop body stops the workers from taking further items and
/// is rethrown to the caller (the one of the lowest worker when several threw).
///
/// Three ways to hand out the items, so that a caller whose output depends on which worker
/// computed what (per-worker state reduced afterwards) keeps a fixed partition:
/// - ParallelFor: dynamic, `chunk` items at a time from a shared counter (load balance);
/// - ParallelForInterleaved: static, worker w takes items w, w + workers, w + 2 workers, ...;
/// - ParallelForSlices: static, worker w takes the contiguous slice [n w / W, n (w + 1) / W).

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <thread>
#include <vector>

namespace amrsp
{

/// `requested` when positive, else the hardware's concurrency (at least 1).
inline int WorkerCount(int requested = 0)
{
  if (requested > 0)
  {
    return requested;
  }
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/// Runs work(w) for every worker w in [0, max(1, workers)) at the same time.
template <class Work>
void RunWorkers(int workers, const Work& work)
{
  workers = std::max(1, workers);
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(workers));
  auto run = [&work, &errors](int w)
  {
    try
    {
      work(w);
    }
    catch (...)
    {
      errors[static_cast<std::size_t>(w)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(workers - 1));
  try
  {
    for (int w = 1; w < workers; ++w)
    {
      pool.emplace_back(run, w);
    }
  }
  catch (...)
  {
    errors[0] = std::current_exception(); // a thread could not be started: no worker 0
    workers = 0;
  }
  if (workers > 0)
  {
    run(0);
  }
  for (std::thread& t : pool)
  {
    t.join();
  }
  for (const std::exception_ptr& e : errors)
  {
    if (e)
    {
      std::rethrow_exception(e);
    }
  }
}

/// f(i) for every i in [0, n) on WorkerCount(threads) workers (at most one per chunk), each
/// taking the next `chunk` items from a shared counter until none is left. The order in which
/// items run is unspecified: for bodies whose results do not depend on it.
template <class F>
void ParallelFor(int64_t n, const F& f, int threads = 0, int64_t chunk = 1)
{
  chunk = std::max<int64_t>(1, chunk);
  const int64_t chunks = (std::max<int64_t>(0, n) + chunk - 1) / chunk;
  const int workers = static_cast<int>(std::min<int64_t>(WorkerCount(threads), chunks));
  std::atomic<int64_t> next(0);
  std::atomic<bool> failed(false);
  RunWorkers(workers,
    [&](int)
    {
      while (!failed.load(std::memory_order_relaxed))
      {
        const int64_t begin = next.fetch_add(chunk);
        if (begin >= n)
        {
          return;
        }
        const int64_t end = std::min(n, begin + chunk);
        try
        {
          for (int64_t i = begin; i < end; ++i)
          {
            f(i);
          }
        }
        catch (...)
        {
          failed = true;
          throw;
        }
      }
    });
}

/// f(i) for every i in [0, n); with W = min(WorkerCount(threads), n) workers, worker w runs the
/// items w, w + W, w + 2 W, ... in increasing order.
template <class F>
void ParallelForInterleaved(int64_t n, const F& f, int threads = 0)
{
  const int workers = static_cast<int>(std::min<int64_t>(WorkerCount(threads), n));
  std::atomic<bool> failed(false);
  RunWorkers(workers,
    [&](int w)
    {
      try
      {
        for (int64_t i = w; i < n && !failed.load(std::memory_order_relaxed); i += workers)
        {
          f(i);
        }
      }
      catch (...)
      {
        failed = true;
        throw;
      }
    });
}

/// body(begin, end) once per worker w in [0, max(1, workers)), on the contiguous slices
/// [n w / W, n (w + 1) / W) that together cover [0, n).
template <class Body>
void ParallelForSlices(int64_t n, int workers, const Body& body)
{
  const int64_t count = std::max(1, workers);
  RunWorkers(static_cast<int>(count), [&](int w) { body(n * w / count, n * (w + 1) / count); });
}

} // namespace amrsp
