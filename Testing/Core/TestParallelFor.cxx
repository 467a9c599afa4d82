// SPDX-License-Identifier: BSD-3-Clause
// amrsp/ParallelFor.h: every item runs once, the static partitions are the documented ones, and
// an exception in a loop body reaches the caller.
#include "amrsp/ParallelFor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using namespace amrsp;

TEST(ParallelFor, EveryItemOnce)
{
  for (int threads : { 0, 1, 3, 16 })
  {
    for (int64_t chunk : { 1, 7 })
    {
      for (int64_t n : { 0, 1, 5, 1000 })
      {
        std::vector<std::atomic<int>> seen(static_cast<std::size_t>(n));
        ParallelFor(
          n, [&](int64_t i) { ++seen[static_cast<std::size_t>(i)]; }, threads, chunk);
        for (const std::atomic<int>& s : seen)
        {
          EXPECT_EQ(s.load(), 1) << "threads " << threads << ", chunk " << chunk << ", n " << n;
        }
      }
    }
  }
}

TEST(ParallelFor, InterleavedPartition)
{
  const int64_t n = 103;
  const int threads = 4;
  std::vector<std::thread::id> owner(n);
  std::vector<int64_t> order;
  std::mutex lock;
  ParallelForInterleaved(
    n,
    [&](int64_t i)
    {
      owner[static_cast<std::size_t>(i)] = std::this_thread::get_id();
      std::lock_guard<std::mutex> guard(lock);
      order.push_back(i);
    },
    threads);
  ASSERT_EQ(order.size(), static_cast<std::size_t>(n));
  // items i and i + threads belong to one worker, which runs them in increasing order
  for (int64_t i = 0; i + threads < n; ++i)
  {
    EXPECT_EQ(owner[static_cast<std::size_t>(i)], owner[static_cast<std::size_t>(i + threads)]);
  }
  for (int w = 0; w < threads; ++w)
  {
    int64_t last = -1;
    for (int64_t i : order)
    {
      if (i % threads == w)
      {
        EXPECT_GT(i, last);
        last = i;
      }
    }
  }
}

TEST(ParallelFor, SlicesCoverTheRange)
{
  for (int workers : { 1, 3, 8 })
  {
    std::vector<std::pair<int64_t, int64_t>> slices;
    std::mutex lock;
    ParallelForSlices(100, workers,
      [&](int64_t begin, int64_t end)
      {
        std::lock_guard<std::mutex> guard(lock);
        slices.emplace_back(begin, end);
      });
    std::sort(slices.begin(), slices.end());
    ASSERT_EQ(slices.size(), static_cast<std::size_t>(workers));
    for (int w = 0; w < workers; ++w)
    {
      EXPECT_EQ(slices[static_cast<std::size_t>(w)].first, 100 * w / workers);
      EXPECT_EQ(slices[static_cast<std::size_t>(w)].second, 100 * (w + 1) / workers);
    }
  }
}

TEST(ParallelFor, CallingThreadIsWorkerZero)
{
  std::thread::id zero;
  RunWorkers(3,
    [&](int w)
    {
      if (w == 0)
      {
        zero = std::this_thread::get_id();
      }
    });
  EXPECT_EQ(zero, std::this_thread::get_id());
}

TEST(ParallelFor, ExceptionsReachTheCaller)
{
  const auto throwAt = [](int64_t bad)
  {
    return [bad](int64_t i)
    {
      if (i == bad)
      {
        throw std::runtime_error("item " + std::to_string(i));
      }
    };
  };
  EXPECT_THROW(ParallelFor(500, throwAt(123), 4), std::runtime_error);
  EXPECT_THROW(ParallelFor(500, throwAt(0), 1), std::runtime_error);
  EXPECT_THROW(ParallelForInterleaved(500, throwAt(499), 4), std::runtime_error);
  EXPECT_THROW(ParallelForSlices(10, 4,
                 [](int64_t begin, int64_t)
                 {
                   if (begin > 0)
                   {
                     throw std::invalid_argument("slice");
                   }
                 }),
    std::invalid_argument);
  // the workers still running when one throws finish; nothing is left running afterwards
  std::atomic<int> done(0);
  EXPECT_THROW(RunWorkers(4,
                 [&](int w)
                 {
                   ++done;
                   if (w == 2)
                   {
                     throw std::runtime_error("worker 2");
                   }
                 }),
    std::runtime_error);
  EXPECT_EQ(done.load(), 4);
}
