/// @file
/// @brief Condensed linear part of the nonlinear HB per harmonic (see nonlinear_hb.hpp):
/// Z_k = (P D_k⁻¹ Pᵀ)⁻¹, F̃_k = Z_k P D_k⁻¹ F_k with D_k = −k²ω²M + ikωC + K, ω = Ω/p, and their
/// analytic Ω-derivatives (dD_k/dΩ = (−2k²ωM + ikC)/p; dZ = Z P D⁻¹ dD D⁻¹ Pᵀ Z), either by an
/// LU of every D_k (direct) or from the pole–residue form of D(s)⁻¹ built once ("Condensation
/// of the linear DOFs"). The smallest estimated reciprocal condition number of the two
/// inversions is kept (linear_rcond).
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>

#include "geardyn/common/check.hpp"
#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {
namespace {

/// Smallest Eigen rcond of the eigenvector matrix V for the pole–residue form: its round-off
/// is ~ε/rcond(V) relative, ≤ 1e-10 here; below, the direct LU.
constexpr double kMinEigenvectorRcond = 1e-6;
/// Smallest rcond of M (its Cholesky factor inverts M in A and in the residues).
constexpr double kMinMassRcond = 1e-12;

}  // namespace

bool NhbSolver::Impl::BuildPoleResidueForm() {
  using C = std::complex<double>;
  const int N = dofs;
  const MatrixX& M = problem.mass;
  Eigen::LDLT<MatrixX> mass_ldlt(M);
  if (mass_ldlt.info() != Eigen::Success || !mass_ldlt.isPositive() ||
      !(mass_ldlt.rcond() >= kMinMassRcond)) {
    return false;
  }
  // y = [q; q̇/ω₀] balances A (ω₀² = ‖K‖/‖M‖, the size of the eigenvalues): A' = S A S⁻¹ =
  // [0 ω₀I; −M⁻¹K/ω₀ −M⁻¹C], S = diag(I, I/ω₀), so D(s)⁻¹ = E₁ᵀ(sI − A')⁻¹E₂ M⁻¹/ω₀.
  const double mass_norm = M.cwiseAbs().colwise().sum().maxCoeff();
  const double stiffness_norm = problem.stiffness.cwiseAbs().colwise().sum().maxCoeff();
  const double w0 =
      stiffness_norm > 0 && mass_norm > 0 ? std::sqrt(stiffness_norm / mass_norm) : 1.0;
  MatrixX A = MatrixX::Zero(2 * N, 2 * N);
  A.topRightCorner(N, N).diagonal().setConstant(w0);
  A.bottomLeftCorner(N, N) = -mass_ldlt.solve(problem.stiffness) / w0;
  A.bottomRightCorner(N, N) = -mass_ldlt.solve(problem.damping);
  if (!A.allFinite()) return false;
  Eigen::EigenSolver<MatrixX> es(A, true);
  if (es.info() != Eigen::Success) return false;
  const MatrixXc V = es.eigenvectors();
  const Eigen::PartialPivLU<MatrixXc> vlu(V);
  if (!(vlu.rcond() >= kMinEigenvectorRcond)) return false;
  const MatrixXc Vinv = vlu.inverse();
  // w_rᵀ = (row r of V⁻¹, bottom half) M⁻¹ / ω₀ (M symmetric: M⁻¹ Wᵀ by the factorisation).
  const MatrixXc Wb = Vinv.rightCols(N);
  const MatrixX Minv = mass_ldlt.solve(MatrixX::Identity(N, N));
  const MatrixXc W = (Wb * Minv.cast<C>()) / w0;  // 2N×N, row r = w_rᵀ
  const MatrixXc Vt = V.topRows(N);               // N×2N, column r = v_r
  const MatrixXc Pc = problem.projection.cast<C>();
  const MatrixXc a = Pc * Vt;                            // n×2N
  const MatrixXc b = W * Pc.transpose();                 // 2N×n
  const VectorXc f0 = W * problem.force_mean.cast<C>();  // 2N
  const VectorXc f1 = W * (0.5 * problem.force_amplitude);
  poles = es.eigenvalues();
  residues.resize(n * n, 2 * N);
  force_residues.resize(2 * n, 2 * N);
  residue_norms.resize(2 * N);
  for (int r = 0; r < 2 * N; ++r) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) residues(i + n * j, r) = a(i, r) * b(r, j);
    }
    force_residues.col(r).head(n) = a.col(r) * f0[r];
    force_residues.col(r).tail(n) = a.col(r) * f1[r];
    residue_norms[r] = Vt.col(r).cwiseAbs().sum() * W.row(r).cwiseAbs().maxCoeff();
  }
  if (!poles.allFinite() || !residues.allFinite() || !force_residues.allFinite()) return false;
  norm_m = mass_norm;
  norm_k = stiffness_norm;
  norm_c = problem.damping.cwiseAbs().colwise().sum().maxCoeff();
  modal_top = Vt;
  modal_left = W;
  pole_weights.resize(2 * N);
  pole_weights2.resize(2 * N);
  receptance.resize(n, n);
  d_receptance.resize(n, n);
  return true;
}

