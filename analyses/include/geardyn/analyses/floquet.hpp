/// @file
/// @brief Floquet stability of the homogeneous LTV gear system, `ComputeFloquet` (spec 02
/// "Floquet", issue 5).
///
/// **Problem.** M q̈ + C(θ) q̇ + K(θ) q = 0 with θ = ω_m t (ω_m = 2π·mesh_frequency_hz), period
/// T = 2π·P_K/ω_m [s] (P_K: the period of K(θ) and C(θ) in mesh cycles, usually 1; the hunting
/// period that tooth errors give ε is not used: ε forces the system, it does not excite it
/// parametrically). State x = [q; q̇] (2n), ẋ = A(t) x; the monodromy Φ(T)
/// maps x(0) to x(T); its eigenvalues are the Floquet multipliers λ, the characteristic
/// exponents are μ = ln(λ)/T [1/s] (principal branch). Unstable when max|λ| > 1.
///
/// **Methods** (FloquetMethod; kAuto picks the cheapest one that is exact or meets the
/// tolerance — see the implementation's selection table in docs/design.md):
// clang-format off
/// | method | when | accuracy |
/// |---|---|---|
/// | kExactSteps | piecewise-constant K, C (HasPiecewiseConstantOperator) | round-off: Π expm(A_k Δt_k) |
/// | kMagnus | smooth coefficients | high-order Magnus/exponential integrator with an error target |
/// | kOdeStepper | always (the reference) | GSL odeiv2 on the 2n×2n fundamental matrix |
/// | kHill | smooth, from the Fourier harmonics (system_harmonics.hpp) | truncation, selected exponents |
/// | kModalProjection | large systems | projection on the lowest LTI modes, with an error estimate |
/// | kArpackMonodromy | large systems, dominant multipliers only | ARPACK Arnoldi on v ↦ Φ(T) v, residual-based estimate |
// clang-format on
///
/// **kAuto** (internal::SelectFloquetMethod, per DOF block): n ≥ modal_projection_min_dofs →
/// kModalProjection; piecewise-constant → kExactSteps; smooth coefficients → by cost, Magnus on
/// the full system or on the mesh-driven modal basis (the modes below 2.25 f_m, those with ≥ 5 %
/// mesh strain energy, and those decaying no faster than these; docs/design.md "Floquet kAuto by
/// cost"): the work of a Magnus run is taken as ω_max T · (2m)³ (ω_max the highest natural
/// frequency kept), and the projection is chosen when its three bases cost less than a quarter
/// of the full run. kAuto's projection reports an estimate of max|λ| (the basis truncation, from
/// the change of max|λ| over the three bases, plus the inner Magnus estimate) and accepts it when
/// it meets the tolerance, or when it is ≤ 1e-4, |1 − max|λ|| exceeds ten estimates and the
/// changes between bases shrink (a warning then says so); otherwise it widens the basis, and
/// solves the full system when the basis would need every mode. builtin:geared-shafts (108
/// DOFs): 193 s → 2.1 s CPU, same verdict
/// (docs/benchmarks.md "Floquet kAuto by cost"). kArpackMonodromy is never chosen
/// automatically: it returns only the arpack_nev largest-|λ| multipliers and forms the same
/// full-size step exponentials as one Magnus run (26 s on the geared shafts). Measured on
/// the 204-DOF geared shafts (docs/benchmarks.md "Floquet"): at the accuracy a modal projection
/// reaches (1e-4 … 1e-5) the projection is 13–23× faster; ARPACK gives the 6 dominant multipliers
/// to 2e-10 in 0.28 s, 2.5× faster than the full exact product (both spend most of it in the dense
/// step exponentials). Ask for it when the dominant multipliers are wanted more accurately than a
/// projection gives them, or may come from high modes outside any modal basis.
/// Not for undamped systems: every multiplier then has |λ| = 1, "largest |λ|" selects nothing and
/// the Arnoldi iteration converges slowly (examples/scenes/helical-pair.toml: 16 s against 0.2 s
/// for kMagnus, same multipliers).
///
/// **kArpackMonodromy** (analyses/src/floquet/arpack_monodromy.cpp): ARPACK's non-symmetric
/// implicitly restarted Arnoldi (dnaupd/dneupd, mode 1, which = "LM") on the operator
/// v ↦ Φ(T) v of the scaled state (floquet_system.hpp), which is never formed: each application
/// propagates one vector over the period with the same propagators as the other methods —
/// piecewise-constant coefficients: the exact step exponentials expm(A_k Δt_k) applied in turn
/// (dense, formed once per distinct step; or, when the state matrices are sparse, their action by
/// a scaled Taylor series without forming them, Al-Mohy & Higham, SIAM J. Sci. Comput. 33 (2011));
/// smooth coefficients: the Gauss–Legendre Magnus step exponentials (magnus_order, magnus_steps
/// or step doubling until the Richardson estimate of the dominant multipliers meets the
/// tolerance). A hunting period of P identical cycles uses the cycle's scaled power (no overflow).
/// Error estimate: min(κ_i ρ_i, √(ρ_i max|λ|)) over the returned multipliers, ρ_i the residuals
/// ‖Φx − λx‖ of the unit right and left Ritz vectors (extra applications, not ARPACK's own
/// estimates), κ_i the eigenvalue condition number from the left vectors (a second ARPACK run on
/// Φᵀ: the factors transposed in reverse order); plus the Magnus truncation and the round-off.
/// ARPACK's convergence (info, converged count, restarts, applications) is reported in the Summary
/// (kNotConverged when fewer than arpack_nev Ritz values converged). Returned: the arpack_nev
/// dominant multipliers of the flexible (rigid-deflated) state (+ the conjugate of the last one),
/// then the 2r exact rigid multipliers 1. A state too small for ARPACK (dimension < arpack_nev + 2)
/// gets Φ from the same step exponentials (kExactSteps, or kMagnus) and all its multipliers.
///
/// Reentrant; never prints; numerical trouble is reported in `summary`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet_verdict.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief How the monodromy (or the multipliers) is computed.
enum class FloquetMethod {
  kAuto,
  kExactSteps,
  kMagnus,
  kOdeStepper,
  kHill,
  kModalProjection,
  kArpackMonodromy
};
/// "auto", "exact_steps", "magnus", "ode_stepper", "hill", "modal_projection", "arpack_monodromy".
const char* ToString(FloquetMethod method);
/// Every FloquetMethod, kAuto first (for option lists and parsers).
inline constexpr FloquetMethod kFloquetMethods[] = {
    FloquetMethod::kAuto,           FloquetMethod::kExactSteps, FloquetMethod::kMagnus,
    FloquetMethod::kOdeStepper,     FloquetMethod::kHill,       FloquetMethod::kModalProjection,
    FloquetMethod::kArpackMonodromy};
