// kOdeStepper: the general reference path. GSL odeiv2 rk8pd (Dormand–Prince 8(9)) integrates the
// fundamental matrix Ż = A(t) Z, Z(0) = I over one period; with piecewise-constant coefficients
// every interval is integrated separately (the stepper never steps across a jump). The error
// estimate is the change of the multipliers between local tolerances 0.01·tol and 1e-4·tol
// (floored at 1e-15): an estimate of the looser run's error, conservative for the tighter run
// that is reported.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn::internal {
namespace {

struct Context {
  const StateSystem* sys = nullptr;
  const MatrixX* constant = nullptr;  // the interval's A (piecewise form), else null
  MatrixX A;
  long evaluations = 0;
};

int Rhs(double t, const double y[], double f[], void* params) {
  auto* ctx = static_cast<Context*>(params);
  const int N = ctx->sys->dim;
  const Eigen::Map<const MatrixX> Y(y, N, N);
  Eigen::Map<MatrixX> F(f, N, N);
  if (ctx->constant != nullptr) {
    F.noalias() = *ctx->constant * Y;
  } else {
    ctx->sys->evaluate(t, &ctx->A);
    F.noalias() = ctx->A * Y;
  }
  ++ctx->evaluations;
  return GSL_SUCCESS;
}

// One run; false (with the GSL code in *message) on failure.
bool Integrate(const StateSystem& sys, double eps, MonodromyOutcome* out) {
  const int N = sys.dim;
  Context ctx;
  ctx.sys = &sys;
  ctx.A.resize(N, N);
  gsl_odeiv2_system ode{Rhs, nullptr, static_cast<std::size_t>(N) * N, &ctx};
  MatrixX Z = MatrixX::Identity(N, N);
  std::vector<double> ends;
  const bool piecewise = !sys.step_matrices.empty();
  if (piecewise) {
    double t = 0.0;
    for (double d : sys.step_durations) ends.push_back(t += d);
    ends.back() = sys.period_s;
  } else {
    ends.push_back(sys.period_s);
  }
  double t = 0.0;
  out->phi = ScaledMatrix{MatrixX::Identity(N, N), 0.0};
  // First trial step h‖A‖₁ ≤ 1 (as the Magnus start, magnus.cpp): rk8pd's stability region
  // reaches |hλ| ≈ 5, so a larger first step is rejected anyway; the controller then adapts.
  const double norm = MaxOperatorNormTimesPeriod(sys, nullptr) / sys.period_s;
  const double h_norm = norm > 0.0 && std::isfinite(norm) ? 1.0 / norm : sys.period_s;
  for (std::size_t k = 0; k < ends.size(); ++k) {
    ctx.constant = piecewise ? &sys.step_matrices[k] : nullptr;
    const double h0 = std::min({ends[k] - t, sys.period_s / 64.0, h_norm});
    gsl_odeiv2_driver* driver =
        gsl_odeiv2_driver_alloc_y_new(&ode, gsl_odeiv2_step_rk8pd, h0, eps, eps);
    gsl_odeiv2_driver_set_nmax(driver, 50'000'000);
    const int status = gsl_odeiv2_driver_apply(driver, &t, ends[k], Z.data());
    out->steps += static_cast<long>(driver->n);
    gsl_odeiv2_driver_free(driver);
    if (status != GSL_SUCCESS) {
      out->converged = false;
      out->message = std::string("ode_stepper: GSL odeiv2 failed at t = ") + std::to_string(t) +
                     " s: " + gsl_strerror(status);
      return false;
    }
  }
  if (!Z.allFinite()) {
    out->converged = false;
    out->message = "ode_stepper: the fundamental matrix has non-finite entries";
    return false;
  }
  out->phi.matrix = Z;
  out->phi.Normalize();
  out->evaluations += ctx.evaluations;
  out->num_factors = static_cast<double>(out->steps);
  return true;
}

}  // namespace

MonodromyOutcome OdeMonodromy(const StateSystem& sys, double tolerance) {
  GEARDYN_THROW_UNLESS(static_cast<bool>(sys.evaluate) || !sys.step_matrices.empty(),
                       "method: ode_stepper needs the coefficients callback or steps");
  gsl_error_handler_t* old = gsl_set_error_handler_off();
  MonodromyOutcome loose, tight;
  const double eps1 = std::max(1e-15, 0.01 * tolerance);
  const double eps2 = std::max(1e-15, 1e-4 * tolerance);
  const bool ok = Integrate(sys, eps1, &loose) && Integrate(sys, eps2, &tight);
  gsl_set_error_handler(old);
  if (!ok) {
    // NaN, never the identity: a failed run must not read as |λ| = 1 (stable).
    MonodromyOutcome& failed = loose.converged ? tight : loose;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    failed.phi = ScaledMatrix{MatrixX::Constant(sys.dim, sys.dim, nan), 0.0};
    failed.truncation_error = nan;
    return failed;
  }
  tight.truncation_error = RelativeDifference(loose.phi, tight.phi);
  tight.evaluations += loose.evaluations;
  if (!(tight.truncation_error <= tolerance)) {
    tight.converged = false;
    tight.message = "ode_stepper: relative error estimate of the monodromy " +
                    FormatEstimate(tight.truncation_error) + " above the tolerance";
  }
  return tight;
}

}  // namespace geardyn::internal
