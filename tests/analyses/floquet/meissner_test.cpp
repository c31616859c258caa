// The Meissner equation x'' + k(t) x = 0 with a rectangular-wave k (k_hi for duty·T, k_lo for the
// rest): the exact-steps multipliers against the closed form (the trace of the product of the two
// exact transfer matrices, cos/cosh products; Richards, Analysis of Periodically Time-Varying
// Systems, 1983, §4.3), the instability tongues near ω_m = 2ω_0/k (k = 1, 2, 3) and the other
// methods against the same closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn::test {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(MeissnerTest, ExactStepsEqualTheClosedFormTo1e12) {
  int checked = 0;
  for (const double duty : {0.3, 0.6}) {
    for (const double k_lo : {0.5, 0.9, -0.2}) {
      for (double T = 0.4; T < 12.0; T += 0.37) {
        const double tr = MeissnerTrace(1.3, k_lo, duty * T, (1 - duty) * T);
        // Near |tr| = 2 the roots are double and only √ε-conditioned: skip a thin band.
        if (std::abs(0.25 * tr * tr - 1.0) < 1e-4) continue;
        const FloquetResult r = ComputeFloquet(MakeMeissnerSystem(1.3, k_lo, duty, T), {});
        ASSERT_TRUE(r.summary.ok()) << r.summary.message;
        EXPECT_EQ(r.method_used, FloquetMethod::kExactSteps);
        EXPECT_LE(MultiplierDistance(r.multipliers, MeissnerMultipliers(tr)), 1e-12)
            << "duty " << duty << " k_lo " << k_lo << " T " << T;
        EXPECT_EQ(r.stable(), std::abs(tr) <= 2.0) << "T " << T;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 150);
}

TEST(MeissnerTest, DampedMultipliersMatchTheClosedFormAndLiouville) {
  // x'' + c x' + k x = 0: with x = e^{−ct/2} y, y'' + (k − c²/4) y = 0, so Φ = e^{−cT/2} Φ_y.
  const double c = 0.15, T = 3.3, duty = 0.6;
  const FloquetResult r = ComputeFloquet(MakeMeissnerSystem(1.2, 0.7, duty, T, c), {});
  const double tr = MeissnerTrace(1.2 - c * c / 4, 0.7 - c * c / 4, duty * T, (1 - duty) * T);
  EXPECT_LE(MultiplierDistance(r.multipliers, std::exp(-c * T / 2) * MeissnerMultipliers(tr)),
            1e-12);
  EXPECT_NEAR(std::abs(r.multipliers.prod()), std::exp(-c * T), 1e-13);
}

TEST(MeissnerTest, TonguesLieNearTwiceTheNaturalFrequencyOverK) {
  // Small variation ±ε about k0 = 1 (duty 0.6, so every harmonic of the wave is present): the
  // k-th tongue is at ω_m ≈ 2ω_0/k, i.e. T = kπ/ω_0, ω_0 = √(mean k), with width O(ε).
  const double eps = 0.1, duty = 0.6;
  const double k_hi = 1 + eps, k_lo = 1 - eps;
  const double w0 = std::sqrt(duty * k_hi + (1 - duty) * k_lo);
  std::vector<int> hits(4, 0);
  for (int i = 0; i <= 1200; ++i) {
    const double T = (0.3 + 3.4 * i / 1200.0) * kPi / w0;
    const FloquetResult r = ComputeFloquet(MakeMeissnerSystem(k_hi, k_lo, duty, T), {});
    if (r.stable()) continue;
    const int k = static_cast<int>(std::lround(T * w0 / kPi));
    ASSERT_GE(k, 1);
    ASSERT_LE(k, 3);
    EXPECT_LT(std::abs(T * w0 / (k * kPi) - 1.0), 0.06) << "unstable at T = " << T;
    ++hits[k];
  }
  for (int k = 1; k <= 3; ++k) EXPECT_GT(hits[k], 0) << "no tongue " << k;
}

TEST(MeissnerTest, OtherMethodsMatchTheClosedFormWithinTheirTolerance) {
  const double duty = 0.6, T = 2.9;
  const double tr = MeissnerTrace(1.3, 0.7, duty * T, (1 - duty) * T);
  const VectorXc exact = MeissnerMultipliers(tr);
  PeriodicSecondOrderSystem sys = MakeMeissnerSystem(1.3, 0.7, duty, T);
  FloquetOptions o;
  o.method = FloquetMethod::kOdeStepper;
  o.tolerance = 1e-10;
  FloquetResult r = ComputeFloquet(sys, o);
  EXPECT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_LE(MultiplierDistance(r.multipliers, exact), 1e-10);
  EXPECT_LE(r.summary.error_estimate, 1e-10);

  // (Hill is tested on smooth coefficients: the wave's 1/m Fourier decay makes it converge
  // slowly here; see mathieu_test.cpp and shortcuts_vs_ode_test.cpp.)
}

TEST(MeissnerTest, LongPeriodOfIdenticalCyclesIsThePowerWithoutOverflow) {
  // 1000 identical cycles (2000 steps): Φ_P = Φ_1^1000. Unstable point (|λ| ≈ 2.6): λ^1000
  // overflows double, the exponents (μ = ln λ / T) do not.
  const double duty = 0.6;
  const int P = 1000;
  for (const double k_lo : {-1.0, 0.7}) {  // unstable, stable
    const double T = k_lo < 0 ? 4.0 : 3.1;
    const PeriodicSecondOrderSystem one = MakeMeissnerSystem(1.9, k_lo, duty, T);
    PeriodicSecondOrderSystem many = one;
    many.period_s = P * T;
    many.steps.clear();
    for (int j = 0; j < P; ++j)
      many.steps.insert(many.steps.end(), one.steps.begin(), one.steps.end());
    const FloquetResult r1 = ComputeFloquet(one, {});
    const FloquetResult rP = ComputeFloquet(many, {});
    ASSERT_TRUE(rP.exponents.allFinite());
    EXPECT_LT(rP.summary.counters.at("steps"), 10);  // the cycle, then squaring
    // Re μ is the same; Im μ agrees modulo 2π/T_P.
    EXPECT_NEAR(rP.exponents.real().maxCoeff(), r1.exponents.real().maxCoeff(), 1e-12);
    if (r1.stable()) {
      VectorXc powered(2);
      for (int i = 0; i < 2; ++i) powered[i] = std::pow(r1.multipliers[i], P);
      EXPECT_LE(MultiplierDistance(rP.multipliers, powered), 1e-10);
      EXPECT_TRUE(rP.stable());
    } else {
      EXPECT_EQ(rP.verdict, FloquetVerdict::kUnstable);  // an overflowing growth, exact exponents
      ASSERT_GT(P * std::log(r1.max_abs_multiplier), 710.0);  // λ^P beyond double
      EXPECT_FALSE(std::isfinite(rP.max_abs_multiplier));
      EXPECT_FALSE(rP.summary.warnings.empty());
    }
  }
}

TEST(MeissnerTest, InvalidInputNamesTheField) {
  FloquetOptions o;
  o.tolerance = -1;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(MakeMeissnerSystem(1, 0.5, 0.5, 1.0), o), InvalidInput,
                        "tolerance");
  PeriodicSecondOrderSystem s = MakeMeissnerSystem(1, 0.5, 0.5, 1.0);
  s.steps[0].duration_s = 0.7;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(s, {}), InvalidInput, "durations sum");
  s = MakeMeissnerSystem(1, 0.5, 0.5, 1.0);
  o = {};
  o.method = FloquetMethod::kHill;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(s, o), InvalidInput, "hill needs");
  s.mass(0, 0) = -1;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(s, {}), InvalidInput, "mass");
}

}  // namespace
}  // namespace geardyn::test
