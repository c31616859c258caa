/// @file
/// @brief Sub-harmonic (period-2) responses on request (NhbOptions::period_multiple = 2): the
/// B&K oscillator x'' + 2ζx' + (1 + α cos Ωt) g(x) = F_m with pure parametric excitation at the
/// principal parametric resonance Ω ≈ 2 (ω_n = 1), where the period-1 orbit is unstable and the
/// response settles on a period-2 orbit with contact loss. Truth: a long GSL rk8pd time
/// integration (bk_time_integration.hpp) from a perturbed start.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "analyses/nonlinear_hb/bk_time_integration.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

TEST(NonlinearHbPeriodTwo, ParametricResonanceOrbitMatchesTimeIntegration) {
  ClearanceOscillatorParameters p;
  p.zeta = 0.03;
  p.alpha = 0.3;
  p.mean_force = 0.1;
  p.alternating_force = 0.0;
  const double omega = 2.0;
  const NhbProblem problem = MakeClearanceOscillator(p);

  // Period 1: the quasi-static orbit exists but is parametrically unstable here.
  NhbOptions one;
  one.harmonics = 16;
  const NhbSolveResult r1 = SolveNonlinearHarmonicBalance(problem, omega, one);
  ASSERT_TRUE(r1.summary.ok()) << r1.summary.BriefReport();
  EXPECT_EQ(r1.point.stable, FloquetVerdict::kUnstable) << "max |μ| = " << r1.point.max_multiplier;

  // Time integration from a perturbed static state: 1500 excitation periods to settle.
  const testing::BkParameters bk{p.zeta, p.alpha, p.mean_force, 0.0, 0.0, true};
  testing::BkState state{1.0 + p.mean_force + 0.05, 0.0, 0.0};
  testing::BkStats ti;
  testing::BkIntegrate(bk, omega, 1500, 20, state, &ti);
  ASSERT_GT(ti.rms, 0.05) << "the time integration did not leave the period-1 orbit";

  // Period 2 from the contact guess plus a sub-harmonic seed (the period-1 subspace is invariant
  // under Newton, so a seed with an odd harmonic of Ω/2 is required).
  NhbOptions two;
  two.harmonics = 32;
  two.period_multiple = 2;
  NhbSolver solver(problem, two, two.harmonics);
  VectorX x = solver.ContactGuess(omega);
  x[1] = ti.rms;  // Re U_1 of base Ω/2
  Status status;
  double residual = 0.0;
  solver.Newton(x, omega, &status, &residual);
  ASSERT_EQ(status, Status::kSuccess) << "residual " << residual;
  NhbPoint pt;
  solver.Describe(x, omega, pt);
  pt.max_multiplier = solver.MaxMultiplier(x, omega);
  EXPECT_LT(pt.max_multiplier, 1.0) << "the period-2 orbit should be stable";
  // A genuine period-2 orbit: the first harmonic of Ω/2 carries a large part of the motion.
  EXPECT_GT(2.0 * std::abs(pt.harmonics(0, 1)), 0.3 * pt.rms[0]);
  EXPECT_NEAR(pt.rms[0], ti.rms, 0.01 * ti.rms);
  EXPECT_NEAR(pt.maximum[0], ti.maximum, 0.01 * std::abs(ti.maximum));
  EXPECT_NEAR(pt.minimum[0], ti.minimum, 0.01 * std::abs(ti.maximum - ti.minimum));
  EXPECT_LT(pt.minimum[0], 1.0);  // contact loss (g = 0 for |x| ≤ 1)
}

}  // namespace
}  // namespace geardyn
