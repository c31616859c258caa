/// @file
/// @brief TdStepper: the adaptive step loop and the event location shared by both methods.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geardyn/common/check.hpp"
#include "td_steppers.hpp"

namespace geardyn::internal {

TdStepper::TdStepper(const TdSystem& sys, const TimeIntegrationOptions& options, TdScales scales,
                     double omega, double theta0)
    : sys_(sys),
      options_(options),
      scales_(std::move(scales)),
      omega_(omega),
      theta0_(theta0),
      ws_(sys) {
  const double mesh_period = 2.0 * std::numbers::pi / omega;
  max_step_ = options.max_step_fraction * mesh_period;
  h_ = std::min(max_step_, mesh_period / 200.0);
  x_ = trial_x_ = VectorX::Zero(sys.n);
  v_ = trial_v_ = VectorX::Zero(sys.n);
  switching_ = trial_switching_ = VectorX::Zero(sys.num_switching);
  live_.assign(static_cast<std::size_t>(sys.num_switching), 0);
  trial_live_ = live_;
}

void TdStepper::Reset(double t, const VectorX& x, const VectorX& v) {
  t_ = t;
  if (sys_.has_breaks) {
    // Starting on a break (θ₀ = 0 is a table node): begin just past it, so that no evaluation
    // straddles it.
    double margin = 0.0;
    const double back = t - 1e-6 * 2.0 * std::numbers::pi / omega_;
    const double tb = sys_.NextBreakTime(back, theta0_, omega_, &margin);
    if (std::abs(tb - t) <= margin) t_ = tb + margin;
  }
  x_ = x;
  v_ = v;
  ResetQuadrature();
  Eval(t, x_, v_, false);
  switching_ = ws_.switching;
  live_ = ws_.switching_live;
  OnReset();
}

void TdStepper::Eval(double t, const Eigen::Ref<const VectorX>& x,
                     const Eigen::Ref<const VectorX>& v, bool jacobians) {
  ++evaluations_;
  EvalForces(sys_, ws_, Phase(t), omega_, x, v, jacobians);
}

double TdStepper::ErrorNorm(const VectorX& ex, const VectorX& ev, const VectorX& x1,
                            const VectorX& v1) const {
  const double atol = options_.absolute_tolerance, rtol = options_.relative_tolerance;
  double err = 0.0;
  for (Eigen::Index i = 0; i < ex.size(); ++i) {
    const double sx = atol * scales_.x(i) + rtol * std::max(std::abs(x_(i)), std::abs(x1(i)));
    err = std::max(err, std::abs(ex(i)) / sx);
    if (ev.size() > 0) {
      const double sv = atol * scales_.v(i) + rtol * std::max(std::abs(v_(i)), std::abs(v1(i)));
      err = std::max(err, std::abs(ev(i)) / sv);
    }
  }
  // NaN propagates as +∞: a failed step, never an accepted one.
  return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
}

bool TdStepper::AdvanceTo(double t1) {
  const double t_tol = 1e-14 * std::max(std::abs(t1), 2.0 * std::numbers::pi / omega_);
  while (t1 - t_ > t_tol) {
    if (steps_ + rejected_ >= options_.max_steps) {
      message_ = "time integration: max_steps = " + std::to_string(options_.max_steps) +
                 " reached at t = " + std::to_string(t_) + " s";
      budget_exhausted_ = true;
      return false;
    }
    // A jump of a piecewise-constant coefficient ahead: step to just before it, then across.
    double target = t1;
    if (sys_.has_breaks) {
      double margin = 0.0;
      const double tb = sys_.NextBreakTime(t_, theta0_, omega_, &margin);
      if (tb - margin - t_ <= t_tol) {
        CrossBreak(tb + margin);
        continue;
      }
      target = std::min(t1, tb - margin);
    }
    double h = std::min({h_, max_step_, target - t_});
    // Do not leave a sliver: stretch to the target when the rest is within 10 % of a step.
    if (target - t_ - h < 0.1 * h) h = target - t_;
    double err = TrialStep(h);
    while (!(err <= 1.0)) {
      ++rejected_;
      const double factor = std::isfinite(err)
                                ? std::clamp(0.9 * std::pow(err, -1.0 / (order() + 1)), 0.1, 0.9)
                                : 0.25;
      h *= factor;
      if (h < 1e-14 * (2.0 * std::numbers::pi / omega_)) {
        message_ = "time integration: step size underflow at t = " + std::to_string(t_) +
                   " s (θ = " + std::to_string(Phase(t_)) + " rad)" +
                   (std::isfinite(err) ? "" : ": the step failed (non-finite or no convergence)");
        return false;
      }
      if (steps_ + rejected_ >= options_.max_steps) {
        message_ = "time integration: max_steps = " + std::to_string(options_.max_steps) +
                   " reached while reducing the step at t = " + std::to_string(t_) + " s";
        budget_exhausted_ = true;
        return false;
      }
      err = TrialStep(h);
    }
    const double grow = err > 0.0 ? 0.9 * std::pow(err, -1.0 / (order() + 1)) : 4.0;
    const double h_next = h * std::clamp(grow, 0.2, 4.0);
    if (options_.locate_events && sys_.num_switching > 0 && !LocateEvent()) return false;
    Commit();
    phase_work_ += trial_work_;
    dissipated_ += trial_dissipated_;
    gross_flow_ += std::abs(trial_work_) + std::abs(trial_dissipated_);
    t_ += trial_h_;
    switching_ = trial_switching_;
    live_ = trial_live_;
    ++steps_;
    // After an event keep the step that reached it (the next one starts on the new side).
    h_ = std::min(h_next, max_step_);
  }
  // Within t_tol of t1: land on it. Past it (a break crossed at t1 moved t_ beyond by the gap):
  // stay there, so that the next step starts on the far side of the break and no evaluation
  // straddles it.
  if (t_ < t1) t_ = t1;
  return true;
}

void TdStepper::CrossBreak(double t_after) {
  // The state is continuous; the stored energy jumps by E(θ+) − E(θ−) at fixed coordinates:
  // work done by the prescribed mesh motion, booked as phase work.
  Eval(t_, x_, v_, false);
  const double before = ws_.mesh_energy;
  t_ = t_after;
  Eval(t_, x_, v_, false);
  phase_work_ += ws_.mesh_energy - before;
  gross_flow_ += std::abs(ws_.mesh_energy - before);
  switching_ = ws_.switching;
  live_ = ws_.switching_live;
  ++breaks_;
  OnRestart();
}

bool TdStepper::LocateEvent() {
  // The earliest live sign change by linear interpolation of the switching functions.
  const double h = trial_h_;
  int first = -1;
  double tau_first = 2.0;
  for (int i = 0; i < sys_.num_switching; ++i) {
    const auto s = static_cast<std::size_t>(i);
    if (!live_[s] || !trial_live_[s]) continue;
    const double g0 = switching_(i), g1 = trial_switching_(i);
    if ((g0 > 0.0) == (g1 > 0.0)) continue;
    const double tau = g0 / (g0 - g1);
    if (tau < tau_first) {
      tau_first = tau;
      first = i;
    }
  }
  if (first < 0) return true;
  ++events_;
  // Illinois regula falsi on g_first(τ h), τ ∈ (a, b], each value from a re-step of length τ h.
  const double t_tol = options_.event_time_tolerance * 2.0 * std::numbers::pi / omega_;
  double a = 0.0, b = 1.0;
  double ga = switching_(first), gb = trial_switching_(first);
  const bool sign0 = ga > 0.0;
  int side = 0;
  for (int it = 0; it < 100 && (b - a) * h > t_tol; ++it) {
    double tau = (a * gb - b * ga) / (gb - ga);
    if (!(tau > a && tau < b)) tau = 0.5 * (a + b);
    // Keep the bracket shrinking even when regula falsi stalls near an end.
    tau = std::clamp(tau, a + 1e-3 * (b - a), b - 1e-3 * (b - a));
    if (!std::isfinite(TrialStep(tau * h))) {
      message_ = "time integration: re-step failed while locating a contact switch";
      return false;
    }
    const double g = trial_switching_(first);
    if ((g > 0.0) == sign0) {
      a = tau;
      ga = g;
      if (side == -1) gb *= 0.5;  // Illinois: halve the retained end
      side = -1;
    } else {
      b = tau;
      gb = g;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  // The committed step ends just past the crossing.
  if (!std::isfinite(TrialStep(b * h))) {
    message_ = "time integration: re-step failed while locating a contact switch";
    return false;
  }
  last_event_time_ = t_ + trial_h_;
  return true;
}

}  // namespace geardyn::internal

namespace geardyn::internal {

std::unique_ptr<TdStepper> MakeStepper(TimeIntegrator method, const TdSystem& sys,
                                       const TimeIntegrationOptions& options, TdScales scales,
                                       double omega, double theta0) {
  GEARDYN_DEMAND(method != TimeIntegrator::kAuto);
  if (method == TimeIntegrator::kRungeKutta)
    return MakeRkStepper(sys, options, std::move(scales), omega, theta0);
  return MakeAlphaStepper(sys, options, std::move(scales), omega, theta0);
}

}  // namespace geardyn::internal
