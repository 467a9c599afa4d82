// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspProgress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace amrsp
{
namespace harness
{

namespace
{
using Clock = std::chrono::steady_clock;

struct ProgressState
{
  bool Quiet = false;
  std::string Step;
  Clock::time_point Started;
  Clock::time_point LastDrawn;
  bool Drawn = false; // the current step's line is on the terminal
  int Fd = STDERR_FILENO;
};

void Write(int fd, const std::string& text)
{
  const ssize_t ignored = write(fd, text.data(), text.size());
  (void)ignored;
}

ProgressState& State()
{
  static ProgressState state;
  return state;
}

double DrawAfterSeconds()
{
  const char* after = std::getenv("AMRSP_PROGRESS_AFTER");
  return after ? std::atof(after) : 1.0;
}
} // namespace

void SetProgressQuiet(bool quiet)
{
  State().Quiet = quiet;
}

void SetProgressDescriptor(int fd)
{
  State().Fd = fd;
}

void ReportProgress(const std::string& step, const std::string& detail, double fraction)
{
  ProgressState& s = State();
  if (s.Quiet || !isatty(s.Fd))
  {
    return;
  }
  const Clock::time_point now = Clock::now();
  if (step != s.Step || (fraction <= 0.0 && s.Drawn))
  {
    if (s.Drawn)
    {
      Write(s.Fd, "\n");
    }
    s.Step = step;
    s.Started = now;
    s.Drawn = false;
  }
  const double elapsed = std::chrono::duration<double>(now - s.Started).count();
  const bool done = fraction >= 1.0;
  const bool due = std::chrono::duration<double>(now - s.LastDrawn).count() >= 0.1;
  if (elapsed < DrawAfterSeconds() || (!due && !done))
  {
    return;
  }
  constexpr int width = 30;
  const int filled = static_cast<int>(std::min(1.0, std::max(0.0, fraction)) * width);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(width, '.');
  const std::string label = step + ": " + detail;
  char line[160];
  std::snprintf(line, sizeof(line), "\ramrsp: %-44.44s [%s] %3d%%%s", label.c_str(), bar.c_str(),
    static_cast<int>(100.0 * std::min(1.0, std::max(0.0, fraction))), done ? "\n" : "");
  std::fflush(stderr); // what the tool printed before the bar comes first
  Write(s.Fd, line);
  s.Drawn = !done;
  s.LastDrawn = now;
  if (done)
  {
    s.Step.clear();
  }
}

ProgressCallback ProgressOf(const std::string& step, const std::string& detail)
{
  return [step, detail](double fraction) { ReportProgress(step, detail, fraction); };
}

} // namespace harness
} // namespace amrsp
