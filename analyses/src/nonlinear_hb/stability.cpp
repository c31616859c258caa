/// @file
/// @brief Stability of a harmonic-balance orbit (see nonlinear_hb.hpp, "Stability"):
/// * monodromy: Φ(T) = Π exp(Ω_j) over pieces [θ_a, θ_b] of the base period (uniform steps
///   split at the contact switches located on u(θ)), Ω = h/2 (A₁ + A₂) + √3/12 h² [A₂, A₁]
///   (Magnus-4, A at the Gauss points θ_mid ∓ Δθ/(2√3), h = Δθ/ω [time]),
///   A = [0 I; −M⁻¹(K + Pᵀ ∂g/∂u P) −M⁻¹C]; max |eig Φ|.
/// * Hill: eigenvalues λ of Σ_m [δ_km((λ + ikω)²M + (λ + ikω)C + K) + G_{k−m}] Y_m = 0,
///   k, m = −H..H, via the companion linearisation; the 2N exponents with the smallest |Im λ|
///   are the Floquet exponents (the others are their copies λ + ijω), μ = e^{λT}.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>
#include <utility>
#include <vector>

#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {
namespace {

/// exp of a real 2×2 matrix in closed form: with m = tr/2, B = X − mI, B² = δI (δ = −det B),
/// exp X = e^m (c I + s B), c = cosh √δ, s = sinh √δ / √δ (cos/sin for δ < 0).
Eigen::Matrix2d Exp2(const Eigen::Matrix2d& X) {
  const double mean = 0.5 * X.trace();
  Eigen::Matrix2d B = X;
  B.diagonal().array() -= mean;
  const double delta = -B.determinant();
  double c = 1.0, sc = 1.0;
  if (delta > 1e-16) {
    const double r = std::sqrt(delta);
    c = std::cosh(r);
    sc = std::sinh(r) / r;
  } else if (delta < -1e-16) {
    const double r = std::sqrt(-delta);
    c = std::cos(r);
    sc = std::sin(r) / r;
  } else {
    c = 1.0 + 0.5 * delta;  // series to O(δ²) ~ 1e-32
    sc = 1.0 + delta / 6.0;
  }
  return std::exp(mean) * (c * Eigen::Matrix2d::Identity() + sc * B);
}

/// exp of a general square matrix: Taylor to order 8 for small norms, Padé otherwise.
MatrixX ExpGeneral(const MatrixX& X) {
  if (X.lpNorm<1>() < 0.2) {
    // Truncation < 0.2⁹/9! ≈ 1e-12 relative.
    MatrixX E = MatrixX::Identity(X.rows(), X.cols());
    MatrixX term = E;
    for (int j = 1; j <= 8; ++j) {
      term = term * X / double(j);
      E += term;
    }
    return E;
  }
  return X.exp();
}

}  // namespace

