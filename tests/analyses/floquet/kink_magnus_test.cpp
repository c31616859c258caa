// Kink-aware Magnus (issue 12): a linearly interpolated table stiffness has a kink at every sample,
// and a step that straddles one loses Magnus's nominal order. Steps that end on the kinks
// (PeriodicSecondOrderSystem::kinks_s, MagnusGrid) keep order 6; at the 65 536-step cap (the
// helical pair at 5 rpm) the order is measured by a third run (ObservedOrderOfThree) instead of
// assumed to be 1. Truths: the general GSL rk8pd path on the same system (a different method,
// adaptive steps) at a tight tolerance, and a closed-form power law.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "../../../analyses/src/floquet/floquet_internal.hpp"
#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"

namespace geardyn::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kSamples = 8;  // table samples per period: 8 smooth pieces

// x'' + k(t) x = 0 (m = 1, T = 1 s), k the periodic linear interpolation of 8 samples of
// ω0²(1 + 0.3 cos 2πt + 0.1 sin 4πt), ω0 = 2π·3 rad/s (inside no instability tongue; the
// multipliers are on the unit circle). `with_kinks`: tell Floquet where the samples are.
PeriodicSecondOrderSystem TableSdof(bool with_kinks) {
  const double w0 = 2.0 * kPi * 3.0;
  auto samples = std::make_shared<std::vector<double>>();
  for (int s = 0; s < kSamples; ++s) {
    const double t = static_cast<double>(s) / kSamples;
    samples->push_back(w0 * w0 * (1.0 + 0.3 * std::cos(2 * kPi * t) + 0.1 * std::sin(4 * kPi * t)));
  }
  PeriodicSecondOrderSystem sys;
  sys.mass = MatrixX::Identity(1, 1);
  sys.period_s = 1.0;
  sys.coefficients = [samples](double t, MatrixX* K, MatrixX* C) {
    const double x = (t - std::floor(t)) * kSamples;
    const int i = std::min(static_cast<int>(x), kSamples - 1);
    const double f = x - i;
    K->resize(1, 1);
    (*K)(0, 0) = (1.0 - f) * (*samples)[i] + f * (*samples)[(i + 1) % kSamples];
    C->resize(0, 0);
  };
  if (with_kinks) {
    for (int s = 0; s < kSamples; ++s) sys.kinks_s.push_back(static_cast<double>(s) / kSamples);
  }
  return sys;
}

FloquetResult RunFloquet(const PeriodicSecondOrderSystem& sys, FloquetMethod method, int steps,
                         double tol) {
  FloquetOptions o;
  o.method = method;
  o.magnus_steps = steps;
  o.tolerance = tol;
  return ComputeFloquet(sys, o);
}

// Errors of fixed-step Magnus runs against the ODE reference.
std::vector<double> Errors(bool with_kinks, const std::vector<int>& steps,
                           const FloquetResult& reference) {
  std::vector<double> errors;
  for (const int n : steps) {
    const FloquetResult r = RunFloquet(TableSdof(with_kinks), FloquetMethod::kMagnus, n, 1e-10);
    errors.push_back(MultiplierDistance(r.multipliers, reference.multipliers));
  }
  return errors;
}

TEST(KinkMagnusTest, StepsOnTheKinksRestoreTheOrderOfMagnus6) {
  const FloquetResult ode = RunFloquet(TableSdof(false), FloquetMethod::kOdeStepper, 0, 1e-12);
  ASSERT_NE(ode.verdict, FloquetVerdict::kUndetermined) << ode.summary.message;
  ASSERT_LT(ode.summary.error_estimate, 1e-10);
  // Aligned: 3, 5 and 8 steps per piece (24, 40, 64 in all). Nominal order 6; the errors stay
  // far above the reference's.
  const std::vector<int> n = {24, 40, 64};
  const std::vector<double> aligned = Errors(true, n, ode);
  for (std::size_t k = 0; k + 1 < n.size(); ++k) {
    const double q = std::log(aligned[k] / aligned[k + 1]) / std::log(1.0 * n[k + 1] / n[k]);
    SCOPED_TRACE("errors " + std::to_string(aligned[k]) + " → " + std::to_string(aligned[k + 1]));
    EXPECT_GT(q, 5.0);
    EXPECT_GT(aligned[k + 1], 100.0 * ode.summary.error_estimate);
  }
}

TEST(KinkMagnusTest, AutomaticStepsMeetTheToleranceAgainstTheOdePath) {
  const FloquetResult ode = RunFloquet(TableSdof(false), FloquetMethod::kOdeStepper, 0, 1e-12);
  const FloquetResult magnus = RunFloquet(TableSdof(true), FloquetMethod::kAuto, 0, 1e-10);
  ASSERT_EQ(magnus.method_used, FloquetMethod::kMagnus);
  ASSERT_TRUE(magnus.summary.ok()) << magnus.summary.message;
  EXPECT_LE(MultiplierDistance(magnus.multipliers, ode.multipliers),
            magnus.summary.error_estimate + ode.summary.error_estimate + 1e-12);
  EXPECT_EQ(magnus.verdict, ode.verdict);
  // Whole steps per piece: a multiple of the 8 pieces.
  EXPECT_EQ(magnus.summary.counters.at("steps") % kSamples, 0);
}

