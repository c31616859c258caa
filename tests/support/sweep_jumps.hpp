/// @file
/// @brief The jump of a stepped time-domain sweep branch, shared by the sweep cross-checks.
#pragma once

#include <cmath>

#include "geardyn/analyses/time_response.hpp"

namespace geardyn::test {

/// First step of a branch where the RMS DTE (first mesh) changes by more than the factor `ratio`
/// (> 1: up, < 1: down) from one point to the next: the midpoint of that step [Hz], NaN when none.
inline double JumpFrequency(const TimeSweep& sweep, SweepBranch branch, double ratio) {
  const TimeSweepPoint* previous = nullptr;
  for (const TimeSweepPoint& p : sweep.points) {
    if (p.branch != branch) continue;
    if (previous != nullptr && (ratio > 1.0 ? p.rms_dte[0] > ratio * previous->rms_dte[0]
                                            : p.rms_dte[0] < ratio * previous->rms_dte[0])) {
      return 0.5 * (p.mesh_frequency_hz + previous->mesh_frequency_hz);
    }
    previous = &p;
  }
  return std::nan("");
}

}  // namespace geardyn::test
