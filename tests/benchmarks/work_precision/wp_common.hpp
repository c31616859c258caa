/// @file
/// @brief What every work-precision program shares (architecture §3.10): the wall-time
/// measurement and the CSV row `method, knob, wall_time_s, error, evaluations`.
#pragma once

#include <chrono>
#include <cstdio>
#include <functional>

namespace geardyn::wp {

/// Wall time of one call of fn [s], repeated until ≥ 0.05 s have elapsed.
inline double TimeIt(const std::function<void()>& fn) {
  using Clock = std::chrono::steady_clock;
  int reps = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  do {
    fn();
    ++reps;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < 0.05);
  return elapsed / reps;
}

/// One CSV row of the work-precision table.
inline void Row(const char* method, double knob, double time, double error, double evaluations) {
  std::printf("%s,%g,%.4e,%.4e,%.0f\n", method, knob, time, error, evaluations);
}

}  // namespace geardyn::wp