// kinks_s outside [0, T) is bad input.
TEST(KinkMagnusTest, KinkOutsideThePeriodIsRejected) {
  PeriodicSecondOrderSystem sys = TableSdof(true);
  sys.kinks_s.push_back(1.5);
  EXPECT_THROW(RunFloquet(sys, FloquetMethod::kMagnus, 0, 1e-8), InvalidInput);
}

// The hand pair with a 16-sample table stiffness (the kinks of a contact-line table, coarser) and
// mesh damping, at 2 Hz of mesh frequency (a few rpm: ‖A‖T in the thousands, ≈ 200 steps per
// smooth piece): kAuto (Magnus on the kink-aligned grid) meets its tolerance and agrees with the
// GSL rk8pd path within the two estimates, with the same verdict.
TEST(KinkMagnusTest, TableCoreAtLowSpeedAgreesWithTheOdePath) {
  const FourierCoefficient smooth = SmoothStiffness(4e8, 0.2, 0.05);
  constexpr int kTableSamples = 16;
  MatrixX samples(3, kTableSamples);
  for (int s = 0; s < kTableSamples; ++s) {
    VectorX v(3);
    Evaluate(smooth, 2.0 * kPi * s / kTableSamples, v);
    samples.col(s) = v;
  }
  const SystemModel model =
      HandPair(LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, TableCoefficient(samples), 0.0125,
                              std::nullopt, MeshDamping::FromCoefficient(900.0)));
  FloquetOptions o;
  o.mesh_frequency_hz = 2.0;
  o.tolerance = 1e-9;
  const FloquetResult magnus = ComputeFloquet(model, o);
  o.method = FloquetMethod::kOdeStepper;
  o.tolerance = 1e-7;
  const FloquetResult ode = ComputeFloquet(model, o);
  ASSERT_EQ(magnus.method_used, FloquetMethod::kMagnus);
  ASSERT_TRUE(magnus.summary.ok()) << magnus.summary.message;
  ASSERT_TRUE(std::isfinite(ode.summary.error_estimate)) << ode.summary.message;
  EXPECT_LE(MultiplierDistance(magnus.multipliers, ode.multipliers),
            magnus.summary.error_estimate + ode.summary.error_estimate + 1e-9);
  EXPECT_NE(magnus.verdict, FloquetVerdict::kUndetermined);
  if (ode.verdict != FloquetVerdict::kUndetermined) {
    EXPECT_EQ(magnus.verdict, ode.verdict);
  }
}

// The order fitted to three runs at unequal ratios (the step cap's first comparison, magnus.cpp)
// recovers q of an exact power law e(N) = C N^−q (closed form), and falls back to 1 on bad data.
TEST(KinkMagnusTest, ObservedOrderOfThreeRecoversAPowerLaw) {
  for (const double q : {1.0, 2.0, 4.0, 5.5, 6.0}) {
    auto e = [q](double n) { return 3.0 * std::pow(n, -q); };
    const long n0 = 32768, n1 = 49152, n2 = 65536;
    EXPECT_NEAR(internal::ObservedOrderOfThree(e(n0) - e(n1), e(n1) - e(n2), n0, n1, n2, 6), q,
                1e-9);
  }
  EXPECT_EQ(internal::ObservedOrderOfThree(0.0, 1e-9, 1, 2, 3, 6), 1.0);
  EXPECT_EQ(internal::ObservedOrderOfThree(1e-9, 1e-9, 3, 2, 4, 6), 1.0);
  // Faster than the nominal order (pre-asymptotic data) is clamped to it.
  EXPECT_EQ(internal::ObservedOrderOfThree(1.0, 1e-12, 8, 12, 16, 6), 6.0);
}

// Every count of FloquetOptions is bounded at its edge, the message naming the field and the cost.
TEST(KinkMagnusTest, OptionCountsAreBoundedWithTheirCost) {
  FloquetOptions o;
  o.mesh_frequency_hz = 100.0;
  std::string why;
  o.magnus_steps = internal::kMaxMagnusSteps;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.magnus_steps = internal::kMaxMagnusSteps + 1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("magnus_steps: must be in [0, 65536]"), std::string::npos) << why;
  EXPECT_NE(why.find("flops"), std::string::npos) << why;
  o.magnus_steps = 0;
  o.num_modes = internal::kMaxBasisModes;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.num_modes = internal::kMaxBasisModes + 1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("num_modes: must be in [0, 1500]"), std::string::npos) << why;
  o.num_modes = 0;
  o.arpack_max_iterations = 100000;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.arpack_max_iterations = 100001;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("arpack_max_iterations: must be in [1, 100000]"), std::string::npos) << why;
}

}  // namespace
}  // namespace geardyn::test
