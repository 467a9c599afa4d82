// SPDX-License-Identifier: BSD-3-Clause
// amrsp::ProgressTicker and the core loops that report through it.
#include "amrsp/ParallelFor.h"
#include "amrsp/Progress.h"
#include "amrsp/Render.h"
#include "amrsp/SyntheticCosmo.h"

#include <gtest/gtest.h>

#include <vector>

using namespace amrsp;

namespace
{
/// Checks a run of reports: from 0, never decreasing, ending at 1, at most ~102 of them.
void ExpectWellFormed(const std::vector<double>& reports)
{
  ASSERT_GE(reports.size(), 2u);
  EXPECT_EQ(reports.front(), 0.0);
  EXPECT_EQ(reports.back(), 1.0);
  EXPECT_LE(reports.size(), 102u);
  for (std::size_t i = 1; i < reports.size(); ++i)
  {
    EXPECT_GE(reports[i], reports[i - 1]) << "report " << i;
  }
}
} // namespace

TEST(Progress, TickerReportsFromSeveralThreadsInOrder)
{
  std::vector<double> reports; // the ticker calls one report at a time
  ProgressTicker ticker([&reports](double f) { reports.push_back(f); }, 10000);
  ParallelFor(
    10000, [&ticker](int64_t) { ticker.Done(); }, 2);
  ticker.Finish();
  ExpectWellFormed(reports);
  // how many depends on the threads' timing (a crossing while the other thread reports is not
  // reported; under load that can be most of them), so the count is checked on one thread
  std::vector<double> alone;
  ProgressTicker single([&alone](double f) { alone.push_back(f); }, 10000);
  ParallelFor(
    10000, [&single](int64_t) { single.Done(); }, 1);
  single.Finish();
  ExpectWellFormed(alone);
  EXPECT_EQ(alone.size(), 101u); // 0, every hundredth below 1, and 1
}

TEST(Progress, WithoutACallbackTheTickerOnlyCounts)
{
  ProgressTicker ticker(nullptr, 5);
  ticker.Done(5);
  ticker.Finish();
}

TEST(Progress, GenerationAndReferenceReportAndStayTheSame)
{
  const CosmoParameters p = ParseCosmoParameters("grids=20,levels=2,cells=50k,seed=4");
  std::vector<double> generation;
  const Hierarchy h = GenerateCosmo(p, [&generation](double f) { generation.push_back(f); });
  ExpectWellFormed(generation);
  EXPECT_EQ(h.Values, GenerateCosmo(p).Values); // reporting changes nothing
  RenderSettings s;
  s.Width = s.Height = 24;
  s.View = Camera::ResetTo(h.Origin, h.WorldHi(h.RootCells(), 0));
  s.Transfer.Opacity = { { 0.0, 0.0 }, { 1e6, 1.0 } };
  std::vector<double> rows;
  s.Progress = [&rows](double f) { rows.push_back(f); };
  const Image img = RenderReference(h, s);
  ExpectWellFormed(rows);
  s.Progress = nullptr;
  EXPECT_EQ(Rmse(img, RenderReference(h, s)), 0.0);
}
