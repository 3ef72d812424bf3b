#pragma once
// Timing helper shared by the benchmarks.

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

}  // namespace efbench
