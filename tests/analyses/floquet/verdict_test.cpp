// Floquet verdicts (issue 12): three-valued, NaN never read as a number, undamped → marginal.
// Truths: the verdict rules of floquet.hpp (FloquetVerdict) applied to constructed summaries; a
// NaN injected into the coefficients of a closed-form system (every method must answer
// "undetermined", never a verdict from a default Φ); the closed-form Meissner multipliers
// (det Φ = 1 undamped: |λ| = 1 in the stable region → marginal; Liouville det Φ = e^{−cT} damped:
// |λ| = e^{−cT/2} < 1 on the unit-circle pair → not marginal).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "../../../analyses/src/floquet/floquet_internal.hpp"
#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"

namespace geardyn::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

VectorXc Values(std::initializer_list<std::complex<double>> v) {
  VectorXc out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (const auto& x : v) out[i++] = x;
  return out;
}

Summary MakeSummary(Status status, double error) {
  Summary s;
  s.status = status;
  s.error_estimate = error;
  return s;
}

FloquetVerdict Decide(Status status, double error, const VectorXc& l, const VectorXc& mu) {
  return internal::DecideVerdict(MakeSummary(status, error), l, mu, nullptr);
}

TEST(FloquetVerdictTest, RulesOfTheThreeValuedVerdict) {
  const VectorXc inside = Values({0.9, 0.5});
  const VectorXc mu = Values({-0.1, -0.7});
  const VectorXc outside = Values({1.2, 0.5});
  const VectorXc mu_out = Values({0.18, -0.7});
  // Success, finite, inside → stable; outside beyond e → unstable.
  EXPECT_EQ(Decide(Status::kSuccess, 1e-12, inside, mu), FloquetVerdict::kStable);
  EXPECT_EQ(Decide(Status::kSuccess, 1e-12, outside, mu_out), FloquetVerdict::kUnstable);
  // A NaN estimate is undetermined, whatever the multipliers say (std::max would have dropped it).
  EXPECT_EQ(Decide(Status::kSuccess, kNaN, inside, mu), FloquetVerdict::kUndetermined);
  EXPECT_EQ(Decide(Status::kSuccess, kNaN, outside, mu_out), FloquetVerdict::kUndetermined);
  // An infinite estimate: the issue's "max|λ| = inf, stable" case.
  EXPECT_EQ(Decide(Status::kToleranceNotMet, kInf, Values({kInf, 0.5}), Values({kInf, 0.0})),
            FloquetVerdict::kUndetermined);
  EXPECT_EQ(Decide(Status::kSuccess, kInf, inside, mu), FloquetVerdict::kUndetermined);
  // A NaN multiplier.
  EXPECT_EQ(Decide(Status::kSuccess, 1e-12, Values({kNaN, 0.5}), Values({kNaN, 0.0})),
            FloquetVerdict::kUndetermined);
  // |λ| overflowing double with a finite positive exponent is a growth, not a failure.
  EXPECT_EQ(Decide(Status::kSuccess, 1e-3, Values({kInf, 0.5}), Values({3.0, -0.7})),
            FloquetVerdict::kUnstable);
  // ... but an infinite |λ| whose exponent is not finite is a failure.
  EXPECT_EQ(Decide(Status::kSuccess, 1e-3, Values({kInf, 0.5}), Values({kInf, -0.7})),
            FloquetVerdict::kUndetermined);
  // Tolerance missed: unstable beyond the estimate stays unstable, anything else is unknown.
  EXPECT_EQ(Decide(Status::kToleranceNotMet, 1e-3, outside, mu_out), FloquetVerdict::kUnstable);
  EXPECT_EQ(Decide(Status::kToleranceNotMet, 1e-3, inside, mu), FloquetVerdict::kUndetermined);
  EXPECT_EQ(Decide(Status::kToleranceNotMet, 0.3, outside, mu_out), FloquetVerdict::kUndetermined);
  // Failed runs are never a verdict.
  EXPECT_EQ(Decide(Status::kNumericalIssue, 1e-12, outside, mu_out), FloquetVerdict::kUndetermined);
  EXPECT_EQ(Decide(Status::kNotConverged, 1e-12, inside, mu), FloquetVerdict::kUndetermined);
  // Within the estimate of 1 with success: stable (an undamped system's |λ| = 1 ± round-off).
  EXPECT_EQ(Decide(Status::kSuccess, 1e-9, Values({1.0 + 1e-10, 0.5}), mu),
            FloquetVerdict::kStable);
  // A growth below the 1e-12 floor is round-off even with a smaller estimate (the exact-steps
  // product of an undamped pair: 1 + 1.2e-13 ± 7.7e-14); above the floor and the estimate it is
  // a growth.
  EXPECT_EQ(Decide(Status::kSuccess, 7.7e-14, Values({1.0 + 1.2e-13, 0.5}), mu),
            FloquetVerdict::kStable);
  EXPECT_EQ(Decide(Status::kSuccess, 7.7e-14, Values({1.0 + 5e-12, 0.5}), mu),
            FloquetVerdict::kUnstable);
}

