/// @file
/// @brief The Blankenship & Kahraman (1995) oscillator parameter sets shared by the nonlinear HB
/// tests and the work-precision benchmark (ranges of B&K 1995; see bk_jumps_test.cpp), the trace
/// that reaches the back flank, and the Newton vector of a traced point.
#pragma once

#include <algorithm>

#include "geardyn/analyses/nonlinear_hb.hpp"
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

/// Back-side contact: ζ = 0.08, α = 0.15, F_m = 0.1, F_a = 0.16 (B&K's "double-sided impacts":
/// the upper branch of the softening resonance near Ω ≈ 0.5 reaches the back flank).
inline ClearanceOscillatorParameters BkBackContactSet() {
  ClearanceOscillatorParameters p;
  p.zeta = 0.08;
  p.alpha = 0.15;
  p.mean_force = 0.1;
  p.alternating_force = 0.16;
  return p;
}

/// The back-contact set's trace: from Ω = 1.6 (far above resonance: full contact, the contact
/// guess converges) down through the bistable band to Ω = 0.42, where the orbit has four
/// switches per period (front contact → gap → back contact → gap).
inline NhbContinuationOptions BkBackContactTrace() {
  NhbContinuationOptions c;
  c.omega_start = 1.6;
  c.omega_end = 0.42;
  c.max_step = 0.1;
  c.max_tangent_angle = 0.5;
  return c;
}

/// The Newton vector x (layout of nonlinear_hb.hpp, n = 1) of a point's harmonics, truncated or
/// zero-padded to H harmonics (H < 0: the point's own).
inline VectorX PointUnknowns(const NhbPoint& point, int H = -1) {
  const int own = static_cast<int>(point.harmonics.cols()) - 1;
  if (H < 0) H = own;
  VectorX x = VectorX::Zero(2 * H + 1);
  x[0] = point.harmonics(0, 0).real();
  for (int k = 1; k <= std::min(H, own); ++k) {
    x[2 * k - 1] = point.harmonics(0, k).real();
    x[2 * k] = point.harmonics(0, k).imag();
  }
  return x;
}

}  // namespace geardyn::testing
