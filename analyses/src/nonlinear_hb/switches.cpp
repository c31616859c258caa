/// @file
/// @brief Contact switches of the nonlinear HB orbit: u(θ) and its derivatives synthesized at
/// arbitrary base angles θ = ωt from the harmonics, the switching time located by the Illinois
/// (modified regula falsi) method on the law's SwitchFunction, and the Euler–Maclaurin kink
/// correction of the sampled Fourier coefficients (nonlinear_hb.hpp, "AFT").
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {

void NhbSolver::Impl::EvaluateCoordinate(const VectorX& x, int i, double theta,
                                         double out[3]) const {
  // u = U_0 + 2 Re Σ U_k z^k, u′ = 2 Re Σ ik U_k z^k, u″ = −2 Re Σ k² U_k z^k, z = e^{iθ}.
  const std::complex<double> z = std::polar(1.0, theta);
  std::complex<double> zk = 1.0;
  double value = x[Re(0, i)], slope = 0.0, curvature = 0.0;
  for (int k = 1; k <= H; ++k) {
    zk *= z;
    const std::complex<double> c = std::complex<double>(x[Re(k, i)], x[Im(k, i)]) * zk;
    value += 2.0 * c.real();
    slope -= 2.0 * k * c.imag();
    curvature -= 2.0 * k * k * c.real();
  }
  out[0] = value;
  out[1] = slope;
  out[2] = curvature;
}

// u(θ) and du/dθ of every coordinate at the given angles.
void NhbSolver::Impl::SynthesizeAt(const VectorX& x, const VectorX& theta, MatrixX& uu,
                                   MatrixX* du) const {
  const Eigen::Index count = theta.size();
  uu.resize(n, count);
  if (du) du->resize(n, count);
  double d[3];
  for (Eigen::Index j = 0; j < count; ++j) {
    for (int i = 0; i < n; ++i) {
      EvaluateCoordinate(x, i, theta[j], d);
      uu(i, j) = d[0];
      if (du) (*du)(i, j) = d[1];
    }
  }
}

double NhbSolver::Impl::SwitchValueAt(const VectorX& x, int i, double theta) {
  theta1.resize(1);
  theta1[0] = theta;
  SynthesizeAt(x, theta1, u1, nullptr);
  phase1.resize(1);
  phase1[0] = p * theta;
  sw1.resize(n, 1);
  problem.law->SwitchFunction(u1, phase1, sw1);
  return sw1(i, 0);
}

double NhbSolver::Impl::LocateSwitch(const VectorX& x, int i, double a, double fa, double b,
                                     double fb) {
  // Illinois: regula falsi, halving the retained end's value when it is kept twice in a row.
  const double tol = 1e-14 * 2.0 * std::numbers::pi;
  int side = 0;
  double c = 0.5 * (a + b);
  for (int it = 0; it < 60 && b - a > tol; ++it) {
    c = (fa != fb) ? b - fb * (b - a) / (fb - fa) : 0.5 * (a + b);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double fc = SwitchValueAt(x, i, c);
    if (fc == 0.0) return c;
    if ((fc > 0) == (fb > 0)) {
      b = c;
      fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c;
      fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
  }
  return c;
}

void NhbSolver::Impl::CorrectForceAtSwitches(const VectorX& x) {
  if (!has_switch_function) return;
  problem.law->SwitchFunction(u, phase, sw);
  const double h = 2.0 * std::numbers::pi / S;
  MatrixX dgs(n, n);
  VectorX jump(n);
  for (int i = 0; i < n; ++i) {
    for (int s = 0; s < S; ++s) {
      const int s1 = (s + 1) % S;
      if ((sw(i, s) > 0) == (sw(i, s1) > 0)) continue;
      const double a = h * s;
      const double tau = LocateSwitch(x, i, a, sw(i, s), a + h, sw(i, s1));
      const double phi = std::clamp((tau - a) / h, 0.0, 1.0);
      theta1.resize(1);
      theta1[0] = tau;
      SynthesizeAt(x, theta1, u1, &du1);
      // Slope jump of g in θ: ΔG du/dθ, ΔG = ∂g/∂u after − before (O(h) from the smooth part).
      for (int e = 0; e < n * n; ++e) dgs(e % n, e / n) = dg(e, s1) - dg(e, s);
      jump.noalias() = dgs * du1.col(0);
      // (1/2π) J h² B₂(φ)/2 · e^{−ikτ}: the DFT's 1/S normalisation is 1/2π · h.
      const double w = h * h * (phi * phi - phi + 1.0 / 6.0) / (4.0 * std::numbers::pi);
      const std::complex<double> z = std::polar(1.0, -tau);
      std::complex<double> zk = 1.0;
      for (int k = 0; k <= H; ++k) {
        for (int r = 0; r < n; ++r) g_h(r, k) += w * jump[r] * zk;
        zk *= z;
      }
    }
  }
}

}  // namespace geardyn