void NhbSolver::Impl::UpdateLinear(double omega) {
  if (omega == cached_omega) return;
  cached_omega = omega;
  const double w = omega / p;
  const std::complex<double> I(0.0, 1.0);
  double fmax = 0.0;
  linear_rcond = 1.0;
  for (int k = 0; k <= H; ++k) {
    const double kk = k;
    if (uncondensed) {
      // Z_k = D_k, written in place (no temporaries: this runs at every new Ω).
      Z[k] = (-kk * kk * w * w) * mass_c + (I * kk * w) * damping_c + stiffness_c;
      dZ[k] = (-2.0 * kk * kk * w / p) * mass_c + (I * kk / double(p)) * damping_c;
      F[k].setZero();
      if (k == 0) F[k] = problem.force_mean.cast<std::complex<double>>();
      if (k == p) F[k] = 0.5 * problem.force_amplitude;
      dF[k].setZero();
    } else if (pole_residue) {
      // R_k = Σ_r ρ_r/(s − λ_r), dR_k/dΩ = −(ik/p) Σ_r ρ_r/(s − λ_r)², s = ikω.
      const std::complex<double> s(0.0, kk * w), ds(0.0, kk / p);
      double inverse_bound = 0.0;  // ≥ ‖D_k⁻¹‖₁
      for (Eigen::Index r = 0; r < poles.size(); ++r) {
        const std::complex<double> d = s - poles[r];
        const double d2 = std::norm(d);
        const std::complex<double> q = std::conj(d) / d2;  // 1/d without a complex division
        pole_weights[r] = q;
        pole_weights2[r] = -ds * q * q;
        inverse_bound += residue_norms[r] / std::sqrt(d2);
      }
      Eigen::Map<VectorXc>(receptance.data(), n * n).noalias() = residues * pole_weights;
      Eigen::Map<VectorXc>(d_receptance.data(), n * n).noalias() = residues * pole_weights2;
      if (n == 1) {
        Z[k](0, 0) = 1.0 / receptance(0, 0);
      } else if (n == 2) {
        // Closed-form 2×2 inverse (no LU, no allocation; one mesh with its tilt coordinate).
        const std::complex<double> det =
            receptance(0, 0) * receptance(1, 1) - receptance(0, 1) * receptance(1, 0);
        Z[k](0, 0) = receptance(1, 1) / det;
        Z[k](1, 1) = receptance(0, 0) / det;
        Z[k](0, 1) = -receptance(0, 1) / det;
        Z[k](1, 0) = -receptance(1, 0) / det;
      } else {
        Z[k] = receptance.partialPivLu().inverse();
      }
      // dZ = −Z dR Z.
      dZ[k].noalias() = -Z[k] * d_receptance * Z[k];
      const double norm_d = norm_k + kk * w * norm_c + kk * kk * w * w * norm_m;
      // 1/cond₁ of R_k exactly (n×n, its inverse at hand).
      const double norm_r = receptance.cwiseAbs2().cwiseSqrt().colwise().sum().maxCoeff();
      const double norm_z = Z[k].cwiseAbs2().cwiseSqrt().colwise().sum().maxCoeff();
      const double rcond_r = 1.0 / (norm_r * norm_z);
      linear_rcond = std::min(
          {linear_rcond, 1.0 / (norm_d * inverse_bound), std::isfinite(rcond_r) ? rcond_r : 0.0});
      F[k].setZero();
      dF[k].setZero();
      const int load = k == 0 ? 0 : (k == p ? 1 : -1);
      if (load >= 0) {
        // F̃_k = Z g, g = P D⁻¹ F_k = Σ_r φ_r/(s − λ_r); dF̃ = dZ g + Z dg/dΩ.
        const auto rows = force_residues.middleRows(load * n, n);
        const VectorXc gk = rows * pole_weights;
        const VectorXc dgk = rows * pole_weights2;
        F[k] = Z[k] * gk;
        dF[k] = dZ[k] * gk + Z[k] * dgk;
      }
    } else {
      const MatrixXc D = (-kk * kk * w * w) * mass_c + (I * kk * w) * damping_c + stiffness_c;
      const MatrixXc dD = (-2.0 * kk * kk * w / p) * mass_c + (I * kk / double(p)) * damping_c;
      VectorXc Fk = VectorXc::Zero(dofs);
      if (k == 0) Fk = problem.force_mean.cast<std::complex<double>>();
      if (k == p) Fk = 0.5 * problem.force_amplitude;
      const MatrixXc Pc = problem.projection.cast<std::complex<double>>();
      Eigen::PartialPivLU<MatrixXc> dlu(D);
      const MatrixXc Y = dlu.solve(Pc.transpose());  // D⁻¹ Pᵀ, N×n
      const Eigen::PartialPivLU<MatrixXc> zlu(Pc * Y);
      Z[k] = zlu.inverse();
      // Both inversions of the condensation: D_k and P D_k⁻¹ Pᵀ (Eigen's 1-norm estimates).
      linear_rcond = std::min({linear_rcond, dlu.rcond(), zlu.rcond()});
      const VectorXc wv = dlu.solve(Fk);
      F[k] = Z[k] * (Pc * wv);
      dZ[k] = Z[k] * (Pc * dlu.solve(dD * Y)) * Z[k];
      dF[k] = dZ[k] * (Pc * wv) - Z[k] * (Pc * dlu.solve(dD * wv));
    }
    fmax = std::max(fmax, F[k].cwiseAbs().maxCoeff());
  }
  force_scale = 1.0 + fmax;
}

