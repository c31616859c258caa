/// @file
/// @brief Stability of a harmonic-balance orbit (see nonlinear_hb.hpp, "Stability"):
/// * monodromy: Φ(T) = Π_s exp(A(t_s) h), h = T/S, A = [0 I; −M⁻¹(K + Pᵀ ∂g/∂u(t_s) P) −M⁻¹C]
///   held constant on [t_s − h/2, t_s + h/2] (midpoint rule); max |eig Φ|.
/// * Hill: eigenvalues λ of Σ_m [δ_km((λ + ikω)²M + (λ + ikω)C + K) + G_{k−m}] Y_m = 0,
///   k, m = −H..H, via the companion linearisation; the 2N exponents with the smallest |Im λ|
///   are the Floquet exponents (the others are their copies λ + ijω), μ = e^{λT}.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {

double NhbSolver::Impl::MonodromyMaxMultiplier(const VectorX& x, double omega) {
  const int N = dofs;
  const double T = 2.0 * std::numbers::pi * p / omega;
  const double h = T / S;
  Synthesize(x);
  problem.law->Evaluate(u, phase, g, dg);
  const MatrixX Minv = problem.mass.inverse();
  const MatrixX& P = problem.projection;
  MatrixX A = MatrixX::Zero(2 * N, 2 * N);
  A.topRightCorner(N, N).setIdentity();
  A.bottomRightCorner(N, N) = -Minv * problem.damping;
  MatrixX phi = MatrixX::Identity(2 * N, 2 * N);
  MatrixX E(2 * N, 2 * N), term(2 * N, 2 * N);
  for (int s = 0; s < S; ++s) {
    const Eigen::Map<const MatrixX> G(dg.col(s).data(), n, n);
    A.bottomLeftCorner(N, N) = -Minv * (problem.stiffness + P.transpose() * G * P);
    const MatrixX Ah = A * h;
    if (Ah.lpNorm<1>() < 0.2) {
      // Taylor series to order 8: truncation < 0.2⁹/9! ≈ 1e-12 relative.
      E.setIdentity();
      term.setIdentity();
      for (int j = 1; j <= 8; ++j) {
        term = term * Ah / double(j);
        E += term;
      }
    } else {
      E = Ah.exp();
    }
    phi = E * phi;
  }
  Eigen::EigenSolver<MatrixX> es(phi, false);
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

double NhbSolver::Impl::HillMaxMultiplier(const VectorX& x, double omega) {
  // Only for uncondensed problems (P = I): the condensed Z_k(λ) is not a polynomial in λ.
  if (!problem.IsUncondensed()) return MonodromyMaxMultiplier(x, omega);
  Synthesize(x);
  problem.law->Evaluate(u, phase, g, dg);
  AnalyseJacobian();
  const double w = omega / p;
  const int N = n;
  const int B = 2 * H + 1;
  const int sz = N * B;
  using C = std::complex<double>;
  const C I(0.0, 1.0);
  MatrixXc K0 = MatrixXc::Zero(sz, sz), C0 = MatrixXc::Zero(sz, sz);
  const MatrixXc M = problem.mass.cast<C>(), Cd = problem.damping.cast<C>(),
                 K = problem.stiffness.cast<C>();
  for (int a = 0; a < B; ++a) {
    const int k = a - H;
    C0.block(a * N, a * N, N, N) = Cd + 2.0 * I * double(k) * w * M;
    K0.block(a * N, a * N, N, N) = -double(k * k) * w * w * M + I * double(k) * w * Cd + K;
    for (int b = 0; b < B; ++b) {
      const int j = a - b;  // G_{k−m}
      const MatrixXc Gj = j >= 0 ? dg_h[j] : MatrixXc(dg_h[-j].conjugate());
      K0.block(a * N, b * N, N, N) += Gj;
    }
  }
  MatrixXc Minv = MatrixXc::Zero(sz, sz);
  const MatrixXc mi = M.inverse();
  for (int a = 0; a < B; ++a) Minv.block(a * N, a * N, N, N) = mi;
  MatrixXc comp = MatrixXc::Zero(2 * sz, 2 * sz);
  comp.topRightCorner(sz, sz).setIdentity();
  comp.bottomLeftCorner(sz, sz) = -Minv * K0;
  comp.bottomRightCorner(sz, sz) = -Minv * C0;
  Eigen::ComplexEigenSolver<MatrixXc> es(comp, false);
  std::vector<C> lambda(es.eigenvalues().data(), es.eigenvalues().data() + 2 * sz);
  std::sort(lambda.begin(), lambda.end(),
            [](const C& l, const C& r) { return std::abs(l.imag()) < std::abs(r.imag()); });
  double re = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < 2 * N; ++i) re = std::max(re, lambda[i].real());
  const double T = 2.0 * std::numbers::pi / w;
  return std::exp(re * T);
}

}  // namespace geardyn
