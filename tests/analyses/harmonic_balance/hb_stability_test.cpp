// The Floquet verdict of the linear-HB points (hb_stability.hpp) against the closed form of the
// damped Meissner equation. The torsional hand pair (θz of both gears, one free rotation) with
// a rectangular-wave mesh stiffness k(θ) (k_hi = 5e8 N/m over 0.6 of the mesh cycle, k_lo = 3e8
// over the rest) and a constant mesh damping c reduces exactly to the SDOF equation of the
// dynamic transmission error δ = r1 θ1 + r2 θ2:
//   δ'' + γ δ' + (k(θ)/m_e) δ = 0,  1/m_e = r1²/I1 + r2²/I2,  γ = c/m_e,
// whose multipliers are e^{−γT/2} times those of the undamped Meissner equation with k/m_e −
// γ²/4 (x = e^{−γt/2} y), the roots of λ² − tr λ + 1 with tr the trace of the two exact transfer
// matrices (Richards, Analysis of Periodically Time-Varying Systems, 1983, §4.3). The rigid
// rotation adds the exact multiplier 1, so max|λ| = max(1, e^{−γT/2} ρ_Meissner).
#include "geardyn/analyses/hb_stability.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "../floquet/floquet_test_support.hpp"
#include "geardyn/analyses/harmonic_balance.hpp"
#include "hb_fixtures.hpp"

namespace geardyn {
namespace {

using test::HandPairParams;

constexpr double kHi = 5e8, kLo = 3e8, kDuty = 0.6;  // SpurWave(3e8, 5e8, 1.6) [N/m], [-]
constexpr double kMeshDamping = 500.0;               // c [N·s/m]: ζ ≈ 0.018 of the mesh mode

double EquivalentMass() {
  const HandPairParams p;
  return 1.0 / (p.r1 * p.r1 / p.I1 + p.r2 * p.r2 / p.I2);
}

// The closed-form largest flexible |λ| at mesh frequency f [Hz] with damping c [N·s/m].
double ClosedFormMaxMultiplier(double f, double c) {
  const double me = EquivalentMass(), gamma = c / me, T = 1.0 / f;
  const double shift = 0.25 * gamma * gamma;
  const double tr =
      test::MeissnerTrace(kHi / me - shift, kLo / me - shift, kDuty * T, (1 - kDuty) * T);
  return std::exp(-0.5 * gamma * T) * test::MeissnerMultipliers(tr).cwiseAbs().maxCoeff();
}

SystemModel TorsionalWavePair(double c) { return test::TorsionalPair(test::HandSpurWaveCore(c)); }

TEST(HbStabilityTest, PrincipalRegionOfTheDampedMeissnerPairIsMarkedUnstable) {
  const SystemModel model = TorsionalWavePair(kMeshDamping);
  ASSERT_EQ(model.num_dofs(), 2);
  // Natural frequency of the mean system: the principal region lies about f_m = 2 f_0; the sweep
  // stays clear of the third region (near 2 f_0 / 3).
  const double f0 =
      std::sqrt((kDuty * kHi + (1 - kDuty) * kLo) / EquivalentMass()) / (2.0 * std::numbers::pi);
  std::vector<double> frequencies;
  for (int i = 0; i <= 56; ++i) frequencies.push_back(2.0 * f0 * (0.75 + 0.6 * i / 56.0));
  const HbStabilitySweep sweep = ComputeHbStability(model, frequencies, FloquetOptions{});
  ASSERT_TRUE(sweep.summary.ok()) << sweep.summary.message;
  ASSERT_EQ(sweep.points.size(), frequencies.size());
  int unstable = 0, stable = 0;
  double first_unstable = 0.0, last_unstable = 0.0;
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    const HbPointStability& p = sweep.points[i];
    const double rho = ClosedFormMaxMultiplier(frequencies[i], kMeshDamping);
    EXPECT_EQ(p.mesh_frequency_hz, frequencies[i]);
    // Near a transition curve the roots are double and only √ε-conditioned: skip a thin band.
    if (std::abs(rho - 1.0) < 1e-4) continue;
    EXPECT_NEAR(p.max_abs_multiplier, std::max(1.0, rho), 1e-9) << "f_m " << frequencies[i];
    if (rho > 1.0) {
      EXPECT_EQ(p.verdict, FloquetVerdict::kUnstable) << "f_m " << frequencies[i];
      if (unstable++ == 0) first_unstable = frequencies[i];
      last_unstable = frequencies[i];
    } else {
      EXPECT_EQ(p.verdict, FloquetVerdict::kStable) << "f_m " << frequencies[i];
      ++stable;
    }
  }
  // The sweep crosses the principal region (and only it) with points on both sides.
  EXPECT_GE(unstable, 5);
  EXPECT_GE(stable, 10);
  ASSERT_EQ(sweep.unstable_ranges.size(), 1u);
  EXPECT_EQ(sweep.unstable_ranges[0].lo_hz, first_unstable);
  EXPECT_EQ(sweep.unstable_ranges[0].hi_hz, last_unstable);
  EXPECT_EQ(sweep.unstable_ranges[0].points, unstable);
  EXPECT_LT(first_unstable, 2.0 * f0);
  EXPECT_GT(last_unstable, 2.0 * f0);
  ASSERT_FALSE(sweep.summary.warnings.empty());
  EXPECT_NE(sweep.summary.warnings[0].find("parametrically unstable"), std::string::npos);
  EXPECT_EQ(sweep.summary.counters.at("unstable_points"), unstable);
}

TEST(HbStabilityTest, MoreDampingClosesTheRegion) {
  // The closed form at the centre of the region: unstable with c, stable with 20 c (the
  // damped Meissner threshold), and the verdicts follow.
  const double f0 =
      std::sqrt((kDuty * kHi + (1 - kDuty) * kLo) / EquivalentMass()) / (2.0 * std::numbers::pi);
  const double f = 2.0 * f0;
  ASSERT_GT(ClosedFormMaxMultiplier(f, kMeshDamping), 1.0 + 1e-3);
  ASSERT_LT(ClosedFormMaxMultiplier(f, 20 * kMeshDamping), 1.0 - 1e-3);
  EXPECT_EQ(ComputeHbPointStability(TorsionalWavePair(kMeshDamping), f, {}).verdict,
            FloquetVerdict::kUnstable);
  const HbPointStability damped =
      ComputeHbPointStability(TorsionalWavePair(20 * kMeshDamping), f, {});
  EXPECT_EQ(damped.verdict, FloquetVerdict::kStable);
  EXPECT_FALSE(damped.marginal);
}

TEST(HbStabilityTest, DampedLtiPairIsStableEverywhere) {
  // Constant stiffness (k_hi = k_lo): an LTI system with a damped mode, |λ_flex| = e^{−γT/2} < 1
  // at every frequency; the HB points are all stable and no range is reported.
  const SystemModel model = test::TorsionalPair(
      LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, test::SpurWave(4e8, 4e8, 1.6), 0.0125,
                     std::nullopt, MeshDamping::FromCoefficient(kMeshDamping)));
  const HbStabilitySweep sweep =
      ComputeHbStability(model, {1000.0, 5000.0, 9500.0, 20000.0}, FloquetOptions{});
  ASSERT_TRUE(sweep.summary.ok()) << sweep.summary.message;
  for (const HbPointStability& p : sweep.points) {
    EXPECT_EQ(p.verdict, FloquetVerdict::kStable) << "f_m " << p.mesh_frequency_hz;
  }
  EXPECT_TRUE(sweep.unstable_ranges.empty());
}

}  // namespace
}  // namespace geardyn
