// Floquet with meshes at several frequencies (issue 18): two hand pairs that do not touch, pair b
// at r = 2/3 of pair a's mesh frequency. Over the common period of 3 cycles of θ, pair a makes 3
// of its own cycles and pair b 2, so the monodromy is block diagonal with Φ_a³ and Φ_b² and its
// multipliers are {λ_a³} ∪ {λ_b²}, where λ_a, λ_b are each pair's own one-cycle multipliers
// (single-frequency Floquet of the pair alone at its own mesh frequency) — a closed-form
// consequence of the semigroup property, checked for the exact step product (rectangular-wave
// stiffness) and for Magnus (smooth stiffness), with mesh damping so that the mesh modes
// multipliers lie inside the unit circle.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"

namespace geardyn::test {
namespace {

constexpr double kRatio = 2.0 / 3.0;

VectorXc Powers(const VectorXc& lambda, int k) {
  VectorXc out(lambda.size());
  for (Eigen::Index i = 0; i < lambda.size(); ++i) out[i] = std::pow(lambda[i], k);
  return out;
}

void ExpectUnionOfPowers(const MeshCore& core_a, const MeshCore& core_b, FloquetMethod method,
                         double tol) {
  const double f_m = 1300.0;
  const SystemModel both = TwoSeparatePairs(core_a, core_b, kRatio);
  const FloquetResult r = ComputeFloquet(both, FloquetAt(f_m, method));
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.period_meshes, 3);
  EXPECT_NEAR(r.period_s, 3.0 / f_m, 1e-15);
  EXPECT_TRUE(std::any_of(r.summary.warnings.begin(), r.summary.warnings.end(),
                          [](const std::string& w) { return w.find("common period") != w.npos; }));
  // Each pair alone, at its own mesh frequency (the pair-b offset only shifts the time origin).
  const FloquetResult a = ComputeFloquet(HandPair(core_a), FloquetAt(f_m, method));
  const FloquetResult b = ComputeFloquet(HandPair(core_b), FloquetAt(kRatio * f_m, method));
  ASSERT_TRUE(a.summary.ok() && b.summary.ok());
  ASSERT_EQ(r.multipliers.size(), a.multipliers.size() + b.multipliers.size());
  VectorXc expected(r.multipliers.size());
  expected << Powers(a.multipliers, 3), Powers(b.multipliers, 2);
  EXPECT_LE(MultiplierDistance(r.multipliers, expected), tol);
  const double want =
      std::max(std::pow(a.max_abs_multiplier, 3), std::pow(b.max_abs_multiplier, 2));
  EXPECT_NEAR(r.max_abs_multiplier, want, tol);
  // The bearings' modes carry no mesh damping (|λ| = 1): both pairs are stable and marginal,
  // and so is the train.
  ASSERT_EQ(a.verdict, b.verdict);
  EXPECT_EQ(r.verdict, a.verdict);
  EXPECT_EQ(r.marginal, a.marginal || b.marginal);
}

TEST(SeveralFrequenciesFloquet, ExactStepsAreTheUnionOfThePairsPowers) {
  ExpectUnionOfPowers(HandSpurWaveCore(1500.0), HandSpurWaveCore(900.0), FloquetMethod::kAuto,
                      1e-9);
}

TEST(SeveralFrequenciesFloquet, MagnusIsTheUnionOfThePairsPowers) {
  ExpectUnionOfPowers(HandSmoothCore(0.2, 0.05, 1500.0), HandSmoothCore(0.3, 0.0, 900.0),
                      FloquetMethod::kMagnus, 1e-7);
}

TEST(SeveralFrequenciesFloquet, IncommensurateWithoutApproximantsAndHillAreRefusedByName) {
  const SystemModel irrational =
      TwoSeparatePairs(HandSpurWaveCore(1500.0), HandSpurWaveCore(900.0), std::sqrt(2.0) / 2.0);
  try {
    FloquetOptions refuse = FloquetAt(1300.0, FloquetMethod::kAuto);
    refuse.max_approximant_period_meshes = 0;  // the rational approximants off
    (void)ComputeFloquet(irrational, refuse);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("incommensurate"), std::string::npos) << e.what();
  }
  const SystemModel both =
      TwoSeparatePairs(HandSpurWaveCore(1500.0), HandSpurWaveCore(900.0), kRatio);
  try {
    (void)ComputeFloquet(both, FloquetAt(1300.0, FloquetMethod::kHill));
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("method: hill"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace geardyn::test
