/// @file
/// @brief NhbSolver::Newton: damped Newton with backtracking on ‖R‖∞; when it stagnates (the
/// Newton direction is poor near grazing contact, where the residual is only C¹ and its
/// Jacobian changes fast) Powell's hybrid dogleg trust-region method of GSL
/// (gsl_multiroot_fdfsolver_hybridsj) takes over from the initial guess (from the stagnated
/// iterate it stalls as well: the damped steps end next to a grazing configuration).
#include <gsl/gsl_errno.h>
#include <gsl/gsl_multiroots.h>

#include <algorithm>
#include <cmath>

#include "geardyn/common/check.hpp"
#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {
namespace {

/// Backtracking steps shorter than this …
constexpr double kShortStep = 0.125;
/// … in this many consecutive iterations hand the solve to Powell's hybrid method.
constexpr int kStagnantIterations = 3;
/// Newton homotopy (NhbSolver::Impl::Homotopy): first λ step, smallest step, Newton iterations
/// per step.
constexpr double kHomotopyFirstStep = 0.1;
constexpr double kHomotopyMinStep = 1e-4;
constexpr int kHomotopyIterations = 12;
constexpr double kHomotopyMaxStep = 0.2;

void CopyIn(const gsl_vector* v, VectorX& x) {
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = gsl_vector_get(v, static_cast<size_t>(i));
}

}  // namespace

int NhbSolver::Impl::PowellHybrid(VectorX& x, double omega, double tol, double* residual_norm) {
  struct Context {
    Impl* solver;
    double omega;
  };
  // The callbacks evaluate into the scratch x_trial, R_trial and J (never the caller's x).
  static constexpr auto kResidual = [](const gsl_vector* v, void* params, gsl_vector* f) -> int {
    auto& c = *static_cast<Context*>(params);
    Impl& s = *c.solver;
    CopyIn(v, s.x_trial);
    s.Evaluate(s.x_trial, c.omega, &s.R_trial, nullptr, nullptr);
    for (int i = 0; i < s.m; ++i) gsl_vector_set(f, static_cast<size_t>(i), s.R_trial[i]);
    return s.R_trial.allFinite() ? GSL_SUCCESS : GSL_EBADFUNC;
  };
  static constexpr auto kResidualJacobian = [](const gsl_vector* v, void* params, gsl_vector* f,
                                               gsl_matrix* jac) -> int {
    auto& c = *static_cast<Context*>(params);
    Impl& s = *c.solver;
    CopyIn(v, s.x_trial);
    s.Evaluate(s.x_trial, c.omega, &s.R_trial, &s.J, nullptr);
    for (int i = 0; i < s.m; ++i) {
      gsl_vector_set(f, static_cast<size_t>(i), s.R_trial[i]);
      for (int j = 0; j < s.m; ++j) {
        gsl_matrix_set(jac, static_cast<size_t>(i), static_cast<size_t>(j), s.J(i, j));
      }
    }
    return s.R_trial.allFinite() && s.J.allFinite() ? GSL_SUCCESS : GSL_EBADFUNC;
  };
  static constexpr auto kJacobian = [](const gsl_vector* v, void* params, gsl_matrix* jac) -> int {
    gsl_vector* f = gsl_vector_alloc(static_cast<size_t>(static_cast<Context*>(params)->solver->m));
    const int status = kResidualJacobian(v, params, f, jac);
    gsl_vector_free(f);
    return status;
  };
  Context context{this, omega};
  const size_t size = static_cast<size_t>(m);
  gsl_multiroot_function_fdf function{kResidual, kJacobian, kResidualJacobian, size, &context};
  gsl_vector* start = gsl_vector_alloc(size);
  for (size_t i = 0; i < size; ++i) gsl_vector_set(start, i, x[static_cast<Eigen::Index>(i)]);
  gsl_error_handler_t* old_handler = gsl_set_error_handler_off();  // report, never abort
  gsl_multiroot_fdfsolver* solver =
      gsl_multiroot_fdfsolver_alloc(gsl_multiroot_fdfsolver_hybridsj, size);
  int it = 0;
  if (gsl_multiroot_fdfsolver_set(solver, &function, start) == GSL_SUCCESS) {
    for (; it < options.max_newton_iterations; ++it) {
      double rn = 0.0;
      for (size_t i = 0; i < size; ++i) rn = std::max(rn, std::abs(gsl_vector_get(solver->f, i)));
      if (rn <= tol) break;
      if (gsl_multiroot_fdfsolver_iterate(solver) != GSL_SUCCESS) break;
    }
    CopyIn(solver->x, x);
  }
  gsl_multiroot_fdfsolver_free(solver);
  gsl_vector_free(start);
  gsl_set_error_handler(old_handler);
  Evaluate(x, omega, &R, nullptr, nullptr);
  *residual_norm = R.lpNorm<Eigen::Infinity>();
  return it;
}

