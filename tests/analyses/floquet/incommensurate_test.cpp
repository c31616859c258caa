// Floquet with meshes at incommensurate frequencies (issue 18): the rational approximants.
//
// Truth 1: two hand pairs that do not touch, pair b at r = √2/2 of pair a's mesh frequency. The
// quasi-periodic train is then two periodic systems side by side, so its Lyapunov exponents are
// exactly the union of each pair's own characteristic exponents (real parts), pair a's at f_m and
// pair b's at r f_m — each an ordinary single-frequency Floquet analysis of the pair alone, with
// no approximation of r. The approximants' exponents must converge to that union, within the
// error estimate of the convergence study, and the verdict must be the pairs' combined one.
//
// Truth 2, coupled: one pinion meshing with two wheels, the second mesh at r = √2/2 (the LTV
// equations of a two-stage train whose ratio is irrational), every flexible mode damped. Its
// largest Lyapunov exponent by a different method: a long fixed-step RK4 integration of
// M q̈ + C(θ) q̇ + K(θ) q = 0, renormalized every step, the slope of the accumulated log-norm
// (Benettin et al. 1980), with the free rotation projected out (M-orthogonally: it is an
// invariant complement since K(θ) and C(θ) annihilate the rigid mode).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "../../lib/system/periodic_fixture.hpp"
#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/system_damping.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::test {
namespace {

const double kIrrational = std::sqrt(2.0) / 2.0;  // convergents 1/1, 2/3, 5/7, 12/17, 29/41, …
// The coupled case's operating point [Hz] and the length of its Lyapunov integration [cycles].
constexpr double kCoupledMeshFrequency = 1300.0;
constexpr int kLyapunovCycles = 500;

// The real parts of the flexible exponents (rigid multipliers, exactly 1, left out), descending.
std::vector<double> FlexibleRealParts(const FloquetResult& r) {
  std::vector<double> out;
  for (Eigen::Index i = 0; i < r.exponents.size(); ++i) {
    if (r.multipliers[i] != std::complex<double>(1.0, 0.0)) out.push_back(r.exponents[i].real());
  }
  std::sort(out.begin(), out.end(), std::greater<>());
  return out;
}

SystemModel WithModalDamping(const SystemModel& model, double zeta) {
  SystemDamping damping;
  damping.modal_ratio = zeta;
  return AddSystemDamping(model, damping);
}

TEST(IncommensurateFloquet, ApproximantsAreTheContinuedFractionConvergents) {
  const SystemModel both =
      TwoSeparatePairs(HandSpurWaveCore(1500.0), HandSpurWaveCore(900.0), kIrrational);
  const std::vector<FloquetApproximant> levels = internal::RationalApproximants(both, 1000);
  // √2/2 = [0; 1, 2, 2, 2, …]: convergents p/q with q = 1, 3, 7, 17, 41, 99, 239, 577 (the next,
  // 1393, exceeds the bound); mesh a stays at 1/1, so the common period is q.
  const std::vector<std::int64_t> q = {1, 3, 7, 17, 41, 99, 239, 577};
  const std::vector<std::int64_t> p = {1, 2, 5, 12, 29, 70, 169, 408};
  ASSERT_EQ(levels.size(), q.size());
  for (std::size_t j = 0; j < q.size(); ++j) {
    EXPECT_EQ(levels[j].period_meshes, q[j]);
    ASSERT_EQ(levels[j].ratios.size(), 2u);
    EXPECT_EQ(levels[j].ratios[0], 1.0);
    EXPECT_DOUBLE_EQ(levels[j].ratios[1], static_cast<double>(p[j]) / static_cast<double>(q[j]));
    // |r − p/q| < 1/q² (every convergent), and it falls at every level.
    EXPECT_LT(levels[j].ratio_error, 1.0 / static_cast<double>(q[j] * q[j]));
    if (j > 0) {
      EXPECT_LT(levels[j].ratio_error, levels[j - 1].ratio_error);
    }
  }
}

TEST(IncommensurateFloquet, ExponentsConvergeToTheUnionOfThePairsOwn) {
  const double f_m = 1300.0;
  // Light modal damping of every flexible mode (ζ = 0.1 %): the least-damped exponents lie within
  // the window a 577-cycle product resolves (multipliers within 10⁸ of the largest). The two
  // pairs are alike, so the train's modal damping is the pairs' own (equal ζ and ω over a
  // repeated eigenspace: C = 2ζω M P there, whatever its basis).
  constexpr double kZeta = 1e-3;
  const LinearMeshCore core = HandSpurWaveCore();
  const SystemModel both = WithModalDamping(TwoSeparatePairs(core, core, kIrrational), kZeta);
  const FloquetResult r = ComputeFloquet(both, FloquetAt(f_m, FloquetMethod::kAuto));
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  // The last three approximants within the default bound of 1000 cycles.
  ASSERT_EQ(r.approximants.size(), 3u);
  EXPECT_EQ(r.approximants[0].period_meshes, 99);
  EXPECT_EQ(r.approximants[1].period_meshes, 239);
  EXPECT_EQ(r.approximants[2].period_meshes, 577);
  EXPECT_EQ(r.period_meshes, 577);
  EXPECT_NEAR(r.period_s, 577.0 / f_m, 1e-12);
  EXPECT_NE(r.summary.warnings.front().find("incommensurate"), std::string::npos);

  // Each pair alone, single frequency, b at its exact irrational frequency.
  const SystemModel pair = WithModalDamping(HandPair(core), kZeta);
  const FloquetResult a = ComputeFloquet(pair, FloquetAt(f_m, FloquetMethod::kAuto));
  const FloquetResult b = ComputeFloquet(pair, FloquetAt(kIrrational * f_m, FloquetMethod::kAuto));
  ASSERT_TRUE(a.summary.ok() && b.summary.ok());
  std::vector<double> want = FlexibleRealParts(a);
  const std::vector<double> from_b = FlexibleRealParts(b);
  want.insert(want.end(), from_b.begin(), from_b.end());
  std::sort(want.begin(), want.end(), std::greater<>());
  const std::vector<double> got = FlexibleRealParts(r);
  ASSERT_EQ(got.size(), want.size());
  // Compare the exponents the long product resolves (≥ 4 of them).
  const double floor = got.front() + std::log(1e-8) / r.period_s;
  std::size_t resolved = 0;
  double error = 0.0;
  for (; resolved < got.size() && got[resolved] >= floor; ++resolved) {
    error = std::max(error, std::abs(got[resolved] - want[resolved]));
  }
  ASSERT_GE(resolved, 4u);
  const double scale = std::abs(want.front());  // ζω of the least-damped mode [1/s]
  EXPECT_GT(scale, 1.0);
  EXPECT_LE(error, 1e-3 * scale);
  // The study's estimate (a change of max|λ| over the last period) covers the true error of the
  // exponents: error ≤ estimate / (max|λ| T).
  const double estimate_as_exponent =
      r.summary.error_estimate / (r.max_abs_multiplier * r.period_s);
  EXPECT_LE(error, estimate_as_exponent);
  // Max Re μ of every approximant is the largest of the union; all stable.
  for (const FloquetApproximant& level : r.approximants) {
    EXPECT_NEAR(level.max_real_exponent, want.front(), 1e-3 * scale);
    EXPECT_EQ(level.verdict, FloquetVerdict::kStable);
  }
  EXPECT_EQ(a.verdict, FloquetVerdict::kStable);
  EXPECT_EQ(r.verdict, FloquetVerdict::kStable);
  EXPECT_FALSE(r.marginal);
}

// The largest Lyapunov exponent of the flexible motion [1/s] (see the file comment): RK4 with
// `steps_per_cycle` steps per mesh cycle over `cycles` cycles; the slope of ln‖x‖ by least squares
// over the last three quarters.
double LyapunovExponent(const SystemModel& model, double f_m, int cycles, int steps_per_cycle) {
  const int n = model.num_dofs();
  const MatrixX M = model.DenseMass();
  const MatrixX M_inv = M.inverse();
  SystemWorkspace ws(model, StorageKind::kDense);
  // The rigid mode: the null vector of K̄ (one free rotation).
  const MatrixX kbar = AssembleMeanStiffness(model, ws);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> mean(kbar, M);
  const VectorX rigid = mean.eigenvectors().col(0);
  EXPECT_LT(std::abs(mean.eigenvalues()[0]), 1e-6 * mean.eigenvalues()[1]);
  const double rigid_norm = rigid.dot(M * rigid);
  auto project = [&](VectorX& x) {
    x.head(n) -= rigid * (rigid.dot(M * x.head(n)) / rigid_norm);
    x.tail(n) -= rigid * (rigid.dot(M * x.tail(n)) / rigid_norm);
  };
  const double omega = 2.0 * std::numbers::pi * f_m;
  auto rhs = [&](double t, const VectorX& x) {
    const double theta = omega * t;
    VectorX dx(2 * n);
    dx.head(n) = x.tail(n);
    const VectorX force = AssembleDamping(model, ws, theta) * x.tail(n) +
                          AssembleStiffness(model, ws, theta) * x.head(n);
    dx.tail(n) = -(M_inv * force);
    return dx;
  };
  VectorX x = VectorX::LinSpaced(2 * n, 1.0, 2.0);
  project(x);
  x.normalize();
  const double h = 1.0 / (f_m * steps_per_cycle);
  const long steps = static_cast<long>(cycles) * steps_per_cycle;
  double log_norm = 0.0;
  double sum_t = 0.0, sum_l = 0.0, sum_tt = 0.0, sum_tl = 0.0;
  long count = 0;
  for (long k = 0; k < steps; ++k) {
    const double t = static_cast<double>(k) * h;
    const VectorX k1 = rhs(t, x);
    const VectorX k2 = rhs(t + 0.5 * h, x + 0.5 * h * k1);
    const VectorX k3 = rhs(t + 0.5 * h, x + 0.5 * h * k2);
    const VectorX k4 = rhs(t + h, x + h * k3);
    x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    project(x);
    const double norm = x.norm();
    log_norm += std::log(norm);
    x /= norm;
    if (k >= steps / 4 && (k + 1) % steps_per_cycle == 0) {
      const double tk = static_cast<double>(k + 1) * h;
      sum_t += tk;
      sum_l += log_norm;
      sum_tt += tk * tk;
      sum_tl += tk * log_norm;
      ++count;
    }
  }
  const double c = static_cast<double>(count);
  return (c * sum_tl - sum_t * sum_l) / (c * sum_tt - sum_t * sum_t);
}

TEST(IncommensurateFloquet, CoupledTrainMatchesTheLyapunovExponentOfALongIntegration) {
  const double f_m = kCoupledMeshFrequency;
  const SystemModel train = WithModalDamping(
      TwoMeshBuilder(HandSmoothCore(0.3, 0.05), HandSmoothCore(0.3, 0.0), 0.4, 1.0, kIrrational)
          .Build(),
      0.02);
  FloquetOptions o = FloquetAt(f_m, FloquetMethod::kAuto);
  o.tolerance = 1e-8;
  o.max_approximant_period_meshes = 120;  // approximants of 17, 41 and 99 cycles
  const FloquetResult r = ComputeFloquet(train, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_EQ(r.approximants.size(), 3u);
  EXPECT_EQ(r.approximants.back().period_meshes, 99);
  const double sigma = FlexibleRealParts(r).front();
  const double lyapunov = LyapunovExponent(train, f_m, kLyapunovCycles, 200);
  // The mean (LTI) system's least-damped exponent −ζ ω₁ (modal damping), for comparison.
  SystemWorkspace ws(train, StorageKind::kDense);
  const MatrixX kbar = AssembleMeanStiffness(train, ws);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> mean(kbar, train.DenseMass());
  const double sigma_lti = -0.02 * std::sqrt(mean.eigenvalues()[1]);
  EXPECT_LT(sigma, 0.0);
  EXPECT_EQ(r.verdict, FloquetVerdict::kStable);
  // Measured: σ = −156.666 1/s from the 99-cycle approximant (−156.661 at 17, −156.668 at 41),
  // −156.695 from 500 RK4 cycles (−156.672 from 2000: the time average converges like 1/t).
  EXPECT_NEAR(sigma, lyapunov, 1e-3 * std::abs(lyapunov));
  // The parametric coupling of the two frequencies matters here: the LTI mean system's −ζω₁ is
  // −151.9 1/s, 3 % away, a hundred times the disagreement of the two methods.
  EXPECT_GT(std::abs(sigma - sigma_lti), 0.02 * std::abs(sigma_lti));
  EXPECT_GT(std::abs(sigma - sigma_lti), 50.0 * std::abs(sigma - lyapunov));
}

// ComputeFloquet(model, options) throws InvalidInput whose message contains every `texts`.
void ExpectRefusal(const SystemModel& model, const FloquetOptions& options,
                   const std::vector<std::string>& texts) {
  try {
    (void)ComputeFloquet(model, options);
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    for (const std::string& text : texts) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  }
}

TEST(IncommensurateFloquet, TooSmallABoundAndHillAreRefusedByName) {
  const SystemModel both =
      TwoSeparatePairs(HandSpurWaveCore(1500.0), HandSpurWaveCore(900.0), kIrrational);
  FloquetOptions o = FloquetAt(1300.0, FloquetMethod::kAuto);
  o.max_approximant_period_meshes = 2;  // only 1/1 fits: no convergence study
  ExpectRefusal(both, o, {"max_approximant_period_meshes", "only one"});
  o.max_approximant_period_meshes = 20000;  // beyond the common-period bound of Floquet
  ExpectRefusal(both, o, {"max_approximant_period_meshes"});
  ExpectRefusal(both, FloquetAt(1300.0, FloquetMethod::kHill), {"method: hill"});
}

}  // namespace
}  // namespace geardyn::test
