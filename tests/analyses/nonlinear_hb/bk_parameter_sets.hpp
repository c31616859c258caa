/// @file
/// @brief The Blankenship & Kahraman (1995) oscillator parameter sets shared by the nonlinear HB
/// tests and the work-precision benchmark (ranges of B&K 1995; see bk_jumps_test.cpp).
#pragma once

#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn::testing {

/// Single-sided impacts: ζ = 0.05, α = 0.1, F_m = 0.1, F_a = 0.03 (folds near Ω = 0.76 and 0.90,
/// the back flank never reached).
inline ClearanceOscillatorParameters BkSingleSidedSet() {
  ClearanceOscillatorParameters p;
  p.zeta = 0.05;
  p.alpha = 0.1;
  p.mean_force = 0.1;
  p.alternating_force = 0.03;
  return p;
}

}  // namespace geardyn::testing
