// Every shortcut against the general path (GSL rk8pd on the fundamental matrix) on the same
// system, within the shortcut's stated tolerance (architecture §3.4, spec 02 "Skip what a scene
// doesn't need"): exact steps, Magnus (orders 4 and 6), Hill, modal projection.
#include <gtest/gtest.h>

#include <cmath>

#include "floquet_test_support.hpp"

namespace geardyn::test {
namespace {

constexpr double kMeshHz = 5000.0;

FloquetResult RunMethod(const SystemModel& model, FloquetMethod method, double tol,
                        bool split_blocks = true) {
  FloquetOptions o;
  o.mesh_frequency_hz = kMeshHz;
  o.method = method;
  o.tolerance = tol;
  o.split_blocks = split_blocks;
  FloquetResult r = ComputeFloquet(model, o);
  EXPECT_EQ(r.method_used, method);
  EXPECT_TRUE(r.summary.ok()) << ToString(method) << ": " << r.summary.message;
  return r;
}

TEST(ShortcutsVsOdeTest, ExactStepsEqualTheOdePathOnTheDampedSpurPair) {
  const SystemModel model = HandPair(HandSpurWaveCore(1200.0));
  const FloquetResult ode = RunMethod(model, FloquetMethod::kOdeStepper, 1e-11);
  const FloquetResult exact = RunMethod(model, FloquetMethod::kExactSteps, 1e-11);
  EXPECT_LE(exact.summary.error_estimate, 1e-12);
  EXPECT_LE(MultiplierDistance(exact.multipliers, ode.multipliers),
            exact.summary.error_estimate + ode.summary.error_estimate + 1e-12);
}

TEST(ShortcutsVsOdeTest, MagnusMeetsItsToleranceAgainstTheOdePath) {
  const SystemModel model = HandPair(HandSmoothCore(0.2, 0.05, 900.0));
  const FloquetResult ode = RunMethod(model, FloquetMethod::kOdeStepper, 1e-12);
  for (const int order : {4, 6}) {
    FloquetOptions o;
    o.mesh_frequency_hz = kMeshHz;
    o.method = FloquetMethod::kMagnus;
    o.magnus_order = order;
    o.tolerance = 1e-9;
    const FloquetResult r = ComputeFloquet(model, o);
    ASSERT_TRUE(r.summary.ok()) << r.summary.message;  // Φ within the tolerance
    // The multiplier estimate (conditioning included) is honest and small.
    const double distance = MultiplierDistance(r.multipliers, ode.multipliers);
    EXPECT_LE(distance, r.summary.error_estimate + ode.summary.error_estimate) << order;
    EXPECT_LE(distance, 1e-8) << "order " << order;
  }
}

TEST(ShortcutsVsOdeTest, MagnusConvergesAtItsOrder) {
  // Error against the ODE reference at N and 2N steps: ratio ≈ 2^p.
  const SystemModel model = HandPair(HandSmoothCore(0.3, 0.1));
  const FloquetResult ode = RunMethod(model, FloquetMethod::kOdeStepper, 1e-13);
  for (const int order : {4, 6}) {
    double previous = 0.0;
    for (const int steps : {8, 16}) {
      FloquetOptions o;
      o.mesh_frequency_hz = kMeshHz;
      o.method = FloquetMethod::kMagnus;
      o.magnus_order = order;
      o.magnus_steps = steps;
      const double err = MultiplierDistance(ComputeFloquet(model, o).multipliers, ode.multipliers);
      if (previous > 0.0) {
        EXPECT_GT(previous / err, std::pow(2.0, order) * 0.6) << "order " << order;
      }
      previous = err;
    }
  }
}

TEST(ShortcutsVsOdeTest, HillMeetsItsToleranceAgainstTheOdePath) {
  const SystemModel model = HandPair(HandSmoothCore(0.2, 0.05, 900.0));
  const FloquetResult ode = RunMethod(model, FloquetMethod::kOdeStepper, 1e-12);
  FloquetOptions o;
  o.mesh_frequency_hz = kMeshHz;
  o.method = FloquetMethod::kHill;
  o.hill_harmonics = 6;    // fixed H (the adaptive run is slow in Debug builds)
  o.split_blocks = false;  // one Hill matrix (the counter would sum over blocks)
  const FloquetResult hill = ComputeFloquet(model, o);
  EXPECT_EQ(hill.summary.counters.at("harmonics"), 6);
  const double distance = MultiplierDistance(hill.multipliers, ode.multipliers);
  EXPECT_LE(distance, 1e-6);
  // The H vs 2H/3 estimate bounds the error of H (it estimates the coarser run's error).
  EXPECT_LE(distance, hill.summary.error_estimate + 1e-12);
}

TEST(ShortcutsVsOdeTest, ModalProjectionMeetsItsEstimateOnGearedShafts) {
  // 60 DOFs; the full exact-steps result is the reference for the retained multipliers.
  const SystemModel model = GearedShafts(4, HandSpurWaveCore(600.0));
  ASSERT_EQ(model.num_dofs(), 60);
  // (Exact steps = the ODE path is shown on the 12-DOF pair above; the 120-state ODE run is too
  // slow for a unit test.)
  const FloquetResult full = RunMethod(model, FloquetMethod::kExactSteps, 1e-10, false);
  FloquetOptions o;
  o.mesh_frequency_hz = kMeshHz;
  o.method = FloquetMethod::kModalProjection;
  o.split_blocks = false;
  o.tolerance = 1e-6;
  const FloquetResult r = ComputeFloquet(model, o);
  EXPECT_EQ(r.method_used, FloquetMethod::kModalProjection);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_LE(r.summary.error_estimate, 1e-6);
  // Each multiplier of the reduced model is near one of the full model's.
  VectorXc nearest(r.multipliers.size());
  for (int i = 0; i < r.multipliers.size(); ++i) {
    int best = 0;
    for (int j = 1; j < full.multipliers.size(); ++j) {
      if (std::abs(full.multipliers[j] - r.multipliers[i]) <
          std::abs(full.multipliers[best] - r.multipliers[i])) {
        best = j;
      }
    }
    nearest[i] = full.multipliers[best];
  }
  EXPECT_LE((nearest - r.multipliers).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_NEAR(r.max_abs_multiplier, full.max_abs_multiplier, 1e-6);
}

}  // namespace
}  // namespace geardyn::test
