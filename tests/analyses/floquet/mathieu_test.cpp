// The Mathieu equation x'' + (δ + ε cos t) x = 0 (T = 2π): transition curves found by bisection
// on max|λ| = 1 against the classical perturbation series (Nayfeh & Mook, Nonlinear Oscillations,
// 1979, §5.2.1, Eqs. (5.2.15)–(5.2.22); Abramowitz & Stegun §20.2 in the a, q notation):
//   δ = 1/4 ± ε/2 − ε²/8 ∓ ε³/32 + O(ε⁴)      (period 4π, principal tongue)
//   δ = 1 − ε²/12 + O(ε⁴),  δ = 1 + 5ε²/12 + O(ε⁴)   (period 2π, second tongue)
//   δ = −ε²/2 + O(ε⁴)
// The series is accurate to O(ε⁴): the test checks |δ − series| ≤ ε⁴ for ε = 0.1 and 0.2, and that
// the difference falls by about 2⁴ when ε is halved (the order of the series).
// Magnus (kAuto for a smooth system) and Hill must agree on the curves.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "floquet_test_support.hpp"

namespace geardyn::test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool Unstable(double delta, double eps, FloquetMethod method) {
  FloquetOptions o;
  o.method = method;
  o.tolerance = 1e-12;
  o.hill_harmonics = method == FloquetMethod::kHill ? 8 : 0;
  const FloquetResult r = ComputeFloquet(MakeMathieuSystem(delta, eps, kTwoPi), o);
  // In the stable region the undamped multipliers lie on the unit circle to round-off; across
  // the curve a real pair λ, 1/λ appears with |λ| − 1 ~ √(distance).
  return r.max_abs_multiplier > 1.0 + 1e-11;
}

// Bisection for the transition inside [lo, hi] (Unstable differs at the two ends).
double Transition(double lo, double hi, double eps, FloquetMethod method = FloquetMethod::kAuto) {
  const bool at_lo = Unstable(lo, eps, method);
  EXPECT_NE(at_lo, Unstable(hi, eps, method)) << "no transition in [" << lo << ", " << hi << "]";
  for (int i = 0; i < 36; ++i) {
    const double mid = 0.5 * (lo + hi);
    (Unstable(mid, eps, method) == at_lo ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Curve {
  const char* name;
  std::function<double(double)> series;  // δ(ε) to the order given
  std::function<std::pair<double, double>(double)> bracket;
};

std::vector<Curve> Curves() {
  return {
      {"quarter_minus", [](double e) { return 0.25 - e / 2 - e * e / 8 + e * e * e / 32; },
       [](double e) { return std::make_pair(0.25 - e, 0.25 - e * e / 8); }},
      {"quarter_plus", [](double e) { return 0.25 + e / 2 - e * e / 8 - e * e * e / 32; },
       [](double e) { return std::make_pair(0.25 - e * e / 8, 0.25 + e); }},
      {"one_minus", [](double e) { return 1.0 - e * e / 12; },
       [](double e) { return std::make_pair(1.0 - e * e, 1.0 + e * e / 6); }},
      {"one_plus", [](double e) { return 1.0 + 5 * e * e / 12; },
       [](double e) { return std::make_pair(1.0 + e * e / 6, 1.0 + e * e); }},
      {"zero", [](double e) { return -e * e / 2; },
       [](double e) { return std::make_pair(-e * e, 0.1); }},
  };
}

TEST(MathieuTest, TransitionCurvesMatchTheSeriesToTheirOrder) {
  for (const Curve& c : Curves()) {
    double previous = 0.0;
    for (const double eps : {0.2, 0.1}) {
      const auto [lo, hi] = c.bracket(eps);
      const double delta = Transition(lo, hi, eps);
      const double diff = std::abs(delta - c.series(eps));
      EXPECT_LE(diff, std::pow(eps, 4)) << c.name << " eps " << eps << " delta " << delta;
      if (previous > 0.0 && diff > 1e-9) {
        // O(ε⁴): halving ε divides the difference by ≈ 16 (≥ 10 allowing the next term).
        EXPECT_GT(previous / diff, 10.0) << c.name;
      }
      previous = diff;
    }
  }
}

TEST(MathieuTest, HillFindsTheSameCurvesAsMagnus) {
  const double eps = 0.2;
  for (const Curve& c : Curves()) {
    if (std::string(c.name) == "one_plus" || std::string(c.name) == "zero") continue;  // time
    const auto [lo, hi] = c.bracket(eps);
    EXPECT_NEAR(Transition(lo, hi, eps, FloquetMethod::kHill), Transition(lo, hi, eps), 1e-9)
        << c.name;
  }
}

TEST(MathieuTest, MagnusAndHillMultipliersAgreeInsideATongue) {
  FloquetOptions o;
  o.tolerance = 1e-11;
  const PeriodicSecondOrderSystem s = MakeMathieuSystem(0.26, 0.3, kTwoPi, 0.02);
  const FloquetResult magnus = ComputeFloquet(s, o);
  EXPECT_EQ(magnus.method_used, FloquetMethod::kMagnus);
  o.method = FloquetMethod::kHill;
  const FloquetResult hill = ComputeFloquet(s, o);
  o.method = FloquetMethod::kOdeStepper;
  const FloquetResult ode = ComputeFloquet(s, o);
  EXPECT_FALSE(magnus.stable());
  EXPECT_LE(MultiplierDistance(magnus.multipliers, ode.multipliers), 1e-10);
  EXPECT_LE(MultiplierDistance(hill.multipliers, ode.multipliers), 1e-10);
  // Liouville: λ1 λ2 = exp(−c T).
  EXPECT_NEAR(std::abs(magnus.multipliers.prod()), std::exp(-0.02 * kTwoPi), 1e-12);
}

}  // namespace
}  // namespace geardyn::test
