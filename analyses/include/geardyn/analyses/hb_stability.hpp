/// @file
/// @brief The Floquet verdict of the linear harmonic-balance points (issue 12): at each mesh
/// frequency f_m, the stability of the homogeneous system M q̈ + C(θ) q̇ + K(θ) q = 0 whose
/// forced periodic solution the linear HB computes (`ComputeHbStability`).
///
/// **Why.** The linear HB solves the truncated periodic equations at any f_m; inside a
/// parametric instability region (f_m ≈ 2 f_r / k for a mode f_r carrying mesh strain energy)
/// that periodic solution exists but is unstable: any perturbation grows like |λ|^{t/T}, so it
/// is not the response the machine settles to. The verdict says so next to the number.
///
/// **How.** ComputeFloquet (floquet.hpp) on the same SystemModel at f_m, with the given
/// FloquetOptions (kAuto: exact step exponentials for piecewise-constant K, C — an LTI model is
/// one interval, Φ = expm(A T), so its verdict is that of the damped modes; Magnus for smooth
/// coefficients; a modal projection from FloquetOptions::modal_projection_min_dofs DOFs). The
/// period is that of K and C (P_K meshes), not the hunting period of the tooth errors: errors
/// force, they do not excite parametrically. The three-valued FloquetVerdict is kept as is.
///
/// Kept apart from the HB solver (a separate pass over the same frequencies): the two share the
/// model only. Reentrant; never prints.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief The Floquet verdict of one linear-HB point.
struct HbPointStability {
  double mesh_frequency_hz = 0.0;  ///< f_m [Hz]
  FloquetVerdict verdict = FloquetVerdict::kUndetermined;
  /// max|λ| over the flexible multipliers [-] (NaN when the Floquet analysis failed).
  double max_abs_multiplier = std::numeric_limits<double>::quiet_NaN();
  double error_estimate = std::numeric_limits<double>::quiet_NaN();  ///< on the multipliers [-]
  bool marginal = false;  ///< stable, but a multiplier on the unit circle (undamped modes)
  FloquetMethod method_used = FloquetMethod::kAuto;
  Status status = Status::kSuccess;  ///< of the Floquet analysis
  std::string message;               ///< why status is not kSuccess
  double wall_time_s = 0.0;          ///< of this point's Floquet analysis [s]
};

/// @brief A closed range of consecutive unstable points.
struct HbUnstableRange {
  double lo_hz = 0.0;               ///< first unstable f_m of the run [Hz]
  double hi_hz = 0.0;               ///< last unstable f_m of the run [Hz]
  int points = 0;                   ///< points in the run [-]
  double max_abs_multiplier = 0.0;  ///< largest max|λ| in the run [-]
};

/// @brief The verdicts of a sweep.
struct HbStabilitySweep {
  std::vector<HbPointStability> points;          ///< one per frequency, in the given order
  std::vector<HbUnstableRange> unstable_ranges;  ///< runs of kUnstable in the given order
  /// kSuccess unless a verdict is kUndetermined (then kNumericalIssue, the message names the
  /// first such point and the count). warnings: one per unstable range ("parametrically
  /// unstable at f_m = lo … hi Hz (n points, max|λ| up to x): ..."), then the Floquet warnings
  /// of the first point that has any (prefixed "Floquet: ").
  Summary summary;
};

/// @brief The verdict at one mesh frequency f_m [Hz] > 0 (options.mesh_frequency_hz is
/// replaced by f_m).
/// @throws InvalidInput as ComputeFloquet (invalid options, a nonlinear core, f_m ≤ 0).
HbPointStability ComputeHbPointStability(const SystemModel& model, double mesh_frequency_hz,
                                         const FloquetOptions& options);

/// @brief The verdicts at every mesh frequency [Hz] and the unstable ranges (runs of
/// consecutive kUnstable points in the given order).
HbStabilitySweep ComputeHbStability(const SystemModel& model,
                                    const std::vector<double>& mesh_frequencies_hz,
                                    const FloquetOptions& options);

}  // namespace geardyn
