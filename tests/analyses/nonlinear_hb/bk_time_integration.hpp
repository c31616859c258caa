/// @file
/// @brief Independent truth for the nonlinear HB tests: GSL odeiv2 (rk8pd, tight tolerances)
/// time integration of the Blankenship & Kahraman (1995) oscillator
/// x'' + 2ζ x' + (1 + α cos Ωt) g(x) = F_m + F_a cos(Ωt + φ), slow frequency sweeps with the
/// state carried from one frequency to the next, and steady-state statistics of the last cycles.
#pragma once

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace geardyn::testing {

struct BkParameters {
  double zeta, alpha, mean_force, alternating_force, phase;
  bool back_contact;
};

struct BkState {
  double x = 0.0, v = 0.0, t = 0.0;
};

struct BkStats {
  double omega = 0, rms = 0, maximum = 0, minimum = 0, mean = 0;
};

inline double BkClearance(double x, bool back) {
  if (x > 1.0) return x - 1.0;
  if (back && x < -1.0) return x + 1.0;
  return 0.0;
}

struct BkOde {
  BkParameters p;
  double omega;
};

inline int BkRhs(double t, const double y[], double f[], void* params) {
  const BkOde& o = *static_cast<const BkOde*>(params);
  f[0] = y[1];
  f[1] = o.p.mean_force + o.p.alternating_force * std::cos(o.omega * t + o.p.phase) -
         2.0 * o.p.zeta * y[1] -
         (1.0 + o.p.alpha * std::cos(o.omega * t)) * BkClearance(y[0], o.p.back_contact);
  return GSL_SUCCESS;
}

/// Integrates `periods` excitation periods from `state` (continued in time so the excitation
/// phase stays continuous); when `stats` is given, the last `record` periods are sampled at
/// 256 points per period for RMS about the mean, max and min.
inline void BkIntegrate(const BkParameters& p, double omega, int periods, int record,
                        BkState& state, BkStats* stats) {
  BkOde ode{p, omega};
  gsl_odeiv2_system sys{BkRhs, nullptr, 2, &ode};
  gsl_odeiv2_driver* d =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-3, 1e-11, 1e-11);
  // Restart the excitation time at a multiple of the period: phase continuity for this Ω.
  const double T = 2.0 * std::numbers::pi / omega;
  double t = 0.0;
  double y[2] = {state.x, state.v};
  const int per = 256;
  std::vector<double> samples;
  for (int c = 0; c < periods; ++c) {
    for (int j = 1; j <= per; ++j) {
      gsl_odeiv2_driver_apply(d, &t, (c + double(j) / per) * T, y);
      if (c >= periods - record) samples.push_back(y[0]);
    }
  }
  gsl_odeiv2_driver_free(d);
  state = {y[0], y[1], 0.0};
  if (stats) {
    double mean = 0.0;
    for (double s : samples) mean += s;
    mean /= static_cast<double>(samples.size());
    double var = 0.0;
    for (double s : samples) var += (s - mean) * (s - mean);
    stats->omega = omega;
    stats->mean = mean;
    stats->rms = std::sqrt(var / static_cast<double>(samples.size()));
    stats->maximum = *std::max_element(samples.begin(), samples.end());
    stats->minimum = *std::min_element(samples.begin(), samples.end());
  }
}

/// A slow sweep over `omegas` (in the given order): `settle` periods per frequency, statistics
/// of the last `record` periods; the final state is stored in `final_state` when given.
inline std::vector<BkStats> BkSweep(const BkParameters& p, const std::vector<double>& omegas,
                                    BkState state, int settle, int record,
                                    BkState* final_state = nullptr) {
  std::vector<BkStats> out;
  for (double w : omegas) {
    BkStats s;
    BkIntegrate(p, w, settle, record, state, &s);
    out.push_back(s);
  }
  if (final_state) *final_state = state;
  return out;
}

}  // namespace geardyn::testing
