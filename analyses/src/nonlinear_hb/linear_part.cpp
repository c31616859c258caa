/// @file
/// @brief Condensed linear part of the nonlinear HB per harmonic (see nonlinear_hb.hpp):
/// Z_k = (P D_k⁻¹ Pᵀ)⁻¹, F̃_k = Z_k P D_k⁻¹ F_k with D_k = −k²ω²M + ikωC + K, ω = Ω/p, and their
/// analytic Ω-derivatives (dD_k/dΩ = (−2k²ωM + ikC)/p; dZ = Z P D⁻¹ dD D⁻¹ Pᵀ Z). The smallest
/// estimated reciprocal condition number of the two inversions is kept (linear_rcond).
#include <Eigen/LU>
#include <algorithm>
#include <complex>

#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {

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

}  // namespace geardyn