/// @brief The method named `name` (a ToString value).
/// @throws InvalidInput naming `field` and the accepted names for an unknown name.
FloquetMethod ParseFloquetMethod(const std::string& name, const std::string& field = "method");

/// @brief Options of ComputeFloquet.
struct FloquetOptions {
  FloquetMethod method = FloquetMethod::kAuto;
  /// f_m [Hz] > 0: the tooth-mesh frequency (θ = 2π f_m t).
  double mesh_frequency_hz = 0.0;
  /// Error target [-]: on the relative error of Φ(T) for kMagnus and kOdeStepper (the multiplier
  /// error then follows from their conditioning, see floquet_system.hpp), on the multipliers
  /// (absolute, |λ| ~ 1) for kHill and kModalProjection; kArpackMonodromy: ARPACK's relative Ritz
  /// residual is 0.1·tolerance (the multiplier error is κ times larger, see error_estimate) and
  /// the Magnus step doubling meets it on the dominant multipliers.
  double tolerance = 1e-10;
  /// kHill: number of harmonics H (0 = chosen from the tolerance); the Hill matrix dim·(2H+1)
  /// must not exceed 800 (checked against the state dimension by ComputeFloquet, whose message
  /// gives the size, memory and flops), so H ≤ 199 in any case.
  int hill_harmonics = 0;
  /// kModalProjection: number of LTI modes kept, the lowest ones (0 = automatic: the modes that
  /// can resonate with f_m and the mesh modes first, widened until the tolerance is met); at most
  /// 1500, and clamped to n.
  int num_modes = 0;
  /// Keep the 2n×2n monodromy in the result (not formed by every method).
  bool keep_monodromy = false;
  /// kMagnus: order 4 (2 Gauss nodes) or 6 (3 Gauss nodes) [-].
  int magnus_order = 6;
  /// kMagnus: fixed number of steps per period, at most 65 536 (the automatic cap; 0 = chosen
  /// from the tolerance by step doubling; a fixed count skips the error estimate: error_estimate
  /// is then the round-off estimate only). With kinks in K(θ) (tables, steps) the count is
  /// rounded to whole steps per smooth piece once it exceeds the number of pieces (the actual
  /// count is counters["steps"]).
  int magnus_steps = 0;
  /// kMagnus with automatic steps: the measured-order step control (magnus.cpp,
  /// MagnusMonodromyMeasured) instead of the default one. Default (false): the first count puts
  /// h‖A‖₁ ≤ 1, counts double, and the first Richardson comparison takes the order as 1, so the
  /// estimate of a smooth system is ≈ 2⁶ − 1 = 63× pessimistic. True: the first count puts
  /// h‖A‖₁ ≤ 2π, the estimate uses the order measured from the last three runs (clamped to
  /// [1, magnus_order]) with a safety factor 2, and a result is accepted only when the coarser of
  /// the two runs compared is inside the Magnus series' radius (h‖A‖₁ ≤ π, Moan & Niesen 2008).
  /// ≈ 2× fewer A(t) evaluations on the 12-DOF helical pair at 1e-6, because it delivers the
  /// tolerance instead of ≈ 50× better (docs/design.md "Stability charts: the measured-order");
  /// the stability chart of the CLI uses it (its screening run; verdicts tested against the ODE
  /// path).
  bool magnus_measured_order = false;
  /// Fill FloquetResult::undamped_modes when the verdict is marginal (a modal analysis of the
  /// mean system per call); false leaves it empty (the stability chart, which reads only max|λ|).
  bool list_undamped_modes = true;
  /// kArpackMonodromy: number of largest-|λ| multipliers wanted, 1 ≤ nev ≤ 2n [-] (a state of
  /// dimension < nev + 2 returns all its multipliers).
  int arpack_nev = 6;
  /// kArpackMonodromy: number of Arnoldi vectors ncv, 0 → min(dim, max(2·nev + 1, 20)); else
  /// nev + 2 ≤ ncv (capped at the state dimension) [-].
  int arpack_ncv = 0;
  /// kArpackMonodromy: maximum number of implicit restarts (ARPACK iparam[2]), 1 … 100 000 [-].
  int arpack_max_iterations = 1000;
  /// kAuto: systems with at least this many DOFs (after the block split) use kModalProjection
  /// (below it, smooth systems choose by cost, see the @file).
  int modal_projection_min_dofs = 200;
  /// Analyse the decoupled DOF blocks (SystemModel::blocks()) separately (exact: they do not
  /// couple) and merge their multipliers.
  bool split_blocks = true;
  /// Deflate the rigid-body modes (common null space of K(t) and C(t)): each gives the exact double
  /// multiplier 1 (a Jordan block) that a product or an eigen solver resolves only to √ε.
  bool deflate_rigid_modes = true;
  /// Meshes at incommensurate frequencies (no common period of at most 10⁴ mesh cycles): the
  /// longest common period [mesh cycles] of the rational approximants analysed instead (see
  /// ComputeFloquet), in [0, 10⁴]; 0 refuses such a model (InvalidInput, as before issue 18).
  std::int64_t max_approximant_period_meshes = 1000;
  /// False (with the field and value in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief One rational approximant of an incommensurate train (FloquetResult::approximants):
/// every mesh ratio r_k replaced by a continued-fraction convergent p_k/q_k.
struct FloquetApproximant {
  std::vector<double> ratios;      ///< the approximated phase ratio of every mesh [-]
  std::int64_t period_meshes = 0;  ///< their common period [mesh cycles]
  /// max|r_k − p_k/q_k| over the meshes [-]: how far the approximant is from the model.
  double ratio_error = 0.0;
  /// max Re μ [1/s] of the flexible motion: the largest characteristic exponent (ln |λ| / T)
  /// without the rigid-body multipliers (exactly 1), the quantity that converges as the
  /// approximants improve (|λ| itself grows with the period).
  double max_real_exponent = 0.0;
  FloquetVerdict verdict = FloquetVerdict::kUndetermined;
  double error_estimate = 0.0;  ///< the approximant's own monodromy error estimate [-]
};

// FloquetVerdict (three-valued, its rules): floquet_verdict.hpp.

/// @brief A mode of the mean LTI system with no damping (for a marginal verdict).
struct UndampedMode {
  int index = 0;               ///< mode number as `geardyn modes` prints it (from 0) [-]
  double frequency_hz = 0.0;   ///< natural frequency of the mean system [Hz]
  double damping_ratio = 0.0;  ///< ζ = φᵀC̄φ/(2ω) [-] (below 1e-9)
  std::string dominant_dof;    ///< the DOF with the largest kinetic energy φ_i² M_ii
};

/// @brief Multipliers and verdict of one Floquet analysis.
struct FloquetResult {
  Summary summary;  ///< status, message, error_estimate (on the multipliers), counters, time
  FloquetMethod method_used = FloquetMethod::kAuto;
  /// P_K [-]: the period of K(θ) and C(θ) in mesh cycles (internal::OperatorPeriodMeshes), not
  /// the hunting period of the transmission error (which forces, but does not excite); with
  /// meshes at several frequencies, their common period (internal::FloquetPeriodMeshes: 40 for a
  /// planetary stage at 7/40 of the parallel stage's mesh frequency).
  std::int64_t period_meshes = 1;
  double period_s = 0.0;  ///< T = P_K / f_m [s]
  VectorXc multipliers;  ///< (2n, or fewer for kHill/kModalProjection/kArpackMonodromy) λ, by |λ|
                         ///< descending
  VectorXc exponents;    ///< μ = ln(λ)/T [1/s], same order
  double max_abs_multiplier = 0.0;  ///< max|λ| [-] (NaN when a multiplier is NaN)
  /// 1 − max|λ| [-]: positive when stable; for an undamped system (|λ| = 1 in stable regions)
  /// compare with error_estimate.
  double stability_margin = 0.0;
  /// Three-valued verdict (see FloquetVerdict for the rules).
  FloquetVerdict verdict = FloquetVerdict::kUndetermined;
  /// kStable with a flexible multiplier on the unit circle within the error estimate
  /// (1 − max|λ_flex| ≤ max(e, 1e-12)): stable but not asymptotically (undamped modes).
  bool marginal = false;
  /// When marginal (model entry only, and options.list_undamped_modes): the modes of the mean
  /// system with ζ < 1e-9.
  std::vector<UndampedMode> undamped_modes;
  MatrixX monodromy;  ///< (2n×2n) Φ(T) when options.keep_monodromy and the method forms it
  /// Incommensurate mesh frequencies only: the rational approximants analysed, coarsest first;
  /// the result's multipliers, period and monodromy are the last one's (see ComputeFloquet).
  std::vector<FloquetApproximant> approximants;
  /// True when verdict is kStable.
  bool stable() const { return verdict == FloquetVerdict::kStable; }
};

/// @brief Floquet multipliers of the model at the given mesh frequency (see the @file).
/// Meshes at several commensurate frequencies (a two-stage train: r_k = p_k/q from the tooth
/// counts) make K(θ), C(θ) periodic over their common period of q mesh cycles; the monodromy
/// spans it (exact, not an approximation; the work grows with q) and a warning names it.
///
/// **Incommensurate frequencies** (no common period of at most 10⁴ cycles, e.g. r = √2/2): there
/// is no monodromy, but a quasi-periodic system has Lyapunov exponents, and the periodic
/// systems whose ratios are the continued-fraction convergents p_k/q_k of the r_k approach it.
/// ComputeFloquet analyses the last three approximants whose common period is at most
/// options.max_approximant_period_meshes (the convergents of all ratios, taken together by a
/// growing denominator bound), reports them in FloquetResult::approximants, and returns the
/// last one's multipliers. The convergence study gives the error estimate: the largest change of
/// a resolved exponent's real part between the last two approximants, Δσ [1/s] (the flexible
/// multipliers within a factor 10⁸ of the largest, in descending order: a product over a long
/// period does not resolve the smaller ones), as a change of the multipliers over the last
/// period, max|λ| · T · Δσ (added to the monodromy's own estimate).
/// The verdict is the last approximant's when the last two agree, kUndetermined (with a warning)
/// when they do not. A heuristic, not a bound: near a parametric resonance of a combination
/// frequency an approximant can resonate where the quasi-periodic system does not, which the
/// disagreement of successive approximants then shows (docs/design.md "Incommensurate
/// frequencies: rational approximants").
/// @throws InvalidInput on invalid options, a model with a nonlinear core, meshes at frequencies
///   without a common period of at most 10⁴ mesh cycles when max_approximant_period_meshes is 0
///   or too small for two approximants (internal::FloquetPeriodMeshes), or method kHill with
///   several mesh frequencies.
FloquetResult ComputeFloquet(const SystemModel& model, const FloquetOptions& options);

namespace internal {
/// @brief The method ComputeFloquet runs on `model` (never kAuto; kAuto: n ≥
/// options.modal_projection_min_dofs → kModalProjection; piecewise-constant K, C (constant
/// included: one interval, Φ = expm(A T)) → kExactSteps; otherwise kModalProjection when its
/// estimated Magnus work is below a quarter of the full system's, else kMagnus; see the @file).
/// With options.split_blocks it is applied to every block separately.
FloquetMethod SelectFloquetMethod(const SystemModel& model, const FloquetOptions& options);

/// @brief The rational approximants of a model whose meshes run at incommensurate frequencies
/// (rational_approximants.cpp): for every growing bound Q on the denominators, each ratio's last
/// continued-fraction convergent p/q with p ≥ 1, q ≤ Q; distinct levels only, in order, up to the
/// first whose common period (FindCommonPeriodMeshes) exceeds max_period_meshes. Only
/// ratios, ratio_error and period_meshes are set.
std::vector<FloquetApproximant> RationalApproximants(const SystemModel& model,
                                                     std::int64_t max_period_meshes);
}  // namespace internal

}  // namespace geardyn
