/// @file
/// @brief NhbSolver: harmonic residual R_k = Z_k U_k + N_k − F̃_k, its analytic Jacobian
/// (Toeplitz blocks ∂N_k/∂U_m = G_{k−m}), Newton with backtracking, the contact-branch initial
/// guess and the description of a solution (RMS, peak-to-peak, error estimate).
#include <algorithm>
#include <cmath>
#include <complex>

#include "geardyn/common/check.hpp"
#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {
namespace {

/// G_j for any integer j (G_{−j} = conj(G_j)).
MatrixXc Block(const std::vector<MatrixXc>& g, int j) {
  return j >= 0 ? g[j] : MatrixXc(g[-j].conjugate());
}

}  // namespace

void NhbSolver::Impl::Evaluate(const VectorX& x, double omega, VectorX* residual, MatrixX* jacobian,
                               VectorX* d_omega) {
  UpdateLinear(omega);
  Synthesize(x);
  problem.law->Evaluate(u, phase, g, dg);
  AnalyseForce();
  // Complex harmonics U_k of x.
  auto U = [&](int k, int i) {
    return k == 0 ? std::complex<double>(x[i], 0.0)
                  : std::complex<double>(x[Re(k, i)], x[Im(k, i)]);
  };
  VectorXc Uk(n);
  if (residual) {
    for (int k = 0; k <= H; ++k) {
      for (int i = 0; i < n; ++i) Uk[i] = U(k, i);
      const VectorXc r = Z[k] * Uk + g_h.col(k) - F[k];
      for (int i = 0; i < n; ++i) {
        (*residual)[Re(k, i)] = r[i].real();
        if (k > 0) (*residual)[Im(k, i)] = r[i].imag();
      }
    }
  }
  if (d_omega) {
    for (int k = 0; k <= H; ++k) {
      for (int i = 0; i < n; ++i) Uk[i] = U(k, i);
      const VectorXc r = dZ[k] * Uk - dF[k];
      for (int i = 0; i < n; ++i) {
        (*d_omega)[Re(k, i)] = r[i].real();
        if (k > 0) (*d_omega)[Im(k, i)] = r[i].imag();
      }
    }
  }
  if (!jacobian) return;
  AnalyseJacobian();
  MatrixX& Jm = *jacobian;
  Jm.setZero();
  const std::complex<double> I(0.0, 1.0);
  for (int k = 0; k <= H; ++k) {
    for (int mm = 0; mm <= H; ++mm) {
      // ∂N_k/∂(Re U_m) and ∂N_k/∂(Im U_m), from δU_{±m}: U_m = a + ib, U_{−m} = a − ib.
      MatrixXc dA, dB;
      if (mm == 0) {
        dA = Block(dg_h, k);
      } else {
        const MatrixXc minus = Block(dg_h, k - mm);
        const MatrixXc plus = Block(dg_h, k + mm);
        dA = minus + plus;
        dB = I * (minus - plus);
      }
      if (k == mm) {
        dA += Z[k];
        if (k > 0) dB += I * Z[k];
      }
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          Jm(Re(k, a), Re(mm, b)) = dA(a, b).real();
          if (k > 0) Jm(Im(k, a), Re(mm, b)) = dA(a, b).imag();
          if (mm > 0) {
            Jm(Re(k, a), Im(mm, b)) = dB(a, b).real();
            if (k > 0) Jm(Im(k, a), Im(mm, b)) = dB(a, b).imag();
          }
        }
      }
    }
  }
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
const NhbProblem& NhbSolver::problem() const { return impl_->problem; }

void NhbSolver::Evaluate(const VectorX& x, double omega, VectorX* residual, MatrixX* jacobian,
                         VectorX* d_omega) {
  GEARDYN_CHECK_SIZE(x.size(), impl_->m, "x");
  if (residual) residual->resize(impl_->m);
  if (jacobian) jacobian->resize(impl_->m, impl_->m);
  if (d_omega) d_omega->resize(impl_->m);
  impl_->Evaluate(x, omega, residual, jacobian, d_omega);
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

int NhbSolver::Newton(VectorX& x, double omega, Status* status, double* residual_norm) {
  Impl& s = *impl_;
  GEARDYN_CHECK_SIZE(x.size(), s.m, "x");
  s.UpdateLinear(omega);
  const double tol = s.options.newton_tolerance * s.force_scale;
  int it = 0;
  double rn = 0.0;
  *status = Status::kNotConverged;
  for (; it <= s.options.max_newton_iterations; ++it) {
    s.Evaluate(x, omega, &s.R, &s.J, nullptr);
    rn = s.R.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(rn)) {
      *status = Status::kNumericalIssue;
      break;
    }
    if (rn <= tol) {
      *status = Status::kSuccess;
      break;
    }
    if (it == s.options.max_newton_iterations) break;
    s.lu.compute(s.J);
    s.dx = s.lu.solve(-s.R);
    if (!s.dx.allFinite()) {
      *status = Status::kNumericalIssue;
      break;
    }
    // Backtracking on ‖R‖∞ (Armijo-like, 10 halvings at most).
    double lambda = 1.0;
    bool accepted = false;
    for (int ls = 0; ls < 10; ++ls) {
      s.x_trial = x + lambda * s.dx;
      s.Evaluate(s.x_trial, omega, &s.R_trial, nullptr, nullptr);
      if (s.R_trial.lpNorm<Eigen::Infinity>() < (1.0 - 1e-4 * lambda) * rn) {
        accepted = true;
        break;
      }
      lambda *= 0.5;
    }
    x = s.x_trial;  // the smallest trial step when none was accepted (escape a kink)
    (void)accepted;
  }
  if (residual_norm) *residual_norm = rn;
  return it;
}

void NhbSolver::Describe(const VectorX& x, double omega, NhbPoint& point) {
  Impl& s = *impl_;
  GEARDYN_CHECK_SIZE(x.size(), s.m, "x");
  s.Synthesize(x);
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
  point.maximum = s.u.rowwise().maxCoeff();
  point.minimum = s.u.rowwise().minCoeff();
  point.peak_to_peak = point.maximum - point.minimum;
  point.error_estimate = total > 0 ? std::sqrt(top / total) : 0.0;
}

double NhbSolver::MaxMultiplier(const VectorX& x, double omega) {
  switch (impl_->options.stability) {
    case NhbStabilityMethod::kNone:
      return 0.0;
    case NhbStabilityMethod::kMonodromy:
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
