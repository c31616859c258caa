/// @file
/// @brief The two time steppers of the time-domain analyses behind one interface: adaptive
/// steps, event (contact switch) location by Illinois regula falsi on re-steps, and the energy
/// quadrature of the balance (time_response.hpp).
#pragma once

#include <limits>
#include <memory>
#include <string>

#include "geardyn/analyses/time_response.hpp"
#include "td_system.hpp"

namespace geardyn::internal {

/// @brief Error scales of the step control: coordinate i is measured against
/// atol·scale_x(i) + rtol·|x_i|, its velocity against atol·scale_v(i) + rtol·|v_i|.
struct TdScales {
  VectorX x;  ///< (n) [m, rad]
  VectorX v;  ///< (n) [m/s, rad/s]
};

/// @brief One integration method with adaptive steps and event location (see the @file).
///
/// Time t is local to a run; θ = theta0 + omega·t. AdvanceTo(t1) ends exactly at t1. The
/// accumulators phase_work (∫ΣP dt), dissipated (∫(vᵀC0v + ΣD) dt) and gross_flow (Σ over the
/// steps of |phase-work increment| + dissipation increment, plus |energy jump| at each break: the
/// energy the steps moved, the scale of their quadrature error) run from the last
/// ResetQuadrature().
class TdStepper {
 public:
  TdStepper(const TdSystem& sys, const TimeIntegrationOptions& options, TdScales scales,
            double omega, double theta0);
  virtual ~TdStepper() = default;

  /// Sets the state at t (velocity, coordinates) and resets the quadrature.
  void Reset(double t, const VectorX& x, const VectorX& v);
  /// Integrates to t1 ≥ t. False on failure (message()).
  bool AdvanceTo(double t1);
  void ResetQuadrature() { phase_work_ = dissipated_ = gross_flow_ = 0.0; }

  double t() const { return t_; }
  const VectorX& x() const { return x_; }
  const VectorX& v() const { return v_; }
  double phase_work() const { return phase_work_; }
  double dissipated() const { return dissipated_; }
  double gross_flow() const { return gross_flow_; }
  long steps() const { return steps_; }
  long rejected() const { return rejected_; }
  long events() const { return events_; }
  /// Coefficient jumps crossed.
  long breaks() const { return breaks_; }
  /// End of the step that crossed the last located switching zero [s] (NaN before any).
  double last_event_time() const { return last_event_time_; }
  long evaluations() const { return evaluations_; }
  const std::string& message() const { return message_; }
  /// True when the last AdvanceTo stopped at options.max_steps: the run did not finish (a
  /// budget, not a numerical failure; time_response.hpp: "exceeded → kNotConverged").
  bool budget_exhausted() const { return budget_exhausted_; }
  /// θ at local time t [rad].
  double Phase(double t) const { return theta0_ + omega_ * t; }

 protected:
  /// A trial step of length h from the committed state into the trial buffers; returns the
  /// scaled local error (≤ 1: acceptable), +∞ when the step failed (Newton, non-finite).
  virtual double TrialStep(double h) = 0;
  /// Makes the trial state the committed one.
  virtual void Commit() = 0;
  /// Called by Reset after the state is set (e.g. the consistent acceleration).
  virtual void OnReset() {}
  /// Called after a coefficient jump (ws_ holds the forces at the new phase).
  virtual void OnRestart() {}
  /// Order of the local error estimate (step-size exponent 1/(order+1)).
  virtual int order() const = 0;

  /// Evaluates forces at (t, x, v) into ws_ (counts evaluations).
  void Eval(double t, const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
            bool jacobians);
  /// Scaled max-norm of a coordinate error (and velocity error when ev.size() > 0).
  double ErrorNorm(const VectorX& ex, const VectorX& ev, const VectorX& x1,
                   const VectorX& v1) const;

  const TdSystem& sys_;
  TimeIntegrationOptions options_;
  TdScales scales_;
  double omega_, theta0_;
  TdWorkspace ws_;
  double t_ = 0.0;
  VectorX x_, v_;  // committed state
  VectorX trial_x_, trial_v_;
  double trial_h_ = 0.0;
  double trial_work_ = 0.0, trial_dissipated_ = 0.0;  // quadrature increments of the trial
  VectorX switching_, trial_switching_;               // at the committed / trial state
  std::vector<char> live_, trial_live_;
  double phase_work_ = 0.0, dissipated_ = 0.0, gross_flow_ = 0.0;
  double h_ = 0.0, max_step_ = 0.0;
  long steps_ = 0, rejected_ = 0, events_ = 0, evaluations_ = 0, breaks_ = 0;
  double last_event_time_ = std::numeric_limits<double>::quiet_NaN();
  std::string message_;
  bool budget_exhausted_ = false;

 private:
  /// Locates the earliest switching-function zero in the trial step and leaves the trial just
  /// past it. False on failure.
  bool LocateEvent();
  /// Moves from just before a coefficient jump to t_after, just past it, booking the energy jump.
  void CrossBreak(double t_after);
};

/// The GSL rk8pd stepper (rk_stepper.cpp).
std::unique_ptr<TdStepper> MakeRkStepper(const TdSystem& sys, const TimeIntegrationOptions& options,
                                         TdScales scales, double omega, double theta0);
/// The generalized-α stepper (alpha_stepper.cpp).
std::unique_ptr<TdStepper> MakeAlphaStepper(const TdSystem& sys,
                                            const TimeIntegrationOptions& options, TdScales scales,
                                            double omega, double theta0);

/// @brief Makes the stepper of a concrete method (not kAuto).
std::unique_ptr<TdStepper> MakeStepper(TimeIntegrator method, const TdSystem& sys,
                                       const TimeIntegrationOptions& options, TdScales scales,
                                       double omega, double theta0);

}  // namespace geardyn::internal