double NhbSolver::ResidualTolerance(double omega) {
  impl_->UpdateLinear(omega);
  return impl_->options.newton_tolerance * impl_->force_scale;
}

int NhbSolver::Newton(VectorX& x, double omega, Status* status, double* residual_norm) {
  Impl& s = *impl_;
  GEARDYN_CHECK_SIZE(x.size(), s.m, "x");
  s.UpdateLinear(omega);
  const double tol = s.options.newton_tolerance * s.force_scale;
  int it = 0;
  int short_steps = 0;
  double rn = 0.0;
  s.x_start = x;
  *status = Status::kNotConverged;
  // Newton homotopy R(x) − (1 − λ) R(x₀) = 0, λ: 0 → 1 in adaptive steps from x = x₀ (x is
  // overwritten with the last point reached); kSuccess when λ = 1 with ‖R‖∞ ≤ tol. Returns the
  // Newton iterations used.
  auto homotopy = [&s, omega, tol](VectorX& hx, Status* hstatus, double* hnorm) -> int {
    s.Evaluate(hx, omega, &s.R, nullptr, nullptr);
    const VectorX r0 = s.R;  // R(x₀)
    int total = 0;
    // Damped Newton on R(hx) − shift = 0 from hx; true when ‖·‖∞ ≤ target.
    auto solve = [&](const VectorX& shift, double target, VectorX& xs, double* norm) {
      for (int k = 0; k < kHomotopyIterations; ++k, ++total) {
        s.Evaluate(xs, omega, &s.R, &s.J, nullptr);
        s.R -= shift;
        const double hr = s.R.lpNorm<Eigen::Infinity>();
        *norm = hr;
        if (!std::isfinite(hr)) return false;
        if (hr <= target) return true;
        s.lu.compute(s.J);
        s.dx = s.lu.solve(-s.R);
        if (!s.dx.allFinite()) return false;
        double step = 1.0;
        for (int ls = 0; ls < 10; ++ls) {
          s.x_trial = xs + step * s.dx;
          s.Evaluate(s.x_trial, omega, &s.R_trial, nullptr, nullptr);
          s.R_trial -= shift;
          if (s.R_trial.lpNorm<Eigen::Infinity>() < (1.0 - 1e-4 * step) * hr) break;
          step *= 0.5;
        }
        xs = s.x_trial;
      }
      return false;
    };
    // Pseudo-arclength in (x/x_scale, λ): the path folds in λ where contact is lost (the
    // contact branch softens and turns back), so λ alone cannot parametrize it.
    const int mm = s.m;
    const double xs_scale = std::max(hx.norm(), 1e-300);
    Eigen::PartialPivLU<MatrixX> blu;
    MatrixX B(mm + 1, mm + 1);
    VectorX rhs(mm + 1), dz(mm + 1);
    // Unit tangent at (x, λ) (scaled), oriented along `previous`: J x' = −r0, λ' = 1.
    auto tangent_at = [&](const VectorX& xx, double l, const VectorX& previous, VectorX* t) {
      s.Evaluate(xx, omega, &s.R, &s.J, nullptr);
      s.lu.compute(s.J);
      const VectorX xp = s.lu.solve(-r0);
      if (!xp.allFinite()) return false;
      t->resize(mm + 1);
      t->head(mm) = xp / xs_scale;
      (*t)[mm] = 1.0;
      t->normalize();
      if (previous.size() == mm + 1 && t->dot(previous) < 0.0) *t = -*t;
      (void)l;
      return true;
    };
    double lambda = 0.0, ds = kHomotopyFirstStep;
    double hr = r0.lpNorm<Eigen::Infinity>();
    *hstatus = Status::kNotConverged;
    VectorX t;
    if (!tangent_at(hx, 0.0, VectorX(), &t)) return total;
    VectorX x_prev = hx;
    double lambda_prev = 0.0;
    while (lambda < 1.0 && ds >= kHomotopyMinStep && total < 20 * s.options.max_newton_iterations) {
      // Every predictor step counts (issue 16): a corrector that converges at its first
      // evaluation leaves the loop before its own ++total, so a path that runs away from λ = 1
      // (λ → −∞ seen with a back gap of 1e12) would otherwise never reach the limit.
      ++total;
      // Predictor along the tangent, corrector on [R − (1 − λ) r0; tᵀ(y − y_pred)] = 0.
      const VectorX xpred = hx + ds * xs_scale * t.head(mm);
      const double lpred = lambda + ds * t[mm];
      VectorX xc = xpred;
      double lc = lpred;
      bool ok = false;
      for (int k = 0; k < kHomotopyIterations; ++k, ++total) {
        s.Evaluate(xc, omega, &s.R, &s.J, nullptr);
        s.R -= (1.0 - lc) * r0;
        hr = s.R.lpNorm<Eigen::Infinity>();
        if (!std::isfinite(hr)) break;
        if (hr <= 1e3 * tol) {
          ok = true;
          break;
        }
        B.topLeftCorner(mm, mm) = s.J;
        B.topRightCorner(mm, 1) = r0;  // ∂/∂λ of R − (1 − λ) r0
        B.bottomLeftCorner(1, mm) = t.head(mm).transpose() / xs_scale;
        B(mm, mm) = t[mm];
        rhs.head(mm) = -s.R;
        rhs[mm] = -(t.head(mm).dot(xc - xpred) / xs_scale + t[mm] * (lc - lpred));
        blu.compute(B);
        dz = blu.solve(rhs);
        if (!dz.allFinite()) break;
        xc += dz.head(mm);
        lc += dz[mm];
      }
      if (!ok) {
        ds *= 0.5;
        continue;
      }
      x_prev = hx;
      lambda_prev = lambda;
      hx = xc;
      lambda = lc;
      ds = std::min(1.5 * ds, kHomotopyMaxStep);
      VectorX t_new;
      if (!tangent_at(hx, lambda, t, &t_new)) break;
      t = t_new;
    }
    if (lambda >= 1.0) {
      // Passed λ = 1: interpolate between the last two points, then Newton at λ = 1.
      const double w = (1.0 - lambda_prev) / (lambda - lambda_prev);
      VectorX xs = x_prev + w * (hx - x_prev);
      if (solve(VectorX::Zero(mm), tol, xs, &hr)) {
        hx = xs;
      } else {
        lambda = 0.0;  // not reached
      }
    }
    if (lambda >= 1.0) {
      s.Evaluate(hx, omega, &s.R, nullptr, nullptr);
      hr = s.R.lpNorm<Eigen::Infinity>();
      *hstatus = hr <= tol ? Status::kSuccess : Status::kNotConverged;
    } else if (!std::isfinite(hr)) {
      *hstatus = Status::kNumericalIssue;
    }
    *hnorm = hr;
    return total;
  };

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
    if (short_steps >= kStagnantIterations) {
      x = s.x_start;
      it += s.PowellHybrid(x, omega, tol, &rn);
      if (rn <= tol) {
        *status = Status::kSuccess;
      } else if (!std::isfinite(rn)) {
        *status = Status::kNumericalIssue;
      }
      break;
    }
    s.lu.compute(s.J);
    s.dx = s.lu.solve(-s.R);
    if (!s.dx.allFinite()) {
      *status = Status::kNumericalIssue;
      break;
    }
    // Backtracking on ‖R‖∞ (Armijo-like, 10 halvings at most).
    double lambda = 1.0;
    for (int ls = 0; ls < 10; ++ls) {
      s.x_trial = x + lambda * s.dx;
      s.Evaluate(s.x_trial, omega, &s.R_trial, nullptr, nullptr);
      if (s.R_trial.lpNorm<Eigen::Infinity>() < (1.0 - 1e-4 * lambda) * rn) break;
      lambda *= 0.5;
    }
    x = s.x_trial;  // the smallest trial step when none was accepted (escape a kink)
    short_steps = lambda < kShortStep ? short_steps + 1 : 0;
  }
  if (*status == Status::kNotConverged) {
    // Issue 13: from the contact guess of a gear system with back-flank contact both damped
    // Newton and the dogleg stall (measured: ‖R‖∞ 180 → 55 N at 1 600 Hz on the spur pair with
    // backlash). The Newton homotopy R(x) − (1 − λ) R(x₀) = 0 starts at its solution x₀ (λ = 0)
    // and reaches R = 0 at λ = 1 in steps small enough for Newton from the previous point.
    VectorX homotopy_x = s.x_start;
    const int used = homotopy(homotopy_x, status, &rn);
    it += used;
    if (*status == Status::kSuccess) x = homotopy_x;
  }
  if (residual_norm) *residual_norm = rn;
  return it;
}

}  // namespace geardyn
