/// @file
/// @brief The pole–residue condensation (nonlinear_hb.hpp, "Condensation of the linear DOFs")
/// against the general path, an LU of every D_k (NhbCondensation::kDirect), on the
/// Kahraman–Blankenship rig with a 10-slice mesh (9 condensed DOFs, 2 nonlinear coordinates):
/// residual, Jacobian and ∂R/∂Ω at frequencies below, at and above the mesh resonance; ∂R/∂Ω
/// against central differences; the linear response against a dense solve written here; and a
/// traced curve's folds.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <complex>
#include <numbers>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "kb_rig_fixture.hpp"

namespace geardyn {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Round-off of the partial fractions: ~ε·cond(V) (V the eigenvectors of the balanced state
// matrix, rcond ≥ 1e-6 required) times the H-fold sums; the direct LU errs by ε·cond(D_k).
constexpr double kPathTol = 1e-9;
// Richardson-extrapolated central differences in Ω with a relative step 1e-4: truncation
// O(h⁴) (the plain central difference at 1e-5 erred by 1.4e-6 at 700 Hz, where harmonic 5 is
// near the mesh mode), cancellation ~1e-16/1e-4.
constexpr double kDifferenceTol = 1e-8;

/// x near the contact branch with every harmonic excited (contact loss at large k).
VectorX TestState(NhbSolver& solver, double omega) {
  VectorX x = solver.ContactGuess(omega);
  const double mean = x[0];
  for (Eigen::Index i = 2; i < x.size(); ++i) {
    const double di = static_cast<double>(i);
    x[i] += 0.3 * mean * std::sin(1.7 * di) / (1.0 + 0.2 * di);
  }
  return x;
}

double Relative(const MatrixX& a, const MatrixX& b) {
  return (a - b).lpNorm<Eigen::Infinity>() / b.lpNorm<Eigen::Infinity>();
}

TEST(PoleResidueCondensation, ResidualJacobianAndOmegaDerivativeEqualTheDirectLu) {
  const SystemModel model = testing::KbRigSliceModel();
  const SystemNhbProblem sp = MakeSystemNhbProblem(model);
  ASSERT_FALSE(sp.problem.IsUncondensed());
  const int H = 12;
  NhbOptions modal_options;
  modal_options.period_multiple = sp.period_meshes;
  NhbOptions direct_options = modal_options;
  direct_options.condensation = NhbCondensation::kDirect;
  NhbSolver modal(sp.problem, modal_options, H);
  NhbSolver direct(sp.problem, direct_options, H);
  // Below the mesh mode (3379 Hz, all loaded), at it, above it, and where harmonics 2–12 sweep
  // the bearing modes.
  for (double hz : {700.0, 1475.0, 3379.0, 6000.0}) {
    SCOPED_TRACE(hz);
    const double omega = kTwoPi * hz;
    const VectorX x = TestState(direct, omega);
    VectorX r_modal, r_direct, d_modal, d_direct;
    MatrixX j_modal, j_direct;
    modal.Evaluate(x, omega, &r_modal, &j_modal, &d_modal);
    direct.Evaluate(x, omega, &r_direct, &j_direct, &d_direct);
    EXPECT_LT(Relative(r_modal, r_direct), kPathTol);
    EXPECT_LT(Relative(j_modal, j_direct), kPathTol);
    EXPECT_LT(Relative(d_modal, d_direct), kPathTol);
    EXPECT_NEAR(modal.ResidualTolerance(omega) / direct.ResidualTolerance(omega), 1.0, kPathTol);

    // ∂R/∂Ω against central differences of the residual (the direct path's own derivative is
    // the same formula, so this checks both against an independent truth).
    auto central = [&](double h) {
      VectorX r_plus, r_minus;
      modal.Evaluate(x, omega + h, &r_plus, nullptr, nullptr);
      modal.Evaluate(x, omega - h, &r_minus, nullptr, nullptr);
      return VectorX((r_plus - r_minus) / (2.0 * h));
    };
    // Richardson: (4 D(h/2) − D(h))/3 errs by O(h⁴).
    const double h = 1e-4 * omega;
    const VectorX difference = (4.0 * central(0.5 * h) - central(h)) / 3.0;
    EXPECT_LT(Relative(d_modal, difference), kDifferenceTol);

    // The reported 1/cond of the condensation is a lower bound of Eigen's estimate (which
    // over-estimates 1/cond), within the factor of the bound's sum over 2N poles.
    NhbPoint p_modal, p_direct;
    modal.Describe(x, omega, p_modal);
    direct.Describe(x, omega, p_direct);
    EXPECT_LE(p_modal.condensation_rcond, p_direct.condensation_rcond * (1.0 + 1e-12));
    EXPECT_GT(p_modal.condensation_rcond, 1e-3 * p_direct.condensation_rcond);
  }
}

TEST(PoleResidueCondensation, LinearResponseEqualsDenseSolve) {
  using C = std::complex<double>;
  const SystemModel model = testing::KbRigSliceModel();
  const SystemNhbProblem sp = MakeSystemNhbProblem(model);
  const NhbProblem& p = sp.problem;
  const int H = 8;
  NhbOptions options;
  options.period_multiple = sp.period_meshes;
  NhbSolver solver(p, options, H);
  const Eigen::Index N = p.mass.rows();
  MatrixXc b(N, H + 1);
  for (Eigen::Index i = 0; i < N; ++i) {
    const double di = static_cast<double>(i);
    for (int k = 0; k <= H; ++k)
      b(i, k) = C(std::cos(1.3 * di + k), k == 0 ? 0.0 : std::sin(di - k));
  }
  for (double hz : {500.0, 3379.0}) {
    const double omega = kTwoPi * hz;
    const MatrixXc q = solver.SolveLinear(omega, b);
    const double w = omega / options.period_multiple;
    for (int k = 0; k <= H; ++k) {
      // D_k = −k²ω²M + ikωC + K, solved here by a full-pivoting LU.
      const MatrixXc D = (-double(k * k) * w * w) * p.mass.cast<C>() +
                         C(0.0, k * w) * p.damping.cast<C>() + p.stiffness.cast<C>();
      const VectorXc expected = D.fullPivLu().solve(b.col(k));
      EXPECT_LT((q.col(k) - expected).norm() / expected.norm(), kPathTol) << hz << " Hz, k " << k;
    }
  }
}

TEST(PoleResidueCondensation, TracedFoldsEqualTheDirectLu) {
  // The rig's super-harmonic pair of folds (up 1064.43 Hz, down 1010.29 Hz) traced on both
  // paths: the folds agree to the fold tolerance.
  const SystemModel model = testing::KbRigSliceModel();
  SystemNhbOptions o;
  o.hb.harmonics = 16;
  o.start_hz = 950.0;
  o.end_hz = 1150.0;
  o.continuation.max_omega_step = kTwoPi * 2.0;
  o.continuation.initial_step = 0.005;
  o.continuation.fold_tolerance = 1e-9;
  SystemNhbOptions direct = o;
  direct.hb.condensation = NhbCondensation::kDirect;
  const SystemNhbCurve a = TraceSystemNonlinearHb(model, o);
  const SystemNhbCurve b = TraceSystemNonlinearHb(model, direct);
  ASSERT_TRUE(a.summary.ok()) << a.summary.message;
  ASSERT_TRUE(b.summary.ok()) << b.summary.message;
  ASSERT_EQ(a.fold_frequencies_hz.size(), 2u);
  ASSERT_EQ(b.fold_frequencies_hz.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const double tol = a.fold_errors_hz[i] + b.fold_errors_hz[i] + 1e-9 * a.fold_frequencies_hz[i];
    EXPECT_NEAR(a.fold_frequencies_hz[i], b.fold_frequencies_hz[i], tol);
  }
  EXPECT_NEAR(a.points.back().meshes[0].rms_dte, b.points.back().meshes[0].rms_dte,
              1e-8 * b.points.back().meshes[0].rms_dte);
}

}  // namespace
}  // namespace geardyn
