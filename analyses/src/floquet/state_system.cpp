// MakeStateSystem: validation, rigid-body deflation and the scaled first-order form ż = A(t) z of
// a PeriodicSecondOrderSystem (floquet_system.hpp, steps 1–2).
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/numerics/rigid_modes.hpp"

namespace geardyn::internal {
namespace {

constexpr double kRigidZeroTol = 1e-10;  // as ComputeModes' zero_tol (relative to s)
constexpr double kSymmetryTol = 1e-12;   // relative asymmetry treated as symmetric
constexpr double kNullCheckTol = 1e-8;   // ‖K v‖ ≤ tol·‖K‖ at every sample for a rigid v

bool IsSymmetric(const MatrixX& A) {
  return A.size() == 0 || (A - A.transpose()).norm() <= kSymmetryTol * A.norm();
}

void CheckMatrix(const MatrixX& A, int n, const std::string& what, bool allow_empty) {
  if (allow_empty && A.size() == 0) return;
  GEARDYN_THROW_UNLESS(A.rows() == n && A.cols() == n, what << ": must be " << n << "x" << n
                                                            << ", got " << A.rows() << "x"
                                                            << A.cols());
  GEARDYN_THROW_UNLESS(A.allFinite(), what << ": has non-finite entries");
}

// Fills K, C (n×n) from the steps at time t ∈ [0, T] (the step containing t).
struct StepLookup {
  std::vector<double> ends;  // cumulative end times
  const PeriodicSecondOrderSystem* system = nullptr;
  int Find(double t) const {
    const auto it = std::upper_bound(ends.begin(), ends.end(), t);
    return std::min(static_cast<int>(it - ends.begin()), static_cast<int>(ends.size()) - 1);
  }
};

}  // namespace

MatrixX StateSystem::ToOriginalMonodromy(const MatrixX& phi_z) const {
  const int n = num_dofs, f = n - num_rigid;
  MatrixX S = MatrixX::Zero(2 * n, dim), Sinv = MatrixX::Zero(dim, 2 * n);
  S.block(0, 0, n, f) = basis;
  S.block(n, f, n, f) = omega_s * basis;
  Sinv.block(0, 0, f, n) = basis_inverse;
  Sinv.block(f, n, f, n) = basis_inverse / omega_s;
  MatrixX phi = S * phi_z * Sinv;
  if (num_rigid > 0) {
    // (a, ȧ) ↦ (a + T ȧ, ȧ): q part R(a + Tȧ), q̇ part R ȧ.
    const MatrixX& RI = rigid_inverse;
    phi.block(0, 0, n, n) += rigid * RI;
    phi.block(0, n, n, n) += period_s * rigid * RI;
    phi.block(n, n, n, n) += rigid * RI;
  }
  return phi;
}

StateSystem MakeStateSystem(const PeriodicSecondOrderSystem& system, bool deflate_rigid) {
  const int n = system.num_dofs();
  GEARDYN_THROW_UNLESS(n >= 1, "mass: the system has no DOF");
  CheckMatrix(system.mass, n, "mass", false);
  GEARDYN_THROW_UNLESS(IsSymmetric(system.mass), "mass: must be symmetric");
  const double T = system.period_s;
  GEARDYN_THROW_UNLESS(std::isfinite(T) && T > 0.0, "period_s: must be finite and > 0, got " << T);
  GEARDYN_THROW_UNLESS(
      !system.steps.empty() || system.coefficients || !system.stiffness_harmonics.empty(),
      "system: give steps, coefficients or stiffness_harmonics");
  double total = 0.0;
  for (std::size_t k = 0; k < system.steps.size(); ++k) {
    const PeriodicStep& s = system.steps[k];
    GEARDYN_THROW_UNLESS(
        std::isfinite(s.duration_s) && s.duration_s > 0.0,
        "steps[" << k << "].duration_s: must be finite and > 0, got " << s.duration_s);
    CheckMatrix(s.stiffness, n, "steps[" + std::to_string(k) + "].stiffness", false);
    CheckMatrix(s.damping, n, "steps[" + std::to_string(k) + "].damping", true);
    total += s.duration_s;
  }
  GEARDYN_THROW_UNLESS(system.steps.empty() || std::abs(total - T) <= 1e-9 * T,
                       "steps: durations sum to " << total << " s, not period_s = " << T);
  for (std::size_t m = 0; m < system.stiffness_harmonics.size(); ++m) {
    const MatrixXc& K = system.stiffness_harmonics[m];
    GEARDYN_THROW_UNLESS(K.rows() == n && K.cols() == n,
                         "stiffness_harmonics[" << m << "]: must be " << n << "x" << n);
  }
  for (std::size_t m = 0; m < system.damping_harmonics.size(); ++m) {
    const MatrixXc& C = system.damping_harmonics[m];
    GEARDYN_THROW_UNLESS(C.rows() == n && C.cols() == n,
                         "damping_harmonics[" << m << "]: must be " << n << "x" << n);
  }
  const Eigen::LLT<MatrixX> llt(system.mass);
  GEARDYN_THROW_UNLESS(llt.info() == Eigen::Success, "mass: must be positive definite");
  const MatrixX L = llt.matrixL();

  StateSystem out;
  out.num_dofs = n;
  out.period_s = T;
  {
    // Non-smooth points strictly inside (0, T): the given kinks and the step starts, sorted and
    // merged within 1e-12·T (0 and T end every grid anyway).
    std::vector<double> kinks;
    for (std::size_t k = 0; k < system.kinks_s.size(); ++k) {
      const double t = system.kinks_s[k];
      GEARDYN_THROW_UNLESS(
          std::isfinite(t) && t >= 0.0 && t < T,
          "kinks_s[" << k << "]: must be in [0, period_s = " << T << "), got " << t);
      kinks.push_back(t);
    }
    double start = 0.0;
    for (const PeriodicStep& s : system.steps) {
      kinks.push_back(start);
      start += s.duration_s;
    }
    std::sort(kinks.begin(), kinks.end());
    const double gap = 1e-12 * T;
    for (const double t : kinks) {
      if (t > gap && t < T - gap && (out.kinks.empty() || t - out.kinks.back() > gap)) {
        out.kinks.push_back(t);
      }
    }
  }

  // Samples of K and C: the steps, else 16 callback samples, else the mean harmonic.
  std::vector<MatrixX> Ks, Cs;
  std::vector<double> weights;
  if (!system.steps.empty()) {
    for (const PeriodicStep& s : system.steps) {
      Ks.push_back(s.stiffness);
      Cs.push_back(s.damping.size() ? s.damping : MatrixX::Zero(n, n));
      weights.push_back(s.duration_s / T);
    }
  } else if (system.coefficients) {
    constexpr int kSamples = 16;
    for (int j = 0; j < kSamples; ++j) {
      MatrixX K, C;
      system.coefficients(T * (j + 0.5) / kSamples, &K, &C);
      CheckMatrix(K, n, "coefficients: K(t)", false);
      CheckMatrix(C, n, "coefficients: C(t)", true);
      Ks.push_back(K);
      Cs.push_back(C.size() ? C : MatrixX::Zero(n, n));
      weights.push_back(1.0 / kSamples);
    }
  } else {
    Ks.push_back(system.stiffness_harmonics[0].real());
    Cs.push_back(system.damping_harmonics.empty() ? MatrixX::Zero(n, n)
                                                  : MatrixX(system.damping_harmonics[0].real()));
    weights.push_back(1.0);
  }
  MatrixX K_mean = MatrixX::Zero(n, n), C_mean = MatrixX::Zero(n, n);
  for (std::size_t j = 0; j < Ks.size(); ++j) {
    K_mean += weights[j] * Ks[j];
    C_mean += weights[j] * Cs[j];
  }
  // y-space (M = L Lᵀ, y = Lᵀ q): K̃ = L⁻¹ K L⁻ᵀ.
  auto congruence = [&](const MatrixX& X) {
    MatrixX Y = L.triangularView<Eigen::Lower>().solve(X);
    return MatrixX(L.triangularView<Eigen::Lower>().solve(Y.transpose()).transpose());
  };
  const MatrixX Kt = congruence(K_mean), Ct = congruence(C_mean);
  const double s0 = Kt.diagonal().cwiseAbs().maxCoeff();
  const double omega0 = s0 > 0.0 ? std::sqrt(s0) : 2.0 * std::numbers::pi / T;

  MatrixX W = MatrixX::Identity(n, n), U(n, 0);
  bool symmetric = true;
  for (std::size_t j = 0; j < Ks.size() && symmetric; ++j) {
    symmetric = IsSymmetric(Ks[j]) && IsSymmetric(Cs[j]);
  }
  if (deflate_rigid && symmetric) {
    const MatrixX G = 0.5 * (Kt + Kt.transpose()) + omega0 * 0.5 * (Ct + Ct.transpose());
    const Eigen::SelfAdjointEigenSolver<MatrixX> eig(G);
    const VectorX& ev = eig.eigenvalues();
    const double zero = kRigidZeroTol * std::max(s0, omega0 * Ct.diagonal().cwiseAbs().maxCoeff());
    // Rigid: the one criterion of rigid_modes.hpp on q = L⁻ᵀu, for K̄ and for C̄.
    const VectorX k_scale = RigidScaling(K_mean.diagonal()),
                  c_scale = RigidScaling(C_mean.diagonal());
    auto rigid_at = [&](int k) {
      const VectorX q =
          L.transpose().triangularView<Eigen::Upper>().solve(eig.eigenvectors().col(k));
      return IsRigidBodyPattern(q.dot(K_mean * q), k_scale, q) &&
             IsRigidBodyPattern(q.dot(C_mean * q), c_scale, q);
    };
    int r = 0;
    while (r < n && rigid_at(r)) ++r;
    const bool psd = ev[0] >= -zero;
    if (psd && r > 0 && r < n) {
      // Verify at every sample: K_j R = 0 and C_j R = 0 (q = L⁻ᵀ u).
      const MatrixX Rq = L.transpose().triangularView<Eigen::Upper>().solve(
          MatrixX(eig.eigenvectors().leftCols(r)));
      bool ok = true;
      for (std::size_t j = 0; j < Ks.size() && ok; ++j) {
        ok = (Ks[j] * Rq).norm() <= kNullCheckTol * Ks[j].norm() * Rq.norm() + 1e-300 &&
             (Cs[j] * Rq).norm() <= kNullCheckTol * Cs[j].norm() * Rq.norm() + 1e-300;
      }
      if (ok) {
        U = eig.eigenvectors().leftCols(r);
        W = eig.eigenvectors().rightCols(n - r);
        out.num_rigid = r;
      }
    }
  }
  const int r = out.num_rigid, f = n - r;
  out.dim = 2 * f;
  // X = L⁻ᵀ Y; an empty Y (no rigid mode, or no flexible one) is not solved: Eigen's triangular
  // solve binds a reference to the null data of an empty matrix (UBSan).
  auto solve_lt = [&L](const MatrixX& Y) {
    if (Y.cols() == 0) return MatrixX(Y.rows(), 0);
    return MatrixX(L.transpose().triangularView<Eigen::Upper>().solve(Y));
  };
  out.basis = solve_lt(W);                            // B = L⁻ᵀ W, Bᵀ M B = I
  out.rigid = solve_lt(U);                            // R = L⁻ᵀ U, Rᵀ M R = I
  out.basis_inverse = W.transpose() * L.transpose();  // y = Wᵀ Lᵀ q
  out.rigid_inverse = U.transpose() * L.transpose();
  const MatrixX Kf = W.transpose() * Kt * W;
  const double s = f > 0 ? Kf.diagonal().cwiseAbs().maxCoeff() : 0.0;
  out.omega_s = s > 0.0 ? std::sqrt(s) : 2.0 * std::numbers::pi / T;
  if (r > 0) {
    out.warnings.push_back(std::to_string(r) +
                           " rigid-body mode(s) deflated: 2 multipliers exactly 1 each");
  }
  if (f == 0) return out;

  // A(K, C) = [[0, ω_s I], [−BᵀKB/ω_s, −BᵀCB]].
  const double ws = out.omega_s;
  auto make_state = [f, ws, B = out.basis](const MatrixX& K, const MatrixX& C, MatrixX* A) {
    A->setZero(2 * f, 2 * f);
    A->block(0, f, f, f).diagonal().setConstant(ws);
    A->block(f, 0, f, f).noalias() = -(B.transpose() * K * B) / ws;
    if (C.size() != 0) A->block(f, f, f, f).noalias() = -(B.transpose() * C * B);
  };
  for (const PeriodicStep& step : system.steps) {
    MatrixX A;
    make_state(step.stiffness, step.damping, &A);
    out.step_durations.push_back(step.duration_s);
    out.step_matrices.push_back(std::move(A));
  }
  // Sparse copies for the matrix-free expm action (kArpackMonodromy): only when B = L⁻ᵀ is
  // diagonal (M diagonal, no rigid mode), so that A_k keeps the sparsity of K_k and C_k.
  const bool diagonal_mass =
      r == 0 && MatrixX(system.mass.triangularView<Eigen::StrictlyLower>()).isZero(0.0) &&
      MatrixX(system.mass.triangularView<Eigen::StrictlyUpper>()).isZero(0.0);
  if (diagonal_mass && !out.step_matrices.empty()) {
    constexpr double kMaxDensity = 0.25;
    for (const MatrixX& A : out.step_matrices) {
      SparseMatrix S = A.sparseView(0.0, 0.0);
      if (static_cast<double>(S.nonZeros()) > kMaxDensity * static_cast<double>(A.size())) {
        out.sparse_step_matrices.clear();
        break;
      }
      S.makeCompressed();
      out.sparse_step_matrices.push_back(std::move(S));
    }
  }
  out.companion = true;  // both forms of evaluate below set [[0, ω_s I], [X, Y]]
  if (system.coefficients) {
    // make_state with the products into kept buffers (no allocation per call: Magnus evaluates
    // A(t) three times per step).
    struct Buffers {
      MatrixX K, C, BtX;
    };
    auto buffers = std::make_shared<Buffers>();
    out.evaluate = [buffers, f, ws, B = out.basis, coefficients = system.coefficients](double t,
                                                                                       MatrixX* A) {
      Buffers& b = *buffers;
      coefficients(t, &b.K, &b.C);
      A->setZero(2 * f, 2 * f);
      A->block(0, f, f, f).diagonal().setConstant(ws);
      b.BtX.noalias() = B.transpose() * b.K;
      A->block(f, 0, f, f).noalias() = b.BtX * B;
      A->block(f, 0, f, f) *= -1.0 / ws;
      if (b.C.size() != 0) {
        b.BtX.noalias() = B.transpose() * b.C;
        A->block(f, f, f, f).noalias() = -(b.BtX * B);
      }
    };
  } else if (!system.steps.empty()) {
    auto lookup = std::make_shared<StepLookup>();
    double end = 0.0;
    for (double d : out.step_durations) lookup->ends.push_back(end += d);
    out.evaluate = [lookup, matrices = out.step_matrices](double t, MatrixX* A) {
      *A = matrices[lookup->Find(t)];
    };
  }
  for (std::size_t m = 0; m < system.stiffness_harmonics.size(); ++m) {
    const MatrixXc Bc = out.basis.cast<std::complex<double>>();
    MatrixXc A = MatrixXc::Zero(2 * f, 2 * f);
    if (m == 0) A.block(0, f, f, f).diagonal().setConstant(ws);
    A.block(f, 0, f, f) = -(Bc.transpose() * system.stiffness_harmonics[m] * Bc) / ws;
    if (m < system.damping_harmonics.size()) {
      A.block(f, f, f, f) = -(Bc.transpose() * system.damping_harmonics[m] * Bc);
    }
    out.harmonics.push_back(std::move(A));
  }
  return out;
}

}  // namespace geardyn::internal
