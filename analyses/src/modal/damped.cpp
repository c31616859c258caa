// Damping path of ComputeModes: classification of C against M and K̄ (Rayleigh / classical /
// non-proportional) and the damped complex modes of the dense state-space problem.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <vector>

#include "modal/modal_internal.hpp"

namespace geardyn::internal {
namespace {

// A zero of the state matrix that belongs to a free rigid-body mode is defective (q = a + b t), so
// a backward-stable eigensolver finds it only to ≈ √ε·‖A‖: |λ| ≤ kDampedZeroTol·ω_s is zero.
constexpr double kDampedZeroTol = 1e-6;

double FrobeniusDot(const SparseMatrix& a, const SparseMatrix& b) {
  return a.cwiseProduct(b).sum();
}

// X ↦ L⁻¹ X L⁻ᵀ with M = L Lᵀ.
MatrixX CongruenceByInverseCholesky(const Eigen::LLT<MatrixX>& llt, MatrixX X) {
  llt.matrixL().solveInPlace<Eigen::OnTheLeft>(X);
  llt.matrixU().solveInPlace<Eigen::OnTheRight>(X);
  return X;
}

bool DampedModeLess(const DampedMode& a, const DampedMode& b) {
  if (a.natural_frequency_hz != b.natural_frequency_hz) {
    return a.natural_frequency_hz < b.natural_frequency_hz;
  }
  return a.frequency_hz < b.frequency_hz;
}

}  // namespace

DampedMode MakeDampedMode(std::complex<double> lambda) {
  DampedMode mode;
  mode.eigenvalue = lambda;
  const double magnitude = std::abs(lambda);
  mode.frequency_hz = std::abs(lambda.imag()) / (2.0 * M_PI);
  mode.natural_frequency_hz = magnitude / (2.0 * M_PI);
  mode.damping_ratio = magnitude > 0.0 ? -lambda.real() / magnitude : 0.0;
  return mode;
}

void ClassifyDamping(const MeanSystem& sys, const ModalOptions& options, const MatrixX& shapes,
                     const VectorX& eigenvalues, ModalResult* result) {
  result->damping_kind = DampingKind::kNone;
  result->rayleigh_alpha = 0.0;
  result->rayleigh_beta = 0.0;
  if (!sys.has_damping) return;
  const double tol = options.proportional_damping_tol;

  // Rayleigh: least squares C ≈ αM + βK̄ in the Frobenius norm, on normalized M̂, K̂.
  const double norm_m = sys.M.norm(), norm_k = sys.K.norm(), norm_c = sys.C.norm();
  Eigen::Matrix2d gram;
  Eigen::Vector2d rhs;
  const SparseMatrix m_hat = sys.M / norm_m;
  const SparseMatrix k_hat = norm_k > 0.0 ? SparseMatrix(sys.K / norm_k) : SparseMatrix(sys.K);
  gram << 1.0, FrobeniusDot(m_hat, k_hat), FrobeniusDot(m_hat, k_hat), FrobeniusDot(k_hat, k_hat);
  rhs << FrobeniusDot(m_hat, sys.C), FrobeniusDot(k_hat, sys.C);
  const Eigen::Vector2d ab = gram.completeOrthogonalDecomposition().solve(rhs);
  const double alpha = ab(0) / norm_m, beta = norm_k > 0.0 ? ab(1) / norm_k : 0.0;
  const SparseMatrix residual = sys.C - alpha * sys.M - beta * sys.K;
  if (residual.norm() <= tol * norm_c) {
    result->damping_kind = DampingKind::kRayleigh;
    result->rayleigh_alpha = alpha;
    result->rayleigh_beta = beta;
    return;
  }

  const int n = static_cast<int>(sys.M.rows());
  if (n <= kDenseDampingTestMaxDofs) {
    // Classical (Caughey & O'Kelly 1965): K̃C̃ = C̃K̃ with K̃ = L⁻¹K̄L⁻ᵀ, C̃ = L⁻¹CL⁻ᵀ.
    const Eigen::LLT<MatrixX> llt{MatrixX(sys.M)};
    const MatrixX kt = CongruenceByInverseCholesky(llt, MatrixX(sys.K));
    const MatrixX ct = CongruenceByInverseCholesky(llt, MatrixX(sys.C));
    const MatrixX product = kt * ct;
    const double commutator = (product - product.transpose()).norm();
    if (commutator <= tol * kt.norm() * ct.norm()) {
      result->damping_kind = DampingKind::kClassical;
      return;
    }
  } else if (shapes.cols() > 0) {
    // Large system: the computed modes must diagonalize C between distinct frequencies.
    const MatrixX modal = shapes.transpose() * (sys.C * shapes);
    const double diag_max = modal.diagonal().cwiseAbs().maxCoeff();
    double worst = 0.0;
    for (Eigen::Index i = 0; i < modal.rows(); ++i) {
      for (Eigen::Index j = 0; j < i; ++j) {
        const double gap = std::abs(eigenvalues(i) - eigenvalues(j));
        if (gap <= options.multiplicity_rel_tol *
                       std::max(std::abs(eigenvalues(i)), std::abs(eigenvalues(j)))) {
          continue;  // a repeated eigenspace: any C-invariant basis of it is as good
        }
        worst = std::max(worst, std::abs(modal(i, j)));
      }
    }
    if (worst <= tol * diag_max) {
      result->damping_kind = DampingKind::kClassical;
      result->summary.warnings.push_back(
          "damping found classical on the computed modes only (n > 2000: no full commutation "
          "test)");
      return;
    }
  }
  result->damping_kind = DampingKind::kNonProportional;
  result->summary.warnings.push_back(
      "damping is not proportional (C is neither αM + βK̄ nor diagonalized by the undamped "
      "modes): the modes are complex; see damped_modes (compute_damped)");
}

std::vector<DampedMode> ComputeDampedModes(const MeanSystem& sys, double spectrum_scale,
                                           int num_rigid_body_modes, Summary* summary) {
  const Eigen::Index n = sys.M.rows();
  const double omega_s = std::sqrt(spectrum_scale > 0.0 ? spectrum_scale : 1.0);
  const Eigen::LLT<MatrixX> llt{MatrixX(sys.M)};
  // ẋ = A x, x = [y; ẏ/ω_s], y = Lᵀq: A = [[0, ω_s I], [−K̃/ω_s, −C̃]].
  MatrixX A = MatrixX::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).diagonal().setConstant(omega_s);
  A.bottomLeftCorner(n, n) = -CongruenceByInverseCholesky(llt, MatrixX(sys.K)) / omega_s;
  A.bottomRightCorner(n, n) = -CongruenceByInverseCholesky(llt, MatrixX(sys.C));
  const Eigen::EigenSolver<MatrixX> solver(A, /*computeEigenvectors=*/false);
  summary->counters["damped_state_dimension"] = static_cast<long>(2 * n);
  if (solver.info() != Eigen::Success || !solver.eigenvalues().allFinite()) {
    if (summary->ok()) {
      summary->status =
          solver.info() != Eigen::Success ? Status::kNotConverged : Status::kNumericalIssue;
      summary->message =
          "the damped state-space eigen solve (real Schur of the 2n×2n state "
          "matrix) failed; no damped modes";
    }
    return {};
  }
  std::vector<std::complex<double>> values(solver.eigenvalues().data(),
                                           solver.eigenvalues().data() + 2 * n);
  // The defective zeros of free modes: at most 2r, the smallest, within √ε-level of 0.
  std::vector<std::size_t> by_magnitude(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) by_magnitude[i] = i;
  std::sort(by_magnitude.begin(), by_magnitude.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(values[a]) < std::abs(values[b]);
  });
  int zeros = 0;
  for (std::size_t i = 0; i < by_magnitude.size() && zeros < 2 * num_rigid_body_modes; ++i) {
    std::complex<double>& v = values[by_magnitude[i]];
    if (std::abs(v) > kDampedZeroTol * omega_s) break;
    v = 0.0;
    ++zeros;
  }
  std::vector<DampedMode> modes;
  // Two zeros (position and velocity of a free mode) count as one mode, like a conjugate pair.
  for (int z = 0; z < (zeros + 1) / 2; ++z) modes.push_back(MakeDampedMode(0.0));
  // A mode C does not damp (one beyond a scene's modal_ratios) has Re λ = 0 exactly; the real
  // Schur finds it to its backward error (geared-shafts read ζ = −3.4e-16 … 1.7e-14). Below the
  // bound 2n·ε·‖A‖_F of the 2n×2n state matrix (Golub & Van Loan §7.5.6, QR algorithm; a
  // well-conditioned eigenvalue moves by no more) Re λ is round-off: the mode is undamped, ζ = 0.
  const double round_off =
      static_cast<double>(2 * n) * std::numeric_limits<double>::epsilon() * A.norm();
  for (std::complex<double> v : values) {
    if (v == 0.0 || v.imag() < 0.0) continue;  // Eigen returns exact conjugates: keep Im ≥ 0
    if (v.imag() > 0.0 && std::abs(v.real()) <= round_off) v = {0.0, v.imag()};
    modes.push_back(MakeDampedMode(v));
  }
  std::sort(modes.begin(), modes.end(), DampedModeLess);
  return modes;
}

std::vector<DampedMode> DampedModesFromModalRatios(const VectorX& eigenvalues,
                                                   const VectorX& modal_damping_ratios) {
  std::vector<DampedMode> modes;
  for (Eigen::Index k = 0; k < eigenvalues.size(); ++k) {
    const double omega = std::sqrt(std::max(eigenvalues(k), 0.0));
    const double zeta = modal_damping_ratios(k);
    if (omega == 0.0) {
      modes.push_back(MakeDampedMode(0.0));
    } else if (zeta < 1.0) {
      modes.push_back(MakeDampedMode({-zeta * omega, omega * std::sqrt(1.0 - zeta * zeta)}));
    } else {  // overdamped: two real roots −ω(ζ ∓ √(ζ² − 1))
      const double root = std::sqrt(zeta * zeta - 1.0);
      modes.push_back(MakeDampedMode(-omega * (zeta - root)));
      modes.push_back(MakeDampedMode(-omega * (zeta + root)));
    }
  }
  std::sort(modes.begin(), modes.end(), DampedModeLess);
  return modes;
}

}  // namespace geardyn::internal
