/// @file
/// @brief Validation of NhbProblem and the nonlinear HB options; the verdict rule NhbVerdict.
#include <cmath>
#include <sstream>

#include "geardyn/analyses/nonlinear_hb.hpp"

namespace geardyn {
namespace {

bool Fail(std::string* why, const std::string& text) {
  if (why) *why = text;
  return false;
}

}  // namespace

FloquetVerdict NhbVerdict(double max_multiplier, double margin) {
  // A NaN compares false both ways and an inf multiplier comes from a failed product, not a
  // measured growth: neither may read as "unstable" (nor, through std::max, as "stable").
  if (!std::isfinite(max_multiplier)) return FloquetVerdict::kUndetermined;
  return max_multiplier < 1.0 + margin ? FloquetVerdict::kStable : FloquetVerdict::kUnstable;
}

bool NhbProblem::IsValid(std::string* why) const {
  if (!law) return Fail(why, "law: must be set");
  const Eigen::Index N = mass.rows();
  const Eigen::Index n = law->num_coordinates();
  if (N < 1 || mass.cols() != N) return Fail(why, "mass: must be square and non-empty");
  if (damping.rows() != N || damping.cols() != N) return Fail(why, "damping: must be N×N");
  if (stiffness.rows() != N || stiffness.cols() != N) return Fail(why, "stiffness: must be N×N");
  if (projection.rows() != n || projection.cols() != N) {
    std::ostringstream s;
    s << "projection: must be n×N = " << n << "×" << N << ", got " << projection.rows() << "×"
      << projection.cols();
    return Fail(why, s.str());
  }
  if (force_mean.size() != N) return Fail(why, "force_mean: must have N entries");
  if (force_amplitude.size() != N) return Fail(why, "force_amplitude: must have N entries");
  if (!mass.allFinite() || !damping.allFinite() || !stiffness.allFinite() ||
      !projection.allFinite() || !force_mean.allFinite() || !force_amplitude.allFinite()) {
    return Fail(why, "problem matrices and forces: must be finite");
  }
  return true;
}

bool NhbProblem::IsUncondensed() const {
  return projection.rows() == projection.cols() &&
         projection.isApprox(MatrixX::Identity(projection.rows(), projection.cols()), 0.0);
}

bool NhbOptions::IsValid(std::string* why) const {
  std::ostringstream s;
  if (harmonics < 0)
    s << "harmonics: must be ≥ 0 (0 = automatic), got " << harmonics;
  else if (!(harmonic_tolerance > 0))
    s << "harmonic_tolerance: must be > 0, got " << harmonic_tolerance;
  else if (max_harmonics < 1)
    s << "max_harmonics: must be ≥ 1, got " << max_harmonics;
  else if (period_multiple < 1)
    s << "period_multiple: must be ≥ 1, got " << period_multiple;
  else if (samples_per_harmonic < 4)
    s << "samples_per_harmonic: must be ≥ 4 (exact Toeplitz Jacobian), got "
      << samples_per_harmonic;
  else if (samples_per_harmonic > kMaxSamplesPerHarmonic)
    s << "samples_per_harmonic: must be ≤ " << kMaxSamplesPerHarmonic << ", got "
      << samples_per_harmonic << " (an FFT of " << samples_per_harmonic
      << "·H samples per residual; the AFT error is at round-off long before)";
  else if (!(newton_tolerance > 0))
    s << "newton_tolerance: must be > 0, got " << newton_tolerance;
  else if (!(stability_margin >= 0) || !std::isfinite(stability_margin))
    s << "stability_margin: must be finite and ≥ 0, got " << stability_margin;
  else if (max_newton_iterations < 1)
    s << "max_newton_iterations: must be ≥ 1, got " << max_newton_iterations;
  else if (monodromy_steps < 0)
    s << "monodromy_steps: must be ≥ 0 (0 = automatic), got " << monodromy_steps;
  else if (monodromy_steps > kMaxMonodromySteps)
    s << "monodromy_steps: must be ≤ " << kMaxMonodromySteps << ", got " << monodromy_steps
      << " (that many 2N×2N matrix exponentials and products per point)";
  else
    return true;
  return Fail(why, s.str());
}

bool NhbContinuationOptions::IsValid(std::string* why) const {
  std::ostringstream s;
  if (!std::isfinite(omega_start) || !std::isfinite(omega_end) || omega_start == omega_end)
    s << "omega_start/omega_end: must be finite and different";
  else if (omega_start <= 0 || omega_end <= 0)
    s << "omega_start/omega_end: must be > 0";
  else if (!(min_step > 0) || !(initial_step >= min_step) || !(max_step >= initial_step))
    s << "steps: need 0 < min_step ≤ initial_step ≤ max_step";
  else if (max_points < 2)
    s << "max_points: must be ≥ 2, got " << max_points;
  else if (max_points > kMaxPoints)
    s << "max_points: must be ≤ " << kMaxPoints << ", got " << max_points
      << " (every point keeps N·(2H+1) harmonics and 2N multipliers)";
  else if (branch_search < 0 || branch_search > 1000)
    s << "branch_search: must be in [0, 1000] frequencies, got " << branch_search
      << " (each costs 4 Newton solves; the CLI's --branch-search has the same bound)";
  else if (max_corrector_iterations < 1)
    s << "max_corrector_iterations: must be ≥ 1";
  else if (!(max_tangent_angle > 0))
    s << "max_tangent_angle: must be > 0";
  else if (!(max_omega_step >= 0) || !std::isfinite(max_omega_step))
    s << "max_omega_step: must be finite and ≥ 0 (0 = no cap), got " << max_omega_step;
  else if (x_scale < 0 || omega_scale < 0)
    s << "x_scale/omega_scale: must be ≥ 0";
  else if (!(fold_tolerance > 0 && fold_tolerance <= 0.1))
    s << "fold_tolerance: must be in (0, 0.1], got " << fold_tolerance;
  else if (branch_search < 0 || branch_search > kMaxBranchSearch)
    s << "branch_search: must be in [0, " << kMaxBranchSearch << "] frequencies (each costs four "
      << "Newton solves), got " << branch_search;
  else
    return true;
  return Fail(why, s.str());
}

}  // namespace geardyn
