// Wall time for progress lines, summaries and benchmarks: a monotonic clock and the seconds since a point on it.
#pragma once

#include <chrono>

namespace lueur {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace lueur
