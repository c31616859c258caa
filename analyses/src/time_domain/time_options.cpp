/// @file
/// @brief Names and validation of the time-response options (time_response.hpp).
#include <cmath>
#include <sstream>

#include "geardyn/analyses/time_response.hpp"

namespace geardyn {
namespace {

/// Writes "field: must be in [lo, hi], got value" into why; false.
template <typename T>
bool OutOfRange(std::string* why, const char* field, T value, const char* bound) {
  if (why != nullptr) {
    std::ostringstream s;
    s << field << ": must be " << bound << ", got " << value;
    *why = s.str();
  }
  return false;
}

bool InRange(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

}  // namespace

const char* ToString(TimeIntegrator integrator) {
  switch (integrator) {
    case TimeIntegrator::kAuto:
      return "auto";
    case TimeIntegrator::kGeneralizedAlpha:
      return "generalized_alpha";
    case TimeIntegrator::kRungeKutta:
      return "runge_kutta";
  }
  return "?";
}

bool ParseTimeIntegrator(const std::string& name, TimeIntegrator* out) {
  for (TimeIntegrator m :
       {TimeIntegrator::kAuto, TimeIntegrator::kGeneralizedAlpha, TimeIntegrator::kRungeKutta}) {
    if (name == ToString(m)) {
      *out = m;
      return true;
    }
  }
  return false;
}

const char* ToString(SteadyVerdict verdict) {
  switch (verdict) {
    case SteadyVerdict::kSteady:
      return "steady";
    case SteadyVerdict::kNotSteady:
      return "not_steady";
    case SteadyVerdict::kUndetermined:
      return "undetermined";
  }
  return "?";
}

const char* ToString(SweepBranch branch) { return branch == SweepBranch::kUp ? "up" : "down"; }

bool TimeIntegrationOptions::IsValid(std::string* why) const {
  if (integrator != TimeIntegrator::kAuto && integrator != TimeIntegrator::kGeneralizedAlpha &&
      integrator != TimeIntegrator::kRungeKutta)
    return OutOfRange(why, "integrator", static_cast<int>(integrator), "a TimeIntegrator");
  if (!(auto_stiffness_limit > 0.0 && auto_stiffness_limit <= 1e6))
    return OutOfRange(why, "auto_stiffness_limit", auto_stiffness_limit, "in (0, 1e6]");
  if (!InRange(relative_tolerance, 1e-14, 1e-2))
    return OutOfRange(why, "relative_tolerance", relative_tolerance, "in [1e-14, 1e-2]");
  if (!InRange(absolute_tolerance, 1e-14, 1.0))
    return OutOfRange(why, "absolute_tolerance", absolute_tolerance, "in [1e-14, 1]");
  if (!InRange(spectral_radius, 0.0, 1.0))
    return OutOfRange(why, "spectral_radius", spectral_radius, "in [0, 1]");
  if (!InRange(newton_tolerance, 1e-10, 0.5))
    return OutOfRange(why, "newton_tolerance", newton_tolerance, "in [1e-10, 0.5]");
  if (max_newton_iterations < 1 || max_newton_iterations > 100)
    return OutOfRange(why, "max_newton_iterations", max_newton_iterations, "in [1, 100]");
  if (!(max_step_fraction > 0.0 && max_step_fraction <= 1.0))
    return OutOfRange(why, "max_step_fraction", max_step_fraction, "in (0, 1]");
  if (max_steps < 1 || max_steps > 1000000000L)
    return OutOfRange(why, "max_steps", max_steps, "in [1, 1e9]");
  if (!InRange(event_time_tolerance, 1e-14, 1e-2))
    return OutOfRange(why, "event_time_tolerance", event_time_tolerance, "in [1e-14, 1e-2]");
  if (samples_per_period < 4 || samples_per_period > 65536)
    return OutOfRange(why, "samples_per_period", samples_per_period, "in [4, 65536]");
  if (sparse_threshold < 1 || sparse_threshold > 10000000)
    return OutOfRange(why, "sparse_threshold", sparse_threshold, "in [1, 1e7]");
  if (channel_decimation < 1 || channel_decimation > 65536)
    return OutOfRange(why, "channel_decimation", channel_decimation, "in [1, 65536]");
  return true;
}

bool SteadyStateOptions::IsValid(std::string* why) const {
  if (!InRange(tolerance, 1e-14, 1.0))
    return OutOfRange(why, "steady.tolerance", tolerance, "in [1e-14, 1]");
  if (consecutive_periods < 1 || consecutive_periods > 1000)
    return OutOfRange(why, "steady.consecutive_periods", consecutive_periods, "in [1, 1000]");
  if (min_periods < 0 || min_periods > 10000000)
    return OutOfRange(why, "steady.min_periods", min_periods, "in [0, 1e7]");
  if (max_periods < 1 || max_periods > 10000000)
    return OutOfRange(why, "steady.max_periods", max_periods, "in [1, 1e7]");
  if (period_multiple < 1 || period_multiple > 1000)
    return OutOfRange(why, "steady.period_multiple", period_multiple, "in [1, 1000]");
  if (record_periods < 1 || record_periods > 1000)
    return OutOfRange(why, "steady.record_periods", record_periods, "in [1, 1000]");
  return true;
}

bool TimeResponseOptions::IsValid(std::string* why) const {
  if (!integration.IsValid(why) || !steady.IsValid(why)) return false;
  if (!std::isfinite(initial_phase))
    return OutOfRange(why, "initial_phase", initial_phase, "finite");
  if (!start_from_static && !initial_state.allFinite())
    return OutOfRange(why, "initial_state", "non-finite entries", "finite");
  return true;
}

bool TimeSweepOptions::IsValid(std::string* why) const {
  if (!response.IsValid(why)) return false;
  if (!up && !down) return OutOfRange(why, "up/down", "both false", "at least one branch");
  return true;
}

}  // namespace geardyn
