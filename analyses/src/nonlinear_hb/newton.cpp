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
  if (residual_norm) *residual_norm = rn;
  return it;
}

}  // namespace geardyn
