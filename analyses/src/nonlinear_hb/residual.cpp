/// @file
/// @brief NhbSolver: harmonic residual R_k = Z_k U_k + N_k − F̃_k, its analytic Jacobian
/// (Toeplitz blocks ∂N_k/∂U_m = G_{k−m}), the contact-branch initial guess and the description
/// of a solution (RMS, peak-to-peak, error estimate).
#include <algorithm>
#include <cmath>
#include <complex>

#include "geardyn/common/check.hpp"
#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {
void NhbSolver::Impl::Evaluate(const VectorX& x, double omega, VectorX* residual, MatrixX* jacobian,
                               VectorX* d_omega) {
  using C = std::complex<double>;
  UpdateLinear(omega);
  ForceHarmonics(x, jacobian != nullptr);
  // Complex harmonic U_k of coordinate i from x.
  auto U = [&](int k, int i) { return k == 0 ? C(x[i], 0.0) : C(x[Re(k, i)], x[Im(k, i)]); };
  auto store = [&](VectorX& out, int k, int a, C r) {
    out[Re(k, a)] = r.real();
    if (k > 0) out[Im(k, a)] = r.imag();
  };
  if (residual) {
    for (int k = 0; k <= H; ++k) {
      for (int a = 0; a < n; ++a) {
        C r = g_h(a, k) - F[k][a];
        for (int b = 0; b < n; ++b) r += Z[k](a, b) * U(k, b);
        store(*residual, k, a, r);
      }
    }
  }
  if (d_omega) {
    for (int k = 0; k <= H; ++k) {
      for (int a = 0; a < n; ++a) {
        C r = -dF[k][a];
        for (int b = 0; b < n; ++b) r += dZ[k](a, b) * U(k, b);
        store(*d_omega, k, a, r);
      }
    }
  }
  if (!jacobian) return;
  MatrixX& Jm = *jacobian;
  // G_j(a, b) for j = −2H..2H (G_{−j} = conj(G_j)) in one flat buffer: no branches in the
  // O(H²n²) loop below.
  const int nn = n * n;
  for (int j = 0; j <= 2 * H; ++j) {
    for (int e = 0; e < nn; ++e) {
      const C value = dg_h[j](e % n, e / n);
      jacobian_coefficients[(2 * H + j) * nn + e] = value;
      jacobian_coefficients[(2 * H - j) * nn + e] = std::conj(value);
    }
  }
  auto G = [&](int j, int e) { return jacobian_coefficients[(2 * H + j) * nn + e]; };
  for (int mm = 0; mm <= H; ++mm) {
    for (int k = 0; k <= H; ++k) {
      for (int b = 0; b < n; ++b) {
        for (int a = 0; a < n; ++a) {
          const int e = a + n * b;
          // ∂N_k/∂(Re U_m) and ∂N_k/∂(Im U_m), from δU_{±m}: U_m = α + iβ, U_{−m} = α − iβ:
          // dA = G_{k−m} + G_{k+m}, dB = i (G_{k−m} − G_{k+m}) (m = 0: dA = G_k).
          C dA, dB;
          if (mm == 0) {
            dA = G(k, e);
          } else {
            const C minus = G(k - mm, e), plus = G(k + mm, e);
            dA = minus + plus;
            const C diff = minus - plus;
            dB = C(-diff.imag(), diff.real());
          }
          if (k == mm) {
            const C z = Z[k](a, b);
            dA += z;
            if (k > 0) dB += C(-z.imag(), z.real());
          }
          Jm(Re(k, a), Re(mm, b)) = dA.real();
          if (k > 0) Jm(Im(k, a), Re(mm, b)) = dA.imag();
          if (mm > 0) {
            Jm(Re(k, a), Im(mm, b)) = dB.real();
            if (k > 0) Jm(Im(k, a), Im(mm, b)) = dB.imag();
          }
        }
      }
    }
  }
}

void NhbSolver::Impl::ForceHarmonics(const VectorX& x, bool jacobian) {
  Synthesize(x);
  if (exact) {
    if (projected) {
      if (integrated_valid && integrated_x == x) return;  // g_h, dg_h of this x are current
      IntegrateProjected(x);
      integrated_x = x;
      integrated_valid = true;
    } else {
      IntegrateExactly(x);
    }
    return;
  }
  problem.law->Evaluate(u, phase, g, dg);
  AnalyseForce();
  if (options.switch_correction) CorrectForceAtSwitches(x);
  if (jacobian) AnalyseJacobian();
}

NhbSolver::NhbSolver(NhbProblem problem, const NhbOptions& options, int harmonics) {
  std::string why;
  GEARDYN_THROW_UNLESS(problem.IsValid(&why), "nonlinear HB problem: " << why);
  GEARDYN_THROW_UNLESS(options.IsValid(&why), "nonlinear HB options: " << why);
  GEARDYN_THROW_UNLESS(harmonics >= 1, "harmonics: must be ≥ 1, got " << harmonics);
  impl_ = std::make_unique<Impl>(std::move(problem), options, harmonics);
}
NhbSolver::~NhbSolver() = default;
NhbSolver::NhbSolver(NhbSolver&&) noexcept = default;
NhbSolver& NhbSolver::operator=(NhbSolver&&) noexcept = default;