TEST(FloquetVerdictTest, NanPropagatesThroughMaxima) {
  EXPECT_TRUE(std::isnan(internal::MaxPropagatingNaN(1.0, kNaN)));
  EXPECT_TRUE(std::isnan(internal::MaxPropagatingNaN(kNaN, 1.0)));
  EXPECT_EQ(internal::MaxPropagatingNaN(1.0, 2.0), 2.0);
  EXPECT_TRUE(std::isnan(internal::MaxAbsOf(Values({2.0, kNaN, 0.5}))));
  EXPECT_EQ(internal::MaxAbsOf(Values({{0.0, 2.0}, 0.5})), 2.0);
}

TEST(FloquetVerdictTest, BlocksCombine) {
  using V = FloquetVerdict;
  EXPECT_EQ(internal::CombineVerdicts(V::kStable, V::kStable), V::kStable);
  EXPECT_EQ(internal::CombineVerdicts(V::kStable, V::kUndetermined), V::kUndetermined);
  EXPECT_EQ(internal::CombineVerdicts(V::kUndetermined, V::kUnstable), V::kUnstable);
  EXPECT_EQ(internal::CombineVerdicts(V::kUnstable, V::kStable), V::kUnstable);
}

// A NaN in the coefficients is bad input (named), never a multiplier.
TEST(FloquetVerdictTest, NanCoefficientsAreRejected) {
  const double T = 3.0;
  PeriodicSecondOrderSystem smooth;
  smooth.mass = MatrixX::Identity(1, 1);
  smooth.period_s = T;
  smooth.coefficients = [T](double t, MatrixX* K, MatrixX* C) {
    *K = MatrixX::Constant(1, 1, t > 0.6 * T ? kNaN : 1.3);
    *C = MatrixX::Zero(1, 1);
  };
  for (const FloquetMethod m : {FloquetMethod::kMagnus, FloquetMethod::kOdeStepper}) {
    FloquetOptions o;
    o.method = m;
    EXPECT_THROW(ComputeFloquet(smooth, o), InvalidInput) << ToString(m);
  }
  PeriodicSecondOrderSystem steps = MakeMeissnerSystem(1.3, 0.7, 0.5, T);
  steps.steps[1].stiffness(0, 0) = kNaN;
  EXPECT_THROW(ComputeFloquet(steps, {}), InvalidInput);
}

// NaN injected into the error estimate of a finished result (the path every method ends in):
// the verdict is undetermined, the maximum keeps the NaN, and the reason is given.
TEST(FloquetVerdictTest, NanEstimateInFinishResultIsUndetermined) {
  FloquetResult r;
  r.period_s = 1.0;
  r.multipliers = Values({0.5, 0.25});
  r.exponents = Values({std::log(0.5), std::log(0.25)});
  r.summary.error_estimate = kNaN;
  internal::FinishResult(1, 1e-10, &r);
  EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined);
  EXPECT_FALSE(r.stable());
  EXPECT_EQ(r.multipliers.size(), 4);  // + the rigid pair
  ASSERT_FALSE(r.summary.warnings.empty());
  EXPECT_NE(r.summary.warnings.back().find("undetermined"), std::string::npos);
  r.multipliers = Values({0.5, kNaN});
  r.exponents = Values({std::log(0.5), kNaN});
  r.summary.error_estimate = 1e-12;
  internal::FinishResult(0, 1e-10, &r);
  EXPECT_TRUE(std::isnan(r.max_abs_multiplier));  // std::max would have returned 0.5
  EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined);
}