double NhbSolver::Impl::MonodromyMaxMultiplier(const VectorX& x, double omega) {
  const int N = dofs;
  const double w = omega / p;
  const double two_pi = 2.0 * std::numbers::pi;
  int Q = options.monodromy_steps > 0 ? options.monodromy_steps : std::max(64, 4 * H);
  // Piece boundaries: the uniform nodes plus every located contact switch.
  std::vector<double> cuts;
  cuts.reserve(static_cast<size_t>(Q) + 8);
  VectorX nodes(Q);
  for (int j = 0; j < Q; ++j) nodes[j] = two_pi * j / Q;
  for (int j = 0; j <= Q; ++j) cuts.push_back(two_pi * j / Q);
  if (has_switch_function) {
    MatrixX un, swn(n, Q);
    SynthesizeAt(x, nodes, un, nullptr);
    VectorX ph = nodes * double(p);
    problem.law->SwitchFunction(un, ph, swn);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < Q; ++j) {
        const int j1 = (j + 1) % Q;
        if ((swn(i, j) > 0) == (swn(i, j1) > 0)) continue;
        cuts.push_back(LocateSwitch(x, i, nodes[j], swn(i, j), two_pi * (j + 1) / Q, swn(i, j1)));
      }
    }
    std::sort(cuts.begin(), cuts.end());
  }
  // Two Gauss points per piece (pieces shorter than 1e-14·2π are dropped: their exp is I).
  std::vector<std::pair<double, double>> pieces;
  for (size_t j = 0; j + 1 < cuts.size(); ++j) {
    if (cuts[j + 1] - cuts[j] > 1e-14 * two_pi) pieces.emplace_back(cuts[j], cuts[j + 1]);
  }
  const Eigen::Index P = static_cast<Eigen::Index>(pieces.size());
  VectorX theta(2 * P);
  const double gauss = 0.5 / std::sqrt(3.0);
  for (Eigen::Index j = 0; j < P; ++j) {
    const double mid = 0.5 * (pieces[j].first + pieces[j].second);
    const double len = pieces[j].second - pieces[j].first;
    theta[2 * j] = mid - gauss * len;
    theta[2 * j + 1] = mid + gauss * len;
  }
  MatrixX ug, gg(n, 2 * P), dgg(n * n, 2 * P);
  SynthesizeAt(x, theta, ug, nullptr);
  const VectorX ph = theta * double(p);
  problem.law->Evaluate(ug, ph, gg, dgg);

  const MatrixX Minv = problem.mass.inverse();
  const MatrixX& Pm = problem.projection;
  const double c3 = std::sqrt(3.0) / 12.0;
  if (N == 1) {
    // SDOF: 2×2 closed-form propagation, A = [0 1; −(K + P G P)/M  −C/M].
    const double minv = Minv(0, 0), k0 = problem.stiffness(0, 0), c0 = problem.damping(0, 0);
    Eigen::Matrix2d phi = Eigen::Matrix2d::Identity();
    for (Eigen::Index j = 0; j < P; ++j) {
      const double h = (pieces[j].second - pieces[j].first) / w;
      double kk[2];
      for (int q = 0; q < 2; ++q) {
        double pgp = 0.0;
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b) pgp += Pm(a, 0) * dgg(a + n * b, 2 * j + q) * Pm(b, 0);
        kk[q] = minv * (k0 + pgp);
      }
      // A_q = [0 1; −κ_q −c/M], κ_q = (K + Pᵀ G P)/M at Gauss point q.
      Eigen::Matrix2d A1, A2;
      A1 << 0.0, 1.0, -kk[0], -minv * c0;
      A2 << 0.0, 1.0, -kk[1], -minv * c0;
      const Eigen::Matrix2d Om = 0.5 * h * (A1 + A2) + c3 * h * h * (A2 * A1 - A1 * A2);
      phi = Exp2(Om) * phi;
    }
    Eigen::EigenSolver<Eigen::Matrix2d> es(phi, false);
    return es.eigenvalues().cwiseAbs().maxCoeff();
  }
  MatrixX A1 = MatrixX::Zero(2 * N, 2 * N);
  A1.topRightCorner(N, N).setIdentity();
  A1.bottomRightCorner(N, N) = -Minv * problem.damping;
  MatrixX A2 = A1;
  MatrixX phi = MatrixX::Identity(2 * N, 2 * N);
  for (Eigen::Index j = 0; j < P; ++j) {
    const double h = (pieces[j].second - pieces[j].first) / w;
    const Eigen::Map<const MatrixX> G1(dgg.col(2 * j).data(), n, n);
    const Eigen::Map<const MatrixX> G2(dgg.col(2 * j + 1).data(), n, n);
    A1.bottomLeftCorner(N, N) = -Minv * (problem.stiffness + Pm.transpose() * G1 * Pm);
    A2.bottomLeftCorner(N, N) = -Minv * (problem.stiffness + Pm.transpose() * G2 * Pm);
    const MatrixX Om = 0.5 * h * (A1 + A2) + c3 * h * h * (A2 * A1 - A1 * A2);
    phi = ExpGeneral(Om) * phi;
  }
  Eigen::EigenSolver<MatrixX> es(phi, false);
  return es.eigenvalues().cwiseAbs().maxCoeff();
}

double NhbSolver::Impl::HillMaxMultiplier(const VectorX& x, double omega) {
  // Only for uncondensed problems (P = I): the condensed Z_k(λ) is not a polynomial in λ.
  if (!problem.IsUncondensed()) return MonodromyMaxMultiplier(x, omega);
  ForceHarmonics(x, true);
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
