/// @file
/// @brief Exact integration of piecewise-linear laws (nonlinear_hb.hpp, "Exact integration")
/// against independent computations: the force harmonics against the sampled AFT with 2¹⁵–2¹⁶
/// samples and the switch correction (its error O(S⁻³) ≈ 1e-13), including a grazing contact
/// narrower than one bracketing interval; solutions against the same dense AFT; the refined
/// extremes against a dense direct synthesis of u(θ); Newton from the contact guess inside the
/// bistable band (Powell's hybrid fallback) against the dense AFT residual; and the input
/// errors of the exact mode.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "analyses/nonlinear_hb/bk_parameter_sets.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"
#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

/// Options of the independent reference: sampled AFT, S = max(64, 4096 H), kink correction.
NhbOptions DenseAft(int H) {
  NhbOptions o;
  o.harmonics = H;
  o.force_integration = NhbForceIntegration::kSampled;
  o.samples_per_harmonic = std::max(4096, 32768 / H);
  o.switch_correction = true;
  o.stability = NhbStabilityMethod::kNone;
  return o;
}

NhbOptions Exact(int H) {
  NhbOptions o;
  o.harmonics = H;
  o.force_integration = NhbForceIntegration::kExact;
  o.stability = NhbStabilityMethod::kNone;
  return o;
}

/// x with u(θ) = Σ given complex harmonics (U_0 real).
VectorX Unknowns(int H, const std::vector<std::complex<double>>& harmonics) {
  VectorX x = VectorX::Zero(2 * H + 1);
  x[0] = harmonics[0].real();
  for (size_t k = 1; k < harmonics.size(); ++k) {
    x[static_cast<Eigen::Index>(2 * k - 1)] = harmonics[k].real();
    x[static_cast<Eigen::Index>(2 * k)] = harmonics[k].imag();
  }
  return x;
}

double ResidualGap(const NhbProblem& problem, int H, const VectorX& x, double omega) {
  NhbSolver exact(problem, Exact(H), H), dense(problem, DenseAft(H), H);
  VectorX re, rd;
  exact.Evaluate(x, omega, &re, nullptr, nullptr);
  dense.Evaluate(x, omega, &rd, nullptr, nullptr);
  return (re - rd).lpNorm<Eigen::Infinity>();
}

TEST(NonlinearHbExactIntegration, ForceHarmonicsMatchDenseAftWithManyCrossings) {
  // Both flanks, parametric stiffness with a phase, and a state that crosses ±1 six times.
  ClearanceOscillatorParameters p;
  p.alpha = 0.3;
  p.back_contact = true;
  const NhbProblem problem = MakeClearanceOscillator(p);
  const int H = 8;
  const VectorX x = Unknowns(H, {0.2, {0.9, 0.3}, {0.0, -0.2}, {0.35, 0.1}, {0.0, 0.05}});
  EXPECT_LT(ResidualGap(problem, H, x, 0.8), 1e-11);
  // Period-2 base (κ̃(θ) = κ(2θ)): the same comparison.
  NhbOptions exact = Exact(H), dense = DenseAft(H);
  exact.period_multiple = dense.period_multiple = 2;
  NhbSolver se(problem, exact, H), sd(problem, dense, H);
  VectorX re, rd;
  se.Evaluate(x, 0.8, &re, nullptr, nullptr);
  sd.Evaluate(x, 0.8, &rd, nullptr, nullptr);
  EXPECT_LT((re - rd).lpNorm<Eigen::Infinity>(), 1e-11);
}