// x'' + k(t) x = 0 with k ≈ 1e200 over T = 1: ‖A‖T ≈ 1e100, far beyond the Magnus step cap.
// Magnus (and ARPACK's Magnus propagators) must not try a coarse count and call it converged:
// nothing is computed and the verdict is undetermined (before issue 12: 8 steps, inf → stable).
TEST(FloquetVerdictTest, TooStiffForTheStepCapIsUndetermined) {
  PeriodicSecondOrderSystem stiff;
  stiff.mass = MatrixX::Identity(2, 2);
  stiff.period_s = 1.0;
  stiff.coefficients = [](double t, MatrixX* K, MatrixX* C) {
    *K = MatrixX::Identity(2, 2) * 1e200 * (1.0 + 0.1 * std::cos(2 * std::numbers::pi * t));
    (*K)(1, 1) = 1.0;
    *C = MatrixX::Zero(2, 2);
  };
  for (const FloquetMethod m : {FloquetMethod::kMagnus, FloquetMethod::kArpackMonodromy}) {
    FloquetOptions o;
    o.method = m;
    o.arpack_nev = 1;
    o.split_blocks = false;
    const FloquetResult r = ComputeFloquet(stiff, o);
    EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined) << ToString(m);
    EXPECT_FALSE(r.summary.ok()) << ToString(m);
    EXPECT_NE(r.summary.message.find("steps"), std::string::npos) << r.summary.message;
  }
}

TEST(FloquetVerdictTest, UndampedStableIsMarginalDampedIsNot) {
  // Meissner k = 1.9 / 0.7, duty 0.6, T = 3.1: |tr Φ| < 2 (closed form) → stable.
  const double T = 3.1;
  const double tr = MeissnerTrace(1.9, 0.7, 0.6 * T, 0.4 * T);
  ASSERT_LT(std::abs(tr), 2.0);
  const FloquetResult undamped = ComputeFloquet(MakeMeissnerSystem(1.9, 0.7, 0.6, T), {});
  EXPECT_EQ(undamped.verdict, FloquetVerdict::kStable);
  EXPECT_TRUE(undamped.marginal);
  // c = 0.05: det Φ = e^{−cT} (Liouville), a complex pair has |λ| = e^{−cT/2}.
  const double c = 0.05;
  const FloquetResult damped = ComputeFloquet(MakeMeissnerSystem(1.9, 0.7, 0.6, T, c), {});
  EXPECT_EQ(damped.verdict, FloquetVerdict::kStable);
  EXPECT_FALSE(damped.marginal);
  EXPECT_NEAR(damped.max_abs_multiplier, std::exp(-0.5 * c * T), 1e-12);
}

// What the reports print next to a verdict (hb text "unstable (parametric, max|λ| = …)", its
// warnings): the helical pair at 2689.68 Hz has max|λ| = 1.00035 and printed "max|λ| = 1" beside
// "unstable". Truth: the printed text read back equals the value to its printed digits and, for
// any growth, reads above 1.
TEST(FloquetVerdictTest, PrintedMaxAbsMultiplierReadsBackAboveOneForEveryGrowth) {
  for (const double m :
       {1.0 + 6.4e-12, 1.0 + 3.5e-4, 1.0 + 4.9e-4, 1.0 - 2e-6, 1.0, 1.069, 0.934}) {
    SCOPED_TRACE(m);
    const std::string text = FormatMaxAbsMultiplier(m);
    double read = 0.0;
    if (text.rfind("1 + ", 0) == 0) {
      read = 1.0 + std::stod(text.substr(4));
    } else if (text.rfind("1 − ", 0) == 0) {
      read = 1.0 - std::stod(text.substr(std::string("1 − ").size()));
    } else {
      read = std::stod(text);
    }
    EXPECT_NEAR(read - 1.0, m - 1.0, 0.01 * std::abs(m - 1.0) + 1e-4 * (std::abs(m - 1.0) >= 5e-4))
        << text;
    EXPECT_EQ(read > 1.0, m > 1.0) << text;
    EXPECT_EQ(read < 1.0, m < 1.0) << text;
  }
  EXPECT_EQ(FormatMaxAbsMultiplier(kNaN), "nan");
  EXPECT_EQ(FormatMaxAbsMultiplier(kInf), "inf");
}

}  // namespace
}  // namespace geardyn::test
