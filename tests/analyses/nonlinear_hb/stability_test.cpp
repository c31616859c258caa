/// @file
/// @brief Stability of the nonlinear HB solutions of the B&K oscillator: the middle branch
/// between the folds is unstable and the outer branches stable (monodromy), Hill's method
/// agrees, and the time integration (GSL rk8pd, independent of the HB) started on an unstable
/// orbit leaves it for a stable branch while one started on a stable orbit stays.
/// Also: the analytic Jacobian and ∂R/∂Ω against central finite differences (exact and sampled
/// force integration).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "analyses/nonlinear_hb/bk_parameter_sets.hpp"
#include "analyses/nonlinear_hb/bk_time_integration.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

ClearanceOscillatorParameters SetA() { return testing::BkSingleSidedSet(); }

/// The traced curve, computed once for all tests of this file.
const NhbCurve& TraceSetA() {
  static const NhbCurve curve = [] {
    NhbOptions options;
    options.harmonics = 16;
    options.stability = NhbStabilityMethod::kMonodromy;
    NhbContinuationOptions c;
    c.omega_start = 0.7;
    c.omega_end = 1.0;
    c.max_step = 0.1;
    c.max_tangent_angle = 0.5;
    return TraceNonlinearHarmonicBalance(MakeClearanceOscillator(SetA()), options, c);
  }();
  return curve;
}