MatrixXc NhbSolver::SolveLinear(double omega, const MatrixXc& b) {
  Impl& s = *impl_;
  GEARDYN_CHECK_SIZE(b.rows(), s.dofs, "b rows");
  GEARDYN_CHECK_SIZE(b.cols(), s.H + 1, "b columns");
  const double w = omega / s.p;
  const std::complex<double> I(0.0, 1.0);
  MatrixXc out(s.dofs, s.H + 1);
  if (s.pole_residue) {
    // D(s)⁻¹ b = Σ_r v_r (w_rᵀ b)/(s − λ_r).
    const MatrixXc modal = s.modal_left * b;  // 2N×(H+1)
    VectorXc scaled(modal.rows());
    for (int k = 0; k <= s.H; ++k) {
      const std::complex<double> sk(0.0, k * w);
      for (Eigen::Index r = 0; r < modal.rows(); ++r) scaled[r] = modal(r, k) / (sk - s.poles[r]);
      out.col(k).noalias() = s.modal_top * scaled;
    }
    return out;
  }
  for (int k = 0; k <= s.H; ++k) {
    const double kk = k;
    const MatrixXc D = (-kk * kk * w * w) * s.mass_c + (I * kk * w) * s.damping_c + s.stiffness_c;
    out.col(k) = D.partialPivLu().solve(b.col(k));
  }
  return out;
}

}  // namespace geardyn