TEST(NonlinearHbExactIntegration, GrazingContactNarrowerThanABracketIsIntegrated) {
  // u = 0.5 + 2·0.25 cos(θ − φ): max 1 + 1e-4… above the front gap b = 1 for a θ-width of
  // ≈ 0.04, less than the bracketing interval 2π/64 ≈ 0.098, centred between two samples.
  const ClearanceOscillatorParameters p = testing::BkSingleSidedSet();
  const NhbProblem problem = MakeClearanceOscillator(p);
  const int H = 4;
  const double h = 2 * kPi / 64;
  for (const double excess : {1e-4, 1e-6}) {
    const VectorX x = Unknowns(H, {0.5 + excess, std::polar(0.25, -0.5 * h)});
    NhbSolver exact(problem, Exact(H), H);
    VectorX re;
    exact.Evaluate(x, 0.9, &re, nullptr, nullptr);
    // Closed form of the mean force (1/2π)∫κ(θ)(u − 1)₊ dθ: u − 1 ≈ ε − (θ − θ₀)²/4 near the
    // peak θ₀ = −h/2, so (1/2π) κ(θ₀) (8/3) ε^{3/2} (relative corrections O(ε) and O(α w²)).
    const double kappa_peak = 1.0 + p.alpha * std::cos(-0.5 * h);
    const double mean_force = kappa_peak * (8.0 / 3.0) * std::pow(excess, 1.5) / (2 * kPi);
    // Harmonic 0 of the residual is N_0 − F_m (Z_0 = K = 0).
    EXPECT_NEAR(re[0] + p.mean_force, mean_force, 1e-3 * mean_force) << "ε = " << excess;
    EXPECT_LT(ResidualGap(problem, H, x, 0.9), 1e-12 + 1e-6 * mean_force) << "ε = " << excess;
  }
}

/// Both solutions polished from xe with a Newton tolerance of 1e-13 (so that the comparison
/// is not limited by the default 1e-10): they agree to the dense AFT's own error.
void ExpectDenseAftLimit(const NhbProblem& problem, int H, const VectorX& x, double omega) {
  NhbOptions exact_options = Exact(H), dense_options = DenseAft(H);
  exact_options.newton_tolerance = dense_options.newton_tolerance = 1e-13;
  NhbSolver exact(problem, exact_options, H), dense(problem, dense_options, H);
  VectorX xe = x, xd = x;
  Status status;
  double rn;
  exact.Newton(xe, omega, &status, &rn);
  ASSERT_EQ(status, Status::kSuccess);
  dense.Newton(xd, omega, &status, &rn);
  ASSERT_EQ(status, Status::kSuccess);
  EXPECT_LT((xe - xd).lpNorm<Eigen::Infinity>(), 1e-11) << "Ω = " << omega;
}

TEST(NonlinearHbExactIntegration, SolutionsAreTheDenseAftLimit) {
  const int H = 12;
  {
    // Contact-loss branch of the single-sided set at Ω = 1.0, from the contact guess.
    const NhbProblem problem = MakeClearanceOscillator(testing::BkSingleSidedSet());
    NhbSolver exact(problem, Exact(H), H);
    VectorX xe = exact.ContactGuess(1.0);
    Status status;
    double rn;
    exact.Newton(xe, 1.0, &status, &rn);
    ASSERT_EQ(status, Status::kSuccess);
    NhbPoint point;
    exact.Describe(xe, 1.0, point);
    EXPECT_LT(point.minimum[0], 1.0) << "contact loss expected";
    ExpectDenseAftLimit(problem, H, xe, 1.0);
  }
  {
    // Back-contact orbit (front contact → gap → back contact → gap) of the back-contact set of
    // bk_jumps_test, reached by continuation from full contact at Ω = 1.6.
    const NhbProblem problem = MakeClearanceOscillator(testing::BkBackContactSet());
    const NhbCurve curve =
        TraceNonlinearHarmonicBalance(problem, Exact(H), testing::BkBackContactTrace());
    ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
    const NhbPoint& last = curve.points.back();
    ASSERT_LT(last.minimum[0], -1.0) << "not a back-contact orbit";
    const VectorX xe = testing::PointUnknowns(last);
    ExpectDenseAftLimit(problem, H, xe, last.omega);
  }
}

