#pragma once
/// @file
/// CPU time of the calling thread [s] (CLOCK_THREAD_CPUTIME_ID; 0 if the clock is unavailable),
/// for measuring work on machines shared with other processes. Header-only.

#include <ctime>

namespace rover {

inline double ThreadCpuSeconds() {
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0.0;
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

}  // namespace rover
