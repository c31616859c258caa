// The measured-order Magnus step control (FloquetOptions::magnus_measured_order, the stability
// chart's screening run): its estimate of the relative error of Φ must cover the true error, and
// its verdicts must be those of the reference. Truths: the general GSL rk8pd path (kOdeStepper /
// OdeMonodromy, a different method with adaptive steps) at a tight tolerance; the exact step
// product (round-off) for a rectangular-wave stiffness forced through Magnus. "Cheaper" is checked
// as a count of A(t) evaluations against the default step control, not as a time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "../../../analyses/src/floquet/floquet_internal.hpp"
#include "floquet_test_support.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::test {
namespace {

FloquetResult RunFloquet(const SystemModel& model, FloquetMethod method, double mesh_hz, double tol,
                         bool measured) {
  FloquetOptions o;
  o.mesh_frequency_hz = mesh_hz;
  o.method = method;
  o.tolerance = tol;
  o.magnus_measured_order = measured;
  return ComputeFloquet(model, o);
}

// The scaled state system of the model at f_m (what ComputeFloquet builds for kMagnus).
internal::StateSystem StateOf(const SystemModel& model, double mesh_hz) {
  const double omega = 2.0 * std::numbers::pi * mesh_hz;
  auto ws = std::make_shared<SystemWorkspace>(model, StorageKind::kDense);
  PeriodicSecondOrderSystem s;
  s.period_s = 1.0 / mesh_hz;
  s.mass = model.DenseMass();
  s.coefficients = [ws, model, omega](double t, MatrixX* K, MatrixX* C) {
    *K = AssembleStiffness(model, *ws, omega * t);
    *C = AssembleDamping(model, *ws, omega * t);
  };
  return internal::MakeStateSystem(s, true);
}

// The relative error of Φ (what the tolerance bounds) against rk8pd at 1e-11: within the
// measured estimate (plus the reference's own), and below the tolerance up to that reference.
TEST(MeasuredOrderMagnusTest, MonodromyErrorIsWithinTheEstimateAgainstRk8pd) {
  const SystemModel model = HandPair(HandSmoothCore(0.2, 0.05, 900.0));
  for (const double hz : {300.0, 2000.0, 8000.0}) {
    const internal::StateSystem sys = StateOf(model, hz);
    const internal::MonodromyOutcome ode = internal::OdeMonodromy(sys, 1e-11);
    // Its estimate enters the comparison (it may miss 1e-11 by a little: tolerance_not_met).
    ASSERT_TRUE(std::isfinite(ode.truncation_error) && ode.truncation_error < 1e-9) << ode.message;
    for (const double tol : {1e-6, 1e-8}) {
      SCOPED_TRACE("f_m = " + std::to_string(hz) + " Hz, tolerance " + std::to_string(tol));
      const internal::MonodromyOutcome m = internal::MagnusMonodromyMeasured(sys, 6, tol);
      ASSERT_TRUE(m.converged) << m.message;
      EXPECT_LE(m.truncation_error, tol);
      const double error = internal::RelativeDifference(m.phi, ode.phi);
      EXPECT_LE(error, m.truncation_error + ode.truncation_error + 1e-12);
      // The default control on the same system and tolerance: the measured one needs fewer
      // A(t) evaluations (the count the chart's speed comes from).
      const internal::MonodromyOutcome d = internal::MagnusMonodromy(sys, 6, tol);
      EXPECT_LT(m.evaluations, d.evaluations);
    }
  }
}

// Multipliers and verdicts of the model entry, damped (asymptotically stable or unstable) and
// undamped (marginal), against kOdeStepper at 1e-11.
TEST(MeasuredOrderMagnusTest, VerdictsAndMultipliersAgreeWithTheOdePath) {
  for (const double c_m : {0.0, 900.0}) {
    const SystemModel model = HandPair(HandSmoothCore(0.2, 0.05, c_m));
    for (const double hz : {500.0, 3000.0, 9000.0, 15000.0}) {
      SCOPED_TRACE("c_m = " + std::to_string(c_m) + ", f_m = " + std::to_string(hz) + " Hz");
      const FloquetResult m = RunFloquet(model, FloquetMethod::kMagnus, hz, 1e-6, true);
      const FloquetResult ode = RunFloquet(model, FloquetMethod::kOdeStepper, hz, 1e-11, false);
      ASSERT_TRUE(m.summary.ok()) << m.summary.message;
      ASSERT_TRUE(ode.summary.ok()) << ode.summary.message;
      EXPECT_LE(MultiplierDistance(m.multipliers, ode.multipliers),
                m.summary.error_estimate + ode.summary.error_estimate + 1e-12);
      EXPECT_EQ(m.verdict, ode.verdict);
      EXPECT_EQ(m.marginal, ode.marginal);
    }
  }
}

// A stiffness jump inside the steps' reach (rectangular wave forced through Magnus): the measured
// order sees the loss of order; the verdict is the exact product's or undetermined, never the
// opposite one, and a converged result meets its estimate.
TEST(MeasuredOrderMagnusTest, ForcedOnStepsIsRightOrUndeterminedAgainstExactSteps) {
  const SystemModel model = HandPair(HandSpurWaveCore(1200.0));
  for (const double hz : {50.0, 500.0, 5000.0}) {
    SCOPED_TRACE("f_m = " + std::to_string(hz) + " Hz");
    const FloquetResult exact = RunFloquet(model, FloquetMethod::kExactSteps, hz, 1e-10, false);
    ASSERT_NE(exact.verdict, FloquetVerdict::kUndetermined);
    const FloquetResult m = RunFloquet(model, FloquetMethod::kMagnus, hz, 1e-6, true);
    if (m.verdict == FloquetVerdict::kUndetermined) continue;
    EXPECT_EQ(m.verdict, exact.verdict);
    if (m.summary.ok()) {
      EXPECT_LE(std::abs(m.max_abs_multiplier - exact.max_abs_multiplier),
                m.summary.error_estimate + exact.summary.error_estimate + 1e-12);
    }
  }
}

// Stiff Mathieu x'' + (δ + ε cos t)x + c x' = 0, δ = 10⁶ (‖A‖T ≈ 6.3·10³): the measured control
// starts far outside the series' radius and must still agree with the ODE path.
TEST(MeasuredOrderMagnusTest, StiffMathieuAgreesWithTheOdePath) {
  const double T = 2.0 * std::numbers::pi;
  for (const double c : {0.0, 0.5}) {
    SCOPED_TRACE("c = " + std::to_string(c));
    const PeriodicSecondOrderSystem sys = MakeMathieuSystem(1e6, 1e4, T, c);
    FloquetOptions o;
    o.method = FloquetMethod::kMagnus;
    o.tolerance = 1e-9;
    o.magnus_measured_order = true;
    const FloquetResult m = ComputeFloquet(sys, o);
    o.method = FloquetMethod::kOdeStepper;
    o.tolerance = 1e-7;
    const FloquetResult ode = ComputeFloquet(sys, o);
    ASSERT_TRUE(m.summary.ok()) << m.summary.message;
    ASSERT_TRUE(std::isfinite(ode.summary.error_estimate)) << ode.summary.message;
    // Accepted only with the coarser compared run inside the radius: h‖A‖ ≤ π on it.
    EXPECT_GE(m.summary.counters.at("steps"), 2 * 6000 / 4);
    EXPECT_LE(MultiplierDistance(m.multipliers, ode.multipliers),
              m.summary.error_estimate + ode.summary.error_estimate + 1e-9);
    // Liouville: det Φ = e^{−cT}, so |λ1 λ2| = e^{−cT} whatever the verdict.
    EXPECT_NEAR(std::abs(m.multipliers[0] * m.multipliers[1]), std::exp(-c * T), 1e-8);
  }
}

}  // namespace
}  // namespace geardyn::test