TEST(NonlinearHbExactIntegration, ExtremesAreThoseOfTheTrigonometricPolynomial) {
  const NhbProblem problem = MakeClearanceOscillator(testing::BkSingleSidedSet());
  const int H = 6;
  const VectorX x = Unknowns(H, {1.1, {0.05, 0.02}, {-0.03, 0.01}, {0.0, 0.004}, {0.002, 0.0}});
  NhbSolver solver(problem, Exact(H), H);
  NhbPoint point;
  solver.Describe(x, 0.9, point);
  // Direct synthesis on 200 001 points, refined by golden-section-free local parabola: the
  // dense grid alone is within (2π/2e5)²·max|u″|/8 ≈ 1e-11 of the extremes.
  double lo = 1e300, hi = -1e300;
  for (int s = 0; s <= 200000; ++s) {
    const double theta = 2 * kPi * s / 200000;
    double u = x[0];
    for (int k = 1; k <= H; ++k) {
      u += 2 * (x[2 * k - 1] * std::cos(k * theta) - x[2 * k] * std::sin(k * theta));
    }
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_NEAR(point.maximum[0], hi, 1e-10);
  EXPECT_NEAR(point.minimum[0], lo, 1e-10);
  EXPECT_GE(point.maximum[0], hi - 1e-15);  // refined: never below the dense grid's maximum
  EXPECT_NEAR(point.peak_to_peak[0], hi - lo, 2e-10);
}

TEST(NonlinearHbExactIntegration, NewtonFromTheContactGuessConvergesInTheBistableBand) {
  // Inside the band between the folds (≈ 0.76–0.90 plus the contact-loss branch up to 1.0) the
  // damped Newton from the linear contact guess stalls near grazing; Powell's hybrid method
  // takes over. The solutions are checked against the dense-AFT residual.
  const NhbProblem problem = MakeClearanceOscillator(testing::BkSingleSidedSet());
  const int H = 16;
  for (const double omega : {0.85, 0.9, 0.95, 0.97}) {
    NhbOptions o = Exact(H);
    const NhbSolveResult r = SolveNonlinearHarmonicBalance(problem, omega, o);
    ASSERT_TRUE(r.summary.ok()) << "Ω = " << omega << ": " << r.summary.BriefReport();
    const VectorX x = testing::PointUnknowns(r.point);
    NhbSolver dense(problem, DenseAft(H), H);
    VectorX rd;
    dense.Evaluate(x, omega, &rd, nullptr, nullptr);
    EXPECT_LT(rd.lpNorm<Eigen::Infinity>(), 1e-9) << "Ω = " << omega;
  }
}

/// A law without the piecewise-linear form (same force as the clearance law).
class OpaqueLaw final : public NhbNonlinearLaw {
 public:
  int num_coordinates() const override { return 1; }
  void Evaluate(const MatrixX& u, const VectorX& phase, MatrixX& force,
                MatrixX& jacobian) const override {
    inner_.Evaluate(u, phase, force, jacobian);
  }
  void ContactBranch(MatrixX& stiffness, VectorX& offset) const override {
    inner_.ContactBranch(stiffness, offset);
  }

 private:
  NhbClearanceLaw inner_{VectorX::Ones(1), VectorX::Zero(1), VectorX::Zero(1), VectorX::Ones(1),
                         VectorX::Ones(1)};
};

/// A law whose form has the wrong number of coordinates.
class BadFormLaw final : public NhbNonlinearLaw {
 public:
  int num_coordinates() const override { return 1; }
  void Evaluate(const MatrixX&, const VectorX&, MatrixX&, MatrixX&) const override {}
  void ContactBranch(MatrixX& stiffness, VectorX& offset) const override {
    stiffness = MatrixX::Ones(1, 1);
    offset = VectorX::Zero(1);
  }
  bool PiecewiseLinearForm(NhbPiecewiseLinearForm* form) const override {
    form->modulation = MatrixXc::Ones(2, 1);
    form->slope = VectorX::Zero(2);
    form->offset = VectorX::Zero(2);
    form->ramp_points.assign(2, {});
    form->ramp_slopes.assign(2, {});
    return true;
  }
};

TEST(NonlinearHbExactIntegration, ExactModeNeedsAWellFormedPiecewiseLinearForm) {
  NhbProblem problem = MakeClearanceOscillator(testing::BkSingleSidedSet());
  problem.law = std::make_shared<OpaqueLaw>();
  EXPECT_THROWS_MESSAGE(NhbSolver(problem, Exact(4), 4), InvalidInput,
                        "force_integration: exact integration needs a law with a "
                        "piecewise-linear form");
  // kAuto falls back to the sampled AFT for such a law.
  NhbOptions automatic = Exact(4);
  automatic.force_integration = NhbForceIntegration::kAuto;
  EXPECT_NO_THROW(NhbSolver(problem, automatic, 4));
  problem.law = std::make_shared<BadFormLaw>();
  EXPECT_THROWS_MESSAGE(NhbSolver(problem, Exact(4), 4), InvalidInput,
                        "piecewise-linear form sizes do not match");
}

}  // namespace
}  // namespace geardyn
