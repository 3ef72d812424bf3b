#pragma once
// Timing helper shared by the benchmarks.

#include <time.h>

#include <algorithm>
#include <chrono>
#include <limits>

namespace efbench {

/// Best wall time in seconds of `repeats` calls of `f` (steady clock).
template <class F>
double best_seconds(int repeats, F&& f) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

/// CPU time of the calling thread in seconds (the machine is shared: wall times are inflated by
/// other jobs).
inline double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace efbench
