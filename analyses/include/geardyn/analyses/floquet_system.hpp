/// @file
/// @brief The generic layer under ComputeFloquet: a periodic second-order system given by its
/// matrices (no SystemModel), for SDOF/Mathieu/Meissner charts and for tests.
///
/// **Problem.** M q̈ + C(t) q̇ + K(t) q = 0, t ∈ [0, T), K and C T-periodic, M constant symmetric
/// positive definite (n×n). Units are the caller's (SI: M [kg], C [N·s/m], K [N/m], t [s]); the
/// multipliers are dimensionless and the exponents are in 1/[t].
///
/// **Forms of K(t), C(t)** (give one or more):
/// * `steps`: piecewise constant — step k lasts steps[k].duration_s with constant K_k, C_k (the
///   durations sum to T). Enables kExactSteps (Φ = Π expm(A_k Δt_k), no time stepping).
/// * `coefficients`: a callback filling K(t), C(t) (n×n) at any t ∈ [0, T]. Enables kMagnus and
///   kOdeStepper. If only `steps` is given, a callback is made from it.
/// * `stiffness_harmonics`, `damping_harmonics`: K(t) = Σ_{m=−N..N} K_m e^{imΩt}, Ω = 2π/T,
///   K_{−m} = conj(K_m), index m = 0 … N. Enables kHill (the Hill matrix uses |m| ≤ 2H).
///
/// **What ComputeFloquet(PeriodicSecondOrderSystem, options) does** (the same engine as the
/// SystemModel front end; options.mesh_frequency_hz is ignored, T is `period_s`):
/// 1. Rigid-body deflation (options.deflate_rigid_modes, symmetric K and C only): the common null
///    space R of the mean K̄ and C̄ (both PSD: R = null(K̄ + ω_s C̄) from the generalized eigen
///    problem with M, zero threshold 1e-10·s as in ComputeModes) is split off with the
///    M-orthogonal complement F (Fᵀ M R = 0): then ä = 0 exactly for q = R a + F b, and each
///    rigid mode gives two multipliers exactly 1 (Φ = [[I, T I], [0, I]] on (a, ȧ)).
/// 2. Scaling: M_f = Fᵀ M F = L Lᵀ, y = Lᵀ b, state z = [y; ẏ/ω_s] with ω_s = √s (s = max diag
///    of L⁻¹ K̄_f L⁻ᵀ, the spectrum scale): ż = A(t) z,
///    A = [[0, ω_s I], [−L⁻¹K_f L⁻ᵀ/ω_s, −L⁻¹C_f L⁻ᵀ]]. An undamped LTI A is then skew-symmetric
///    (normal), which keeps the eigenvalue condition numbers of Φ near 1.
/// 3. The method (see floquet.hpp): kAuto → kExactSteps with `steps`, else kMagnus with
///    `coefficients`, else kHill. kModalProjection projects on the lowest modes of (K̄, M).
/// 4. Multipliers of Φ (Eigen's real Schur), sorted by |λ| descending; exponents
///    μ = (ln λ)/T (principal branch, computed from the scaled product, so no overflow).
///
/// **Error estimate** (FloquetResult::summary.error_estimate, absolute on the multipliers, |λ| ~
/// 1): from the relative error e of Φ — Magnus: step doubling (Richardson, e ≈ ‖Φ_2N − Φ_N‖/‖Φ‖ /
/// (2^p − 1)); ODE: the change between two local tolerances; exact steps: 0 — plus the round-off
/// δ = (ε·(10·2n + number of factors) + e)·‖Φ‖, turned into max_i min(κ_i δ, √(δ‖Φ‖)) with κ_i
/// the eigenvalue condition number (‖x_i‖‖y_i‖/|y_iᴴx_i|); the √ bound covers double multipliers
/// (at a transition curve a multiplier error of √δ is unavoidable). kMagnus and kOdeStepper meet
/// options.tolerance on e (status kToleranceNotMet otherwise). kHill: the multiplier change from
/// H to the previous (or 2H/3) truncation; kModalProjection: from three bases m, ⌈1.5m⌉, ⌈2.25m⌉
/// 4× the larger of the two multiplier changes (see modal_projection.cpp);
/// kArpackMonodromy: the Ritz residuals (floquet.hpp). The verdict is stable when max|λ| ≤ 1 +
/// error_estimate.
#pragma once

#include <functional>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief One interval of constant coefficients.
struct PeriodicStep {
  double duration_s = 0.0;  ///< Δt_k > 0 [s]
  MatrixX stiffness;        ///< K_k (n×n)
  MatrixX damping;          ///< C_k (n×n), or empty for C = 0
};

/// @brief M q̈ + C(t) q̇ + K(t) q = 0 with T-periodic K, C (see the @file).
struct PeriodicSecondOrderSystem {
  MatrixX mass;           ///< M (n×n), symmetric positive definite
  double period_s = 0.0;  ///< T > 0 [s]
  /// Piecewise-constant form (may be empty).
  std::vector<PeriodicStep> steps;
  /// Smooth form: fills K(t) and C(t) (n×n, resized by the callee) at t ∈ [0, T] [s]. May be empty.
  std::function<void(double t, MatrixX* K, MatrixX* C)> coefficients;
  /// Fourier form for kHill: K_m, C_m, m = 0 … N (C may be empty for C = 0).
  std::vector<MatrixXc> stiffness_harmonics;
  std::vector<MatrixXc> damping_harmonics;
  /// Times t ∈ [0, T) [s] where the callback's K(t) or C(t) is not smooth (jumps, or the kinks of
  /// linearly interpolated tables), in any order. kMagnus and kArpackMonodromy end their steps on
  /// them once the steps are shorter than the gaps, so a kink costs no order (issue 12). Empty:
  /// smooth. The step starts of `steps` are added automatically.
  std::vector<double> kinks_s;

  /// n.
  int num_dofs() const { return static_cast<int>(mass.rows()); }
};

/// @brief An SDOF system x'' + c x' + k(t) x = 0 with a rectangular-wave stiffness: k = k_hi for
/// the first fraction `duty` of the period T, k_lo for the rest (the Meissner equation; m = 1).
PeriodicSecondOrderSystem MakeMeissnerSystem(double k_hi, double k_lo, double duty, double period_s,
                                             double damping = 0.0);

/// @brief The Mathieu equation x'' + c x' + (δ + ε cos Ωt) x = 0 with Ω = 2π/T (callback and
/// harmonics forms; m = 1).
PeriodicSecondOrderSystem MakeMathieuSystem(double delta, double epsilon, double period_s,
                                            double damping = 0.0);

/// @brief Floquet multipliers of `system` (see the @file). options.mesh_frequency_hz is ignored.
/// @throws InvalidInput on invalid options (the field named), a non-square or non-SPD M, sizes
///   that do not match n, non-positive durations, durations not summing to T, or a method whose
///   form is missing (e.g. kExactSteps without steps, kHill without harmonics).
FloquetResult ComputeFloquet(const PeriodicSecondOrderSystem& system,
                             const FloquetOptions& options);

}  // namespace geardyn