int NhbSolver::harmonics() const { return impl_->H; }
int NhbSolver::samples() const { return impl_->S; }
int NhbSolver::num_unknowns() const { return impl_->m; }
bool NhbSolver::exact_integration() const { return impl_->exact; }
const NhbProblem& NhbSolver::problem() const { return impl_->problem; }

void NhbSolver::Evaluate(const VectorX& x, double omega, VectorX* residual, MatrixX* jacobian,
                         VectorX* d_omega) {
  GEARDYN_CHECK_SIZE(x.size(), impl_->m, "x");
  if (residual) residual->resize(impl_->m);
  if (jacobian) jacobian->resize(impl_->m, impl_->m);
  if (d_omega) d_omega->resize(impl_->m);
  impl_->Evaluate(x, omega, residual, jacobian, d_omega);
}

MatrixXc NhbSolver::ForceHarmonics(const VectorX& x) {
  GEARDYN_CHECK_SIZE(x.size(), impl_->m, "x");
  impl_->ForceHarmonics(x, false);
  return impl_->g_h;
}

double NhbSolver::LastLawForceNorm() const {
  return impl_->g_h.size() == 0 ? 0.0 : impl_->g_h.cwiseAbs().maxCoeff();
}

VectorX NhbSolver::ContactGuess(double omega) {
  Impl& s = *impl_;
  s.UpdateLinear(omega);
  MatrixX kc;
  VectorX gc;
  s.problem.law->ContactBranch(kc, gc);
  VectorX x = VectorX::Zero(s.m);
  for (int k = 0; k <= s.H; ++k) {
    VectorXc rhs = s.F[k];
    if (k == 0) rhs -= gc.cast<std::complex<double>>();
    const VectorXc Uk = (s.Z[k] + kc.cast<std::complex<double>>()).fullPivLu().solve(rhs);
    for (int i = 0; i < s.n; ++i) {
      x[s.Re(k, i)] = Uk[i].real();
      if (k > 0) x[s.Im(k, i)] = Uk[i].imag();
    }
  }
  return x;
}

void NhbSolver::Describe(const VectorX& x, double omega, NhbPoint& point) {
  Impl& s = *impl_;
  GEARDYN_CHECK_SIZE(x.size(), s.m, "x");
  s.Synthesize(x);
  s.UpdateLinear(omega);
  point.condensation_rcond = s.linear_rcond;
  point.omega = omega;
  point.harmonics.resize(s.n, s.H + 1);
  point.mean.resize(s.n);
  point.rms.resize(s.n);
  double total = 0.0;
  double top = 0.0;
  const int top_from = s.H - std::max(1, s.H / 4) + 1;
  for (int i = 0; i < s.n; ++i) {
    double e = 0.0;
    for (int k = 0; k <= s.H; ++k) {
      const std::complex<double> c = k == 0 ? std::complex<double>(x[i], 0.0)
                                            : std::complex<double>(x[s.Re(k, i)], x[s.Im(k, i)]);
      point.harmonics(i, k) = c;
      if (k >= 1) e += 2.0 * std::norm(c);
      if (k >= top_from) top += 2.0 * std::norm(c);
    }
    point.mean[i] = x[i];
    point.rms[i] = std::sqrt(e);
    total += e;
  }
  point.maximum.resize(s.n);
  point.minimum.resize(s.n);
  for (int i = 0; i < s.n; ++i) {
    point.maximum[i] = s.ExtremeValue(x, i, 1.0);
    point.minimum[i] = s.ExtremeValue(x, i, -1.0);
  }
  point.peak_to_peak = point.maximum - point.minimum;
  s.ForceHarmonics(x, false);
  point.force_harmonics = s.g_h;
  point.error_estimate = total > 0 ? std::sqrt(top / total) : 0.0;
}

double NhbSolver::MaxMultiplier(const VectorX& x, double omega) {
  switch (impl_->options.stability) {
    case NhbStabilityMethod::kNone:
      return 0.0;
    case NhbStabilityMethod::kMonodromy:
      // A projected law's Jacobian is piecewise constant: the exact product.
      if (impl_->projected) return impl_->ProjectedMonodromyMaxMultiplier(x, omega);
      return impl_->MonodromyMaxMultiplier(x, omega);
    case NhbStabilityMethod::kHill:
      return impl_->HillMaxMultiplier(x, omega);
  }
  return 0.0;
}

VectorX NhbSolver::Resize(const VectorX& x, int n, int new_harmonics) {
  VectorX y = VectorX::Zero(n * (2 * new_harmonics + 1));
  const Eigen::Index common = std::min<Eigen::Index>(x.size(), y.size());
  y.head(common) = x.head(common);  // harmonic-major layout: truncation/padding at the end
  return y;
}

}  // namespace geardyn
