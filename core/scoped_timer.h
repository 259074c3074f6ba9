// Wall-time measurement: SecondsSince for a phase's time, ScopedTimer to add
// the wall time of a scope to a running total [s] (profiling counters, e.g.
// the contact broad phase's share of a step: contact/pair_set.h).
#pragma once

#include <chrono>

namespace ipstep {

using WallClock = std::chrono::steady_clock;

// Seconds of wall time since `start` (a WallClock::now()).
inline double SecondsSince(WallClock::time_point start) {
  return std::chrono::duration<double>(WallClock::now() - start).count();
}

class ScopedTimer {
 public:
  explicit ScopedTimer(double* total_seconds)
      : total_(total_seconds), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    *total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  double* total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace ipstep