TEST(NonlinearHbStability, MiddleBranchUnstableOuterBranchesStable) {
  const NhbCurve& curve = TraceSetA();
  ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
  ASSERT_EQ(curve.folds.size(), 2u);
  const double w0 = curve.folds[0].omega, w1 = curve.folds[1].omega;
  int checked = 0;
  for (int i = 0; i < static_cast<int>(curve.points.size()); ++i) {
    // Stability changes at the folds, where |μ| → 1: skip points within 0.5 % of a fold's Ω.
    const double w = curve.points[i].omega;
    if (std::abs(w - w0) < 5e-3 * w0 || std::abs(w - w1) < 5e-3 * w1) continue;
    const NhbPoint& pt = curve.points[i];
    EXPECT_EQ(pt.stable == FloquetVerdict::kStable, pt.branch != 1)
        << "Ω = " << pt.omega << " branch " << pt.branch << " |μ| = " << pt.max_multiplier;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST(NonlinearHbStability, HillAgreesWithMonodromy) {
  const NhbCurve& curve = TraceSetA();
  ASSERT_TRUE(curve.summary.ok());
  NhbOptions hill;
  hill.harmonics = 16;
  hill.stability = NhbStabilityMethod::kHill;
  NhbSolver solver(MakeClearanceOscillator(SetA()), hill, 16);
  const double w0 = curve.folds.at(0).omega, w1 = curve.folds.at(1).omega;
  for (int i = 0; i < static_cast<int>(curve.points.size()); i += 9) {
    const NhbPoint& pt = curve.points[i];
    if (std::abs(pt.omega - w0) < 5e-3 * w0 || std::abs(pt.omega - w1) < 5e-3 * w1) continue;
    const double mu = solver.MaxMultiplier(testing::PointUnknowns(pt), pt.omega);
    EXPECT_EQ(mu < 1.0, pt.stable == FloquetVerdict::kStable) << "Ω = " << pt.omega;
    EXPECT_NEAR(mu, pt.max_multiplier, 0.05 * pt.max_multiplier) << "Ω = " << pt.omega;
  }
}

TEST(NonlinearHbStability, TimeIntegrationLeavesTheUnstableOrbit) {
  const NhbCurve& curve = TraceSetA();
  ASSERT_TRUE(curve.summary.ok());
  const ClearanceOscillatorParameters p = SetA();
  const testing::BkParameters bk{p.zeta, p.alpha, p.mean_force, p.alternating_force, 0.0, true};
  // The middle point of the unstable branch, and a stable point at the same Ω.
  std::vector<int> middle;
  for (int i = 0; i < static_cast<int>(curve.points.size()); ++i) {
    if (curve.points[i].branch == 1) middle.push_back(i);
  }
  ASSERT_GT(middle.size(), 4u);
  const NhbPoint& unstable = curve.points[middle[middle.size() / 2]];
  ASSERT_EQ(unstable.stable, FloquetVerdict::kUnstable);
  auto start_state = [](const NhbPoint& pt) {
    // x(0) = Σ_k U_k, x'(0) = Σ_k ikω U_k (two-sided sums), t = 0 ↔ phase Ωt = 0.
    testing::BkState s;
    s.x = pt.harmonics(0, 0).real();
    for (int k = 1; k < pt.harmonics.cols(); ++k) {
      s.x += 2.0 * pt.harmonics(0, k).real();
      s.v += 2.0 * (std::complex<double>(0.0, k * pt.omega) * pt.harmonics(0, k)).real();
    }
    return s;
  };
  testing::BkState s = start_state(unstable);
  testing::BkStats stats;
  testing::BkIntegrate(bk, unstable.omega, 400, 4, s, &stats);
  EXPECT_GT(std::abs(stats.rms - unstable.rms[0]), 0.2 * unstable.rms[0])
      << "stayed on the unstable orbit";
  // It lands on one of the stable HB branches at this Ω.
  double best = 1e300;
  for (size_t i = 0; i + 1 < curve.points.size(); ++i) {
    const NhbPoint& a = curve.points[i];
    const NhbPoint& b = curve.points[i + 1];
    if (a.stable != FloquetVerdict::kStable || b.stable != FloquetVerdict::kStable) continue;
    if ((a.omega - unstable.omega) * (b.omega - unstable.omega) > 0) continue;
    const double w = (unstable.omega - a.omega) / (b.omega - a.omega);
    best = std::min(best, std::abs(a.rms[0] + w * (b.rms[0] - a.rms[0]) - stats.rms));
  }
  EXPECT_LT(best, 0.01 * stats.rms);
  // Control: a stable orbit (the first point) is kept by the time integration.
  const NhbPoint& stable = curve.points.front();
  ASSERT_EQ(stable.stable, FloquetVerdict::kStable);
  testing::BkState s2 = start_state(stable);
  testing::BkIntegrate(bk, stable.omega, 100, 4, s2, &stats);
  EXPECT_NEAR(stats.rms, stable.rms[0], 1e-3 * stable.rms[0]);
  EXPECT_NEAR(stats.maximum, stable.maximum[0], 1e-3 * stable.maximum[0]);
}

TEST(NonlinearHbJacobian, MatchesCentralDifferences) {
  ClearanceOscillatorParameters p = SetA();
  p.alternating_force = 0.3;  // deep contact loss and back contact in the test state
  const int H = 6;
  for (const NhbForceIntegration integration :
       {NhbForceIntegration::kExact, NhbForceIntegration::kSampled}) {
    SCOPED_TRACE(integration == NhbForceIntegration::kExact ? "exact" : "sampled");
    NhbOptions options;
    options.force_integration = integration;
    NhbSolver solver(MakeClearanceOscillator(p), options, H);
    VectorX x = VectorX::Zero(2 * H + 1);
    x[0] = 0.6;
    x[1] = 0.7;
    x[2] = -0.4;
    x[3] = 0.1;
    x[6] = 0.05;
    const double w = 0.8;
    VectorX R, dR;
    MatrixX J;
    solver.Evaluate(x, w, &R, &J, &dR);
    const double h = 1e-7;
    for (int j = 0; j < x.size(); ++j) {
      VectorX xp = x, xm = x, Rp, Rm;
      xp[j] += h;
      xm[j] -= h;
      solver.Evaluate(xp, w, &Rp, nullptr, nullptr);
      solver.Evaluate(xm, w, &Rm, nullptr, nullptr);
      const VectorX fd = (Rp - Rm) / (2 * h);
      EXPECT_LT((fd - J.col(j)).lpNorm<Eigen::Infinity>(), 1e-6) << "column " << j;
    }
    VectorX Rp, Rm;
    solver.Evaluate(x, w + h, &Rp, nullptr, nullptr);
    solver.Evaluate(x, w - h, &Rm, nullptr, nullptr);
    EXPECT_LT(((Rp - Rm) / (2 * h) - dR).lpNorm<Eigen::Infinity>(), 1e-6);
  }
}

}  // namespace
}  // namespace geardyn
