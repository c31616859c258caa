// PreparedFloquet (the stability chart's per-row fast path): its result must be ComputeFloquet's
// on the same model — the ordinary path, which rebuilds the state system and assembles A(t) from
// the model at every Magnus node — at every frequency and tolerance, and it must fall back to
// that path where its Fourier series of A(θ) is not exact. Truths: ComputeFloquet(model) itself
// (a different assembly of the same operator; at a 100× tighter tolerance where the prepared run
// uses the analytic series' known Magnus order) and, for the series, the closed form of the hand
// core's stiffness k(1 + a cos θ + c sin 2θ): two harmonics.
#include "geardyn/analyses/prepared_floquet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "floquet_test_support.hpp"

namespace geardyn::test {
namespace {

FloquetOptions Options(double mesh_hz, double tolerance) {
  FloquetOptions o;
  o.mesh_frequency_hz = mesh_hz;
  o.tolerance = tolerance;
  o.magnus_measured_order = true;  // the chart's screening run
  o.list_undamped_modes = false;
  return o;
}

// Same Magnus runs (step counts, A(t) evaluations), same verdict, and the multipliers within
// round-off of the ordinary path's.
void ExpectSameResult(const FloquetResult& fast, const FloquetResult& ordinary,
                      const std::string& where) {
  EXPECT_EQ(fast.method_used, ordinary.method_used) << where;
  EXPECT_EQ(fast.verdict, ordinary.verdict) << where;
  EXPECT_EQ(fast.marginal, ordinary.marginal) << where;
  EXPECT_EQ(fast.summary.status, ordinary.summary.status) << where;
  EXPECT_EQ(fast.summary.counters.at("steps"), ordinary.summary.counters.at("steps")) << where;
  EXPECT_EQ(fast.summary.counters.at("evaluations"), ordinary.summary.counters.at("evaluations"))
      << where;
  EXPECT_EQ(fast.period_s, ordinary.period_s) << where;
  ASSERT_EQ(fast.multipliers.size(), ordinary.multipliers.size()) << where;
  EXPECT_LE(MultiplierDistance(fast.multipliers, ordinary.multipliers), 1e-11) << where;
  EXPECT_NEAR(fast.max_abs_multiplier, ordinary.max_abs_multiplier, 1e-12) << where;
  // The estimate's round-off part κ_i·δ is itself round-off sensitive where multipliers are
  // nearly double (the hand pair's mirror-symmetric decoupled blocks: eigenvector condition
  // numbers of a near-degenerate pair), so it agrees only to a factor, not to round-off.
  EXPECT_LE(fast.summary.error_estimate, 3.0 * ordinary.summary.error_estimate) << where;
  EXPECT_GE(fast.summary.error_estimate, ordinary.summary.error_estimate / 3.0) << where;
}

// The measured-order screening run on a prepared row takes the known order of the analytic A(θ)
// (magnus.cpp MagnusMonodromyAnalytic), so its step counts are its own: the truth is then
// ComputeFloquet on the ordinary path at a 100× tighter tolerance (model assembly per node and
// the order measured from three runs): the same verdict, and the multipliers within the fast
// run's estimate plus the reference's (the estimate bounds the true error).
void ExpectWithinEstimate(const FloquetResult& fast, const FloquetResult& reference,
                          const std::string& where) {
  EXPECT_EQ(fast.method_used, reference.method_used) << where;
  EXPECT_EQ(fast.verdict, reference.verdict) << where;
  EXPECT_EQ(fast.marginal, reference.marginal) << where;
  EXPECT_EQ(fast.summary.status, reference.summary.status) << where;
  EXPECT_EQ(fast.period_s, reference.period_s) << where;
  ASSERT_EQ(fast.multipliers.size(), reference.multipliers.size()) << where;
  const double bound = fast.summary.error_estimate + reference.summary.error_estimate;
  EXPECT_LE(MultiplierDistance(fast.multipliers, reference.multipliers), bound) << where;
  EXPECT_LE(std::abs(fast.max_abs_multiplier - reference.max_abs_multiplier), bound) << where;
}

TEST(PreparedFloquetTest, SmoothHandPairMatchesComputeFloquetWithinTheEstimate) {
  // Damped and undamped (marginal) hand pairs; frequencies across the principal resonances.
  for (const double c_m : {0.0, 900.0}) {
    const auto model =
        std::make_shared<const SystemModel>(HandPair(HandSmoothCore(0.2, 0.05, c_m)));
    const PreparedFloquet prepared(model, Options(0.0, 1e-6));
    ASSERT_TRUE(prepared.prepared()) << "fit error " << prepared.fit_error();
    // K = k(1 + a cos θ + c sin 2θ): harmonics 1 and 2 of the mesh phase, nothing above when
    // undamped; the mesh damping C2 = (c_m/K)·K2 (B–S Eq. 39) adds a geometrically decaying
    // series, kept to 1e-13 (and checked at the midpoints).
    if (c_m == 0.0) {
      EXPECT_EQ(prepared.harmonics(), 2);
    } else {
      EXPECT_GE(prepared.harmonics(), 2);
    }
    EXPECT_LE(prepared.fit_error(), kPreparedFitTolerance);
    for (const double hz : {150.0, 700.0, 2500.0, 9000.0}) {
      for (const double tol : {1e-6, 1e-10}) {
        const FloquetOptions o = Options(hz, tol);
        const std::string where = "c_m " + std::to_string(c_m) + ", " + std::to_string(hz) +
                                  " Hz, tol " + std::to_string(tol);
        FloquetOptions tight = o;
        tight.tolerance = 1e-2 * tol;
        ExpectWithinEstimate(prepared.Compute(o), ComputeFloquet(*model, tight), where);
      }
    }
  }
}

TEST(PreparedFloquetTest, DefaultStepControlAndFixedStepsToo) {
  const auto model = std::make_shared<const SystemModel>(HandPair(HandSmoothCore(0.3, 0.1, 500.0)));
  const PreparedFloquet prepared(model, Options(0.0, 1e-8));
  ASSERT_TRUE(prepared.prepared());
  FloquetOptions o = Options(1200.0, 1e-8);
  o.magnus_measured_order = false;
  ExpectSameResult(prepared.Compute(o), ComputeFloquet(*model, o), "default control");
  o.magnus_steps = 64;
  o.magnus_order = 4;
  ExpectSameResult(prepared.Compute(o), ComputeFloquet(*model, o), "64 steps, order 4");
}

TEST(PreparedFloquetTest, PiecewiseConstantStiffnessFallsBackToTheOrdinaryPath) {
  // A rectangular wave is not a trigonometric polynomial, and kAuto runs exact steps on it: not
  // prepared, and Compute is ComputeFloquet exactly.
  const auto model = std::make_shared<const SystemModel>(HandPair(HandSpurWaveCore(900.0)));
  const PreparedFloquet prepared(model, Options(0.0, 1e-6));
  EXPECT_FALSE(prepared.prepared());
  EXPECT_EQ(prepared.harmonics(), -1);
  const FloquetOptions o = Options(1500.0, 1e-6);
  const FloquetResult fast = prepared.Compute(o), ordinary = ComputeFloquet(*model, o);
  EXPECT_EQ(fast.method_used, FloquetMethod::kExactSteps);
  EXPECT_EQ(fast.max_abs_multiplier, ordinary.max_abs_multiplier);
  EXPECT_EQ(fast.verdict, ordinary.verdict);
}

TEST(PreparedFloquetTest, ForcedMagnusOnAJumpingStiffnessFailsTheFitCheck) {
  // Magnus forced on the rectangular wave: the 64-sample series cannot reproduce the jumps at the
  // check points, so the ordinary path runs (the kinks and the step structure stay its own).
  const auto model = std::make_shared<const SystemModel>(HandPair(HandSpurWaveCore(900.0)));
  FloquetOptions o = Options(0.0, 1e-6);
  o.method = FloquetMethod::kMagnus;
  const PreparedFloquet prepared(model, o);
  EXPECT_FALSE(prepared.prepared());
  o.mesh_frequency_hz = 1500.0;
  const FloquetResult fast = prepared.Compute(o), ordinary = ComputeFloquet(*model, o);
  EXPECT_EQ(fast.max_abs_multiplier, ordinary.max_abs_multiplier);
}

TEST(PreparedFloquetTest, OtherOptionsThanPreparedUseTheOrdinaryPath) {
  const auto model =
      std::make_shared<const SystemModel>(HandPair(HandSmoothCore(0.2, 0.05, 900.0)));
  const PreparedFloquet prepared(model, Options(0.0, 1e-6));
  ASSERT_TRUE(prepared.prepared());
  FloquetOptions o = Options(2500.0, 1e-8);
  o.method = FloquetMethod::kOdeStepper;
  const FloquetResult fast = prepared.Compute(o), ordinary = ComputeFloquet(*model, o);
  EXPECT_EQ(fast.method_used, FloquetMethod::kOdeStepper);
  EXPECT_EQ(fast.max_abs_multiplier, ordinary.max_abs_multiplier);
}

TEST(PreparedFloquetTest, TheWholeModelWithoutTheBlockSplitToo) {
  // The hand pair falls into 7 decoupled DOF blocks (the tests above: the mesh block prepared,
  // the others by ComputeFloquet's own path); without the split the whole model is one prepared
  // system (the README chart's helical pair is one block).
  const auto model =
      std::make_shared<const SystemModel>(HandPair(HandSmoothCore(0.2, 0.05, 900.0)));
  ASSERT_GT(model->num_blocks(), 1);
  FloquetOptions o = Options(0.0, 1e-6);
  o.split_blocks = false;
  const PreparedFloquet prepared(model, o);
  EXPECT_TRUE(prepared.prepared());
  o.mesh_frequency_hz = 2500.0;
  FloquetOptions tight = o;
  tight.tolerance = 1e-8;
  const FloquetResult fast = prepared.Compute(o), reference = ComputeFloquet(*model, tight);
  EXPECT_EQ(fast.summary.counters.count("blocks"), 0u);
  ExpectWithinEstimate(fast, reference, "whole model");
}

TEST(PreparedFloquetTest, InvalidOptionsThrowAsComputeFloquet) {
  const auto model = std::make_shared<const SystemModel>(HandPair(HandSmoothCore()));
  const PreparedFloquet prepared(model, Options(0.0, 1e-6));
  EXPECT_THROW(prepared.Compute(Options(0.0, 1e-6)), InvalidInput);    // f_m = 0
  EXPECT_THROW(prepared.Compute(Options(100.0, -1.0)), InvalidInput);  // tolerance < 0
}

}  // namespace
}  // namespace geardyn::test
