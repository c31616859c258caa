/// @file
/// @brief Condensed linear part of the nonlinear HB per harmonic (see nonlinear_hb.hpp):
/// Z_k = (P D_k⁻¹ Pᵀ)⁻¹, F̃_k = Z_k P D_k⁻¹ F_k with D_k = −k²ω²M + ikωC + K, ω = Ω/p, and their
/// analytic Ω-derivatives (dD_k/dΩ = (−2k²ωM + ikC)/p; dZ = Z P D⁻¹ dD D⁻¹ Pᵀ Z).
#include <Eigen/LU>
#include <complex>

#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {

void NhbSolver::Impl::UpdateLinear(double omega) {
  if (omega == cached_omega) return;
  cached_omega = omega;
  const double w = omega / p;
  const std::complex<double> I(0.0, 1.0);
  const bool direct = problem.IsUncondensed();
  double fmax = 0.0;
  for (int k = 0; k <= H; ++k) {
    const double kk = k;
    MatrixXc D = (-kk * kk * w * w) * problem.mass.cast<std::complex<double>>() +
                 (I * kk * w) * problem.damping.cast<std::complex<double>>() +
                 problem.stiffness.cast<std::complex<double>>();
    MatrixXc dD = ((-2.0 * kk * kk * w / p) * problem.mass.cast<std::complex<double>>() +
                   (I * kk / double(p)) * problem.damping.cast<std::complex<double>>());
    VectorXc Fk = VectorXc::Zero(dofs);
    if (k == 0) Fk = problem.force_mean.cast<std::complex<double>>();
    if (k == p) Fk = 0.5 * problem.force_amplitude;
    if (direct) {
      Z[k] = D;
      dZ[k] = dD;
      F[k] = Fk;
      dF[k].setZero();
    } else {
      const MatrixXc Pc = problem.projection.cast<std::complex<double>>();
      Eigen::PartialPivLU<MatrixXc> dlu(D);
      const MatrixXc Y = dlu.solve(Pc.transpose());  // D⁻¹ Pᵀ, N×n
      Z[k] = (Pc * Y).inverse();
      const VectorXc wv = dlu.solve(Fk);
      F[k] = Z[k] * (Pc * wv);
      dZ[k] = Z[k] * (Pc * dlu.solve(dD * Y)) * Z[k];
      dF[k] = dZ[k] * (Pc * wv) - Z[k] * (Pc * dlu.solve(dD * wv));
    }
    fmax = std::max(fmax, F[k].cwiseAbs().maxCoeff());
  }
  force_scale = 1.0 + fmax;
}

}  // namespace geardyn
