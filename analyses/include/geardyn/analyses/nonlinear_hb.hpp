/// @file
/// @brief Nonlinear harmonic balance (spec 02 "Harmonic balance", issue 6): periodic response of
/// M q̈ + C q̇ + K q + Pᵀ g(P q, Ωt) = f₀ + Re(f₁ e^{iΩt}) with a clearance-type force g on a few
/// "nonlinear coordinates" u = P q, by alternating frequency–time (AFT, FFTW) or, for
/// piecewise-linear laws, exact integration ("Exact integration" below), Newton with the
/// analytic Jacobian, pseudo-arclength continuation in Ω and Floquet stability of every point.
///
/// ## Harmonic conventions (shared with the linear HB of harmonic_balance.hpp)
/// * Base frequency ω = Ω / p, Ω the excitation frequency [rad/s, or dimensionless when the
///   problem is], p = NhbOptions::period_multiple (1: period-1 response; 2: period-2
///   sub-harmonic response).
/// * u(t) = Σ_{k=−H..H} U_k e^{ikωt}, U_{−k} = conj(U_k): complex one-sided coefficients U_k,
///   k = 0..H (U_0 real). The amplitude of harmonic k ≥ 1 is 2|U_k|. A cosine force
///   F cos(Ωt + φ) has F_p = (F/2) e^{iφ}; f(t) = f₀ + Re(f₁ e^{iΩt}) has F_0 = f₀, F_p = f₁/2.
/// * Harmonic k of the linear part: D_k = −k²ω² M + ikω C + K (the linear HB's convention).
/// * Newton unknowns (real, harmonic-major, n = number of nonlinear coordinates):
///   x = [U_0 (n), Re U_1 (n), Im U_1 (n), …, Re U_H (n), Im U_H (n)], size n(2H+1).
///
/// ## Condensation of the linear DOFs
/// Only u enters the AFT/Newton loop: per harmonic, u's receptance R_k = P D_k⁻¹ Pᵀ gives the
/// condensed residual Z_k U_k + N_k(U) − F̃_k = 0 with Z_k = R_k⁻¹ and F̃_k = Z_k P D_k⁻¹ F_k,
/// N_k the Fourier coefficients of g(u(t), Ωt). When P is the identity (all DOFs nonlinear, e.g.
/// the SDOF oscillator) Z_k = D_k directly. Condensation needs every D_k, k = 0..H, to be
/// invertible (no rigid-body mode: write a gear pair in its relative coordinate); the problem is
/// LTI outside g — time-varying stiffness belongs in g (as the parametric term of the B&K
/// oscillator).
/// Pole–residue form (NhbOptions::condensation, issue 13): the continuation moves Ω at every
/// corrector iteration, and an LU of every D_k per Ω cost more than the nonlinear force. With M
/// symmetric positive definite, the first-order form A = [0 I; −M⁻¹K −M⁻¹C] = V Λ V⁻¹ (one
/// eigen-decomposition per solver) gives D(s)⁻¹ = Σ_r v_r w_rᵀ / (s − λ_r), s = ikω, with v_r
/// the top half of column r of V and w_rᵀ the bottom half of row r of V⁻¹ times M⁻¹ (exact, not
/// a modal truncation: all 2N poles are kept). Then R_k = Σ_r (P v_r)(w_rᵀ Pᵀ)/(s − λ_r) and
/// dR_k/dΩ = −(ik/p) Σ_r (P v_r)(w_rᵀ Pᵀ)/(s − λ_r)², O(N n²) per harmonic instead of O(N³).
/// Used when V is well conditioned (Eigen's rcond of V ≥ 1e-6, so the round-off stays near
/// 1e-10 relative); otherwise (a defective or nearly defective pencil: critical damping) the
/// direct LU per harmonic. condensation_rcond is then a lower bound of 1/cond₁(D_k):
/// 1 / ((‖K‖₁ + |s|‖C‖₁ + |s|²‖M‖₁) Σ_r ‖v_r‖₁‖w_r‖∞ / |s − λ_r|).
///
/// ## AFT
/// S = max(64, samples_per_harmonic·H) samples per base period (rounded up to even), FFTW r2c/c2r
/// plans made once per solver; S ≥ 4H+2 is required for the exact Toeplitz Jacobian and the
/// oversampling keeps the aliasing of the kinked g small. Jacobian: dg/du sampled, transformed
/// to its Fourier coefficients G_j (j = 0..2H), ∂N_k/∂U_m = G_{k−m} (the convolution/Toeplitz
/// form), real-ified for the unknown layout above.
/// Switch correction (NhbOptions::switch_correction, laws with a SwitchFunction): g(u(t), Ωt) has
/// kinks where u crosses a contact boundary, and the DFT of its samples (the trapezoidal rule)
/// then errs by O(h²), h = 2π/S in θ = ωt. For each kink at θ_τ = θ_s + φh (located on the
/// synthesized u(θ) by the Illinois method) the leading Euler–Maclaurin term of the periodic
/// trapezoidal rule with a derivative jump J (Lyness 1971), exact − sampled =
/// (1/2π) J h² B₂(φ)/2 e^{−ikθ_τ}, B₂(φ) = φ² − φ + 1/6, J = ΔG·du/dθ(θ_τ) with ΔG the jump of
/// ∂g/∂u across the kink (sample difference), is added to N_k. The Jacobian stays the Toeplitz
/// one (the correction's derivative is O(h) relative: Newton converges linearly but fast).
///
/// ## Exact integration of piecewise-linear laws (NhbOptions::force_integration)
/// A law that gives its NhbPiecewiseLinearForm, g_i = κ_i(φ) c_i(u_i) with κ_i a trigonometric
/// polynomial and c_i piecewise linear (continuous), has N_k and the Jacobian coefficients G_j
/// computed exactly instead of from samples (the approach of Blankenship & Kahraman 1995, who
/// solved for the contact switching times). c_i = s u + c₀ + Σ_l Δs_l [u − β_l]₊; on the set
/// A_l = {θ : u(θ) > β_l} (its ends are the roots of the trigonometric polynomial u − β_l,
/// bracketed on the S samples of u and u′, with the pairs inside one sample interval found at
/// the located extrema, and refined by safeguarded Newton to round-off):
///   N_k = Σ_j κ̃_j (s U_{k−j} + c₀ δ_{k−j}) + Σ_l Δs_l Σ_m q_{l,m} I_{l,k−m},
///   q_l(θ) = κ̃(θ)(u(θ) − β_l) (coefficients q_{l,m}, |m| ≤ H + pJ),
///   I_{l,j} = (1/2π) ∫_{A_l} e^{−ijθ} dθ (closed form per interval),
///   G_d = s κ̃_d + Σ_l Δs_l Σ_j κ̃_j I_{l,d−j},
/// κ̃(θ) = κ(pθ). The ramp vanishes at the ends of A_l, so the moving ends add nothing to the
/// derivative: G_d is the exact Jacobian and Newton converges quadratically (away from grazing,
/// where the residual is only C¹). No aliasing: the error is the truncation at H alone.
///
/// ## Exact integration of projected laws (NhbNonlinearLaw::ProjectedForm)
/// The slice law of a gear mesh is not separable per coordinate: slice s acts on
/// v_s = δ_η − σ_s δ_ζ and pushes along [1, −σ_s]. A law given as
/// g = L u + Σ_t k_t(θ) w_t c_t(w_tᵀ u) with k_t piecewise constant in θ (spur slice stiffness:
/// exact steps) is integrated exactly: per term, V_m = w_tᵀ U_m; per ramp, the set
/// A = {σ(v − β) > 0} is located on the trigonometric polynomial v as above, intersected with
/// the weight's pieces, and
///   I_j = (1/2π) Σ_{pieces} k_b ∫_{A ∩ piece} e^{−ijθ} dθ,
///   N_k += s σ w_t Σ_m (V_m − β δ_m) I_{k−m},   G_d += s σ I_d w_t w_tᵀ.
/// ∂g/∂u is then piecewise constant between the located switches and the weight's
/// breakpoints, so the monodromy is the exact product of matrix exponentials over those pieces
/// (no step error: the stability verdict does not depend on monodromy_steps).
///
/// ## Stability
/// Floquet multipliers μ of the periodic orbit (period T = 2π/ω) from the monodromy matrix of
/// the variational equation y' = A(t) y, A = [0 I; −M⁻¹(K + Pᵀ ∂g/∂u(t) P)  −M⁻¹C] on the full
/// 2N state. The period is cut into NhbOptions::monodromy_steps intervals, each split at the
/// contact switches located on the synthesized trigonometric polynomial u(t) (law's
/// SwitchFunction, Illinois method), so ∂g/∂u is smooth on every piece; each piece is
/// propagated by the fourth-order Magnus step exp(h/2 (A₁ + A₂) + √3/12 h² [A₂, A₁]) with A at
/// the two Gauss points (closed-form 2×2 exponential for N = 1). g is continuous at a switch,
/// so no saltation matrix is needed. Fourth order in the step (the old sample-midpoint product
/// was first order at the switches). Stable iff max|μ| < 1. Alternative: Hill's method
/// (NhbStabilityMethod::kHill), eigenvalues of the quadratic Hill problem of the HB Jacobian,
/// keeping the 2N exponents with the smallest |Im λ| (the ones whose eigenvectors are centred on
/// harmonic 0; the others are copies shifted by ±ikω) — only for P = I (uncondensed problems).
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet_verdict.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"

namespace geardyn {

/// @brief Exact form of a piecewise-linear law (see "Exact integration"): for each coordinate
/// i, g_i(u, φ) = κ_i(φ) c_i(u_i) with κ_i(φ) = Σ_{j=−J..J} κ_ij e^{ijφ} (κ_{i,−j} =
/// conj(κ_ij)) and c_i(u) = slope_i u + offset_i + Σ_l ramp_slope_il [u − ramp_point_il]₊.
struct NhbPiecewiseLinearForm {
  MatrixXc modulation;                           ///< n×(J+1): κ_ij, j = 0..J [force/u units].
  VectorX slope;                                 ///< n: s_i [-].
  VectorX offset;                                ///< n: c₀_i [u units].
  std::vector<std::vector<double>> ramp_points;  ///< Per coordinate: β_il [u units].
  std::vector<std::vector<double>> ramp_slopes;  ///< Per coordinate: Δs_il [-].
};

/// @brief One term of an NhbProjectedForm: k(θ) w c(wᵀu), c(v) = Σ_l s_l [σ_l (v − β_l)]₊.
struct NhbProjectedTerm {
  VectorX direction;  ///< w (n) [-]: the term acts on v = wᵀu and pushes along w.
  /// Starts θ_b of the pieces of the weight k over the BASE period θ = ωt ∈ [0, 2π)
  /// (ascending, first ≥ 0); k = weights[b] on [θ_b, θ_{b+1}), the last piece wraps around to
  /// θ_0 + 2π. One entry: a constant weight.
  VectorX breakpoints;
  VectorX weights;                  ///< k_b ≥ 0 [force/u units], one per piece.
  std::vector<double> ramp_points;  ///< β_l [u units].
  std::vector<double> ramp_slopes;  ///< s_l [-].
  std::vector<int> ramp_sides;  ///< σ_l ∈ {+1, −1}: the ramp acts on {σ_l (v − β_l) > 0}.
};

/// @brief Exact form of a law made of projected piecewise-linear terms with piecewise-constant
/// weights (see "Exact integration of projected laws"):
/// g(u, φ) = L u + Σ_t k_t(θ) w_t c_t(w_tᵀ u), θ = φ/p the base angle.
struct NhbProjectedForm {
  MatrixX linear;                       ///< L (n×n) [force/u units].
  std::vector<NhbProjectedTerm> terms;  ///< The terms t.
};

/// @brief Batched nonlinear force on the nonlinear coordinates: force g(u, φ) and ∂g/∂u at S
/// samples in one call (one virtual call per state evaluation, never per sample).
class NhbNonlinearLaw {
 public:
  virtual ~NhbNonlinearLaw() = default;
  /// Number n of nonlinear coordinates.
  virtual int num_coordinates() const = 0;
  /// @param[in] u n×S samples of the nonlinear coordinates [problem units].
  /// @param[in] phase S excitation phases φ_s = Ω t_s [rad].
  /// @param[out] force n×S force g [force units] (pre-sized by the caller).
  /// @param[out] jacobian (n·n)×S: column s is ∂g/∂u at sample s, column-major n×n.
  virtual void Evaluate(const MatrixX& u, const VectorX& phase, MatrixX& force,
                        MatrixX& jacobian) const = 0;
  /// The linear law g ≈ K_c u + g_c valid in full contact, used for the initial guess.
  virtual void ContactBranch(MatrixX& stiffness, VectorX& offset) const = 0;
  /// Optional switching function: `value` (n×S, pre-sized) is continuous in u and changes sign
  /// exactly where ∂g_i/∂u jumps (a contact boundary), positive on one side. Used to locate the
  /// contact switches on the synthesized u(t) (accurate monodromy, AFT switch correction).
  /// @return false (default): not provided; the engine then treats ∂g/∂u as smooth.
  virtual bool SwitchFunction(const MatrixX& u, const VectorX& phase, MatrixX& value) const {
    (void)u;
    (void)phase;
    (void)value;
    return false;
  }
  /// Optional exact piecewise-linear form (NhbPiecewiseLinearForm; must describe the same g as
  /// Evaluate). @return false (default): not provided; the engine then samples g (AFT).
  virtual bool PiecewiseLinearForm(NhbPiecewiseLinearForm* form) const {
    (void)form;
    return false;
  }
  /// Optional exact projected form for the base period of p excitation cycles
  /// (NhbProjectedForm; must describe the same g as Evaluate). Used when PiecewiseLinearForm is
  /// not given. @return false (default): not provided.
  virtual bool ProjectedForm(int period_multiple, NhbProjectedForm* form) const {
    (void)period_multiple;
    (void)form;
    return false;
  }
};

/// @brief M q̈ + C q̇ + K q + Pᵀ g(P q, Ωt) = f₀ + Re(f₁ e^{iΩt}); N DOFs, n nonlinear coords.
struct NhbProblem {
  MatrixX mass;                                ///< M, N×N [kg or dimensionless].
  MatrixX damping;                             ///< C, N×N.
  MatrixX stiffness;                           ///< K, N×N (linear LTI part).
  MatrixX projection;                          ///< P, n×N: u = P q.
  VectorX force_mean;                          ///< f₀, N.
  VectorXc force_amplitude;                    ///< f₁, N (complex amplitude at Ω).
  std::shared_ptr<const NhbNonlinearLaw> law;  ///< g; law->num_coordinates() = n.
  /// Sizes consistent, M invertible-looking (non-empty), law set; `why` names the field.
  bool IsValid(std::string* why) const;
  /// True when P is the N×N identity (no condensation).
  bool IsUncondensed() const;
};

enum class NhbStabilityMethod { kNone, kMonodromy, kHill };

/// How the Fourier coefficients of g(u(t), Ωt) are computed.
enum class NhbForceIntegration {
  kAuto,     ///< kExact when the law gives its NhbPiecewiseLinearForm, else kSampled.
  kSampled,  ///< AFT on S samples (optionally with the switch correction).
  kExact,    ///< Exact integration of the piecewise-linear form (the law must give it).
};

/// How the condensed linear part Z_k = (P D_k⁻¹ Pᵀ)⁻¹ is evaluated at each Ω ("Condensation of
/// the linear DOFs" above). Uncondensed problems (P = I) use Z_k = D_k either way.
enum class NhbCondensation {
  kAuto,    ///< The pole–residue form when it applies (M SPD, V well conditioned), else kDirect.
  kDirect,  ///< An LU of every D_k at every new Ω (O(N³) per harmonic per Ω).
};

/// @brief Options of the single-frequency solve (also used by the continuation).
struct NhbOptions {
  int harmonics = 0;                 ///< H ≥ 1; 0: chosen from harmonic_tolerance.
  double harmonic_tolerance = 1e-6;  ///< H→2H relative RMS change target when harmonics = 0.
  int max_harmonics = 256;           ///< Upper bound of the automatic H.
  int period_multiple = 1;           ///< p ∈ {1, 2, …}: base ω = Ω/p (2: period-2 solutions).
  /// AFT oversampling: S = max(64, this·H), even (exact integration: S = max(64, 4H)); in
  /// [4, kMaxSamplesPerHarmonic].
  int samples_per_harmonic = 16;
  /// Upper bound of samples_per_harmonic: S = 65536·H samples per residual are ≥ 0.5 MB per
  /// coordinate and harmonic, and the AFT error of a kink (∝ S⁻², S⁻³ with the switch
  /// correction) is at round-off long before (the dense-AFT references in the tests use ≤ 32768).
  static constexpr int kMaxSamplesPerHarmonic = 65536;
  /// Upper bound of monodromy_steps: each step is a 2N × 2N Magnus exponential per point, and
  /// 10⁵ steps per period resolve any switch to 10⁻⁵ of the period.
  static constexpr int kMaxMonodromySteps = 100000;
  double newton_tolerance = 1e-10;  ///< ‖R‖∞ ≤ tol·(1 + ‖F̃‖∞ + ‖f₀‖∞).
  int max_newton_iterations = 40;   ///< Newton iterations per solve.
  NhbStabilityMethod stability = NhbStabilityMethod::kMonodromy;
  /// Monodromy steps per base period (Magnus-4 pieces, split at the contact switches);
  /// 0: max(64, 4H).
  int monodromy_steps = 0;
  /// AFT switch correction (needs NhbNonlinearLaw::SwitchFunction): the sampled (trapezoidal)
  /// Fourier coefficients N_k get the leading Euler–Maclaurin term of every located kink of
  /// g(u(t)), so the aliasing error falls from O(S⁻²) to O(S⁻³) (see "AFT" above).
  bool switch_correction = false;
  /// Sampled AFT or exact integration of piecewise-linear laws ("Exact integration" above);
  /// switch_correction only applies to the sampled path.
  NhbForceIntegration force_integration = NhbForceIntegration::kAuto;
  /// How the condensation's receptances P D_k⁻¹ Pᵀ are evaluated per Ω ("Condensation" above).
  NhbCondensation condensation = NhbCondensation::kAuto;
  /// Stable iff max|μ| < 1 + stability_margin: multipliers of undamped parts that the meshes do
  /// not damp (|μ| = 1 to round-off, e.g. bearing modes orthogonal to the line of action of an
  /// undamped structure) count as (marginally) stable; ≥ 0 [-].
  double stability_margin = 1e-5;
  bool IsValid(std::string* why) const;
};

/// @brief One periodic solution.
struct NhbPoint {
  double omega = 0.0;  ///< Excitation frequency Ω.
  MatrixXc harmonics;  ///< n×(H+1): U_k, k = 0..H of base ω = Ω/p.
  /// n×(H+1): N_k, the Fourier coefficients of g(u(t), Ωt) at the solution as the residual
  /// used them (the system outputs read them instead of integrating g again).
  MatrixXc force_harmonics;
  VectorX mean;               ///< n: U_0.
  VectorX rms;                ///< n: RMS of u − U_0, √(2 Σ_{k≥1} |U_k|²).
  VectorX peak_to_peak;       ///< n: max − min of u over the period.
  VectorX maximum;            ///< n: max of u (extreme sample refined to u′ = 0).
  VectorX minimum;            ///< n: min of u (likewise).
  double error_estimate = 0;  ///< RMS of the top quarter of harmonics / RMS (all coordinates).
  double tangent_omega = 0;   ///< dΩ/ds of the continuation tangent (0 for a single solve).
  int branch = 0;             ///< Branch id: incremented at every fold and every segment.
  /// 0: the trace from the start of the range; k ≥ 1: the k-th branch found off that trace by
  /// the branch search (NhbContinuationOptions::branch_search), traced separately — not joined
  /// to the point before it.
  int segment = 0;
  /// Three-valued (issue 12): kStable iff max|μ| < 1 + stability_margin, kUnstable iff
  /// max|μ| ≥ 1 + stability_margin, kUndetermined when max|μ| is NaN or ±inf or the point did
  /// not converge (NhbVerdict). kStable when stability was not computed (kNone: the point is not
  /// judged; folds then give their jumps as for stable branches).
  FloquetVerdict stable = FloquetVerdict::kStable;
  double max_multiplier = 0;  ///< max |μ| (0 when stability was not computed).
  int newton_iterations = 0;  ///< Newton iterations of this point.
  double residual_norm = 0;   ///< Final ‖R‖∞.
  /// Smallest estimated reciprocal condition number (Eigen's rcond) of the condensation's
  /// inversions D_k and P D_k⁻¹ Pᵀ at Ω (1 when uncondensed; for D_k a lower bound under the
  /// pole–residue form, see "Condensation of the linear DOFs"); below
  /// kNhbIllConditioned the single solve and the curve carry a warning.
  double condensation_rcond = 1.0;
  Status status = Status::kSuccess;
};

/// @brief The verdict of a converged point from its largest multiplier modulus:
/// kUndetermined when max_multiplier is NaN or infinite (a failed monodromy or Hill
/// eigenproblem, never "unstable"), kStable when max_multiplier < 1 + margin, else kUnstable.
/// @param[in] max_multiplier max |μ| [-]. @param[in] margin stability_margin ≥ 0 [-].
FloquetVerdict NhbVerdict(double max_multiplier, double margin);

/// Reciprocal condition number of the condensation below which a warning is given [-].
inline constexpr double kNhbIllConditioned = 1e-10;

/// @brief Single-frequency result.
struct NhbSolveResult {
  NhbPoint point;
  int harmonics_used = 0;  ///< H.
  Summary summary;         ///< error_estimate: H→2H relative RMS change (auto H) or top energy.
};

/// @brief Pseudo-arclength continuation options.
struct NhbContinuationOptions {
  double omega_start = 0.5;  ///< First Ω (a solve from the contact-branch guess).
  /// Last Ω: the step that would pass it is replaced by a solve at exactly omega_end, the last
  /// point of the curve (unless the curve turns back or fails before).
  double omega_end = 1.5;
  double initial_step = 0.01;        ///< Arclength step in scaled units (see below).
  double min_step = 1e-6;            ///< Smaller step after failures → stop, kNotConverged.
  double max_step = 0.05;            ///< Largest arclength step.
  int max_points = 20000;            ///< Hard limit on points, in [2, kMaxPoints].
  int max_corrector_iterations = 8;  ///< Corrector Newton iterations before a step is cut.
  double max_tangent_angle = 0.15;   ///< Largest angle between successive tangents [rad].
  /// Largest predicted |ΔΩ| per step (0: no cap) [Ω units]: resolves the frequency axis
  /// without shortening the steps along branches where mostly x changes (there the tangent
  /// angle and the corrector place the points).
  double max_omega_step = 0.0;
  /// Scaling of the arclength: s² = ‖Δx‖²/x_scale² + ΔΩ²/omega_scale²; 0 → automatic
  /// (x_scale = max(‖x_start‖, 1e-12·…), omega_scale = |omega_end − omega_start|).
  double x_scale = 0.0;
  double omega_scale = 0.0;
  /// Relative tolerance of the located folds: every fold (sign change of dΩ/ds) is located by
  /// regula falsi on dΩ/dσ of the bordered system until its estimated error
  /// (NhbFold::omega_error) is ≤ fold_tolerance·|Ω_fold|; in (0, 0.1].
  double fold_tolerance = 1e-8;
  /// Branch search (issue 13: detached branches and isolas that continuation from the start
  /// cannot reach): at this many frequencies evenly inside the range, Newton from the
  /// contact-branch guess with its alternating part scaled by 1, 0.3, 3 and 8; a solution off
  /// the traced curve (farther than 0.5 % in Ω or 2 % in RMS of coordinate 0 from every traced
  /// segment) is traced both ways to the ends of the range (or around its loop) and appended as
  /// a new segment (NhbPoint::segment), and the jumps are found over all segments. 0: off
  /// (the default of the single-coordinate engine, whose tests measured a 100 s Newton from the
  /// ×8 guess on the B&K oscillator; the gear-system path turns it on, SystemNhbOptions); at
  /// most kMaxBranchSearch.
  int branch_search = 0;
  static constexpr int kMaxBranchSearch = 1000;
  /// Formats an Ω for messages and warnings in the caller's units (e.g. "mesh frequency
  /// 562.3 Hz" for Ω = 2π f_m); empty: "Omega = <value>" in the problem's units.
  std::function<std::string(double omega)> omega_text;
  /// Called after every traced point with (points so far, its Ω); empty: none. Never called
  /// concurrently; it must not throw.
  std::function<void(int points, double omega)> progress;
  /// Optional cancel flag (e.g. set by a SIGINT handler), polled before every continuation step:
  /// once true the curve ends with the points traced so far, Status::kInterrupted. Not owned.
  const std::atomic<bool>* cancel = nullptr;
  /// Upper bound of max_points: every point keeps its harmonics (N·(2H+1) values) and its
  /// multipliers; 2·10⁶ points of a 24-harmonic, 12-DOF curve are already ≈ 10 GB.
  static constexpr int kMaxPoints = 2000000;
  bool IsValid(std::string* why) const;
};

/// @brief A fold (turning point): sign change of dΩ/ds, located between two traced points to
/// NhbContinuationOptions::fold_tolerance.
struct NhbFold {
  double omega = 0.0;  ///< Ω at the fold.
  double rms = 0.0;    ///< RMS of coordinate 0 at the fold.
  double maximum = 0;  ///< max of coordinate 0 at the fold.
  double minimum = 0;  ///< min of coordinate 0 at the fold.
  /// Estimated |error| of omega from locating the fold (not the truncation error of H): the
  /// last correction of the fold locator, or, when the locator failed (located = false), the
  /// distance of the Hermite-interpolated Ω from the nearer traced point.
  double omega_error = 0.0;
  bool located = false;        ///< omega_error ≤ fold_tolerance·|omega| (see above).
  int index = 0;               ///< Index of the point just before the fold.
  bool omega_maximum = false;  ///< Ω has a local maximum here (an up-sweep jump point).
};

/// @brief A jump of a slow sweep: from the stable branch ending at a fold to another stable
/// branch at the same Ω (the crossing nearest in RMS; all of them in rms_landings).
struct NhbJump {
  bool up_sweep = true;     ///< true: seen by an increasing-Ω sweep (fold with Ω maximum).
  double omega = 0.0;       ///< Jump frequency (the fold's Ω).
  double rms_before = 0.0;  ///< RMS of coordinate 0 on the branch that ends.
  double rms_after = 0.0;   ///< RMS of coordinate 0 on the landing branch (NaN if none).
  double max_before = 0.0;  ///< max of coordinate 0 before the jump.
  double max_after = 0.0;   ///< max of coordinate 0 after the jump (NaN if none).
  /// RMS of coordinate 0 on every stable branch crossing Ω (other than the two meeting at the
  /// fold), nearest to rms_before first (rms_after is the first). With more than one, which one
  /// a sweep lands on is decided by the transient (the basins of attraction), not by the HB:
  /// on the spur pair with backlash the time integration lands on the farther one.
  std::vector<double> rms_landings;
};

/// @brief A traced frequency-response curve.
struct NhbCurve {
  std::vector<NhbPoint> points;  ///< In arclength order.
  std::vector<NhbFold> folds;
  std::vector<NhbJump> jumps;
  int harmonics_used = 0;  ///< H.
  /// Ω where the trace stopped on a vertical branch (an undamped resonance: the response
  /// doubled within 0.1 % of Ω without a fold; summary.status kNotConverged); 0 when none.
  double undamped_resonance_omega = 0.0;
  /// Damped branches growing without bound (amplitude ∝ 1/|Ω* − Ω|, e.g. a two-flank branch of
  /// a clearance law towards a parametric-instability edge of the large-amplitude linear
  /// system), in the order of their "the branch grows without bound" warnings: the extrapolated
  /// asymptote Ω* and the Ω where the trace of the branch stopped. The status stays success: the
  /// branch is traced as far as it exists.
  std::vector<std::array<double, 2>> unbounded_branches;
  Summary summary;  ///< error_estimate: max point error_estimate; counters: points, newton, folds.
};

/// @brief Reusable solver for one problem and one H: FFTW plans and all scratch made once.
/// One solver per thread. The functions below are thin wrappers around it.
class NhbSolver {
 public:
  /// @throws InvalidInput for an invalid problem/options or harmonics < 1.
  NhbSolver(NhbProblem problem, const NhbOptions& options, int harmonics);
  ~NhbSolver();
  NhbSolver(NhbSolver&&) noexcept;
  NhbSolver& operator=(NhbSolver&&) noexcept;

  int harmonics() const;     ///< H.
  int samples() const;       ///< S.
  int num_unknowns() const;  ///< n(2H+1).
  /// True when the force harmonics are integrated exactly (NhbOptions::force_integration).
  bool exact_integration() const;
  const NhbProblem& problem() const;

  /// Residual R(x, Ω) (size n(2H+1)), its Jacobian ∂R/∂x and ∂R/∂Ω (nullptr → skipped).
  void Evaluate(const VectorX& x, double omega, VectorX* residual, MatrixX* jacobian,
                VectorX* d_omega);
  /// N_k (n×(H+1)): the Fourier coefficients of g(u(t), Ωt) at x, as the residual uses them.
  MatrixXc ForceHarmonics(const VectorX& x);
  /// Response of the linear part to loads: column k of the result is D_k⁻¹ b_k (N×(H+1), b
  /// N×(H+1)) at Ω, D_k = −k²ω²M + ikωC + K, ω = Ω/p; from the pole–residue form when the
  /// solver condenses with it, else an LU per harmonic.
  MatrixXc SolveLinear(double omega, const MatrixXc& b);
  /// Initial guess at Ω: the linear contact-branch response.
  VectorX ContactGuess(double omega);
  /// Newton with backtracking line search from `x` (overwritten with the solution); after three
  /// consecutive short steps (stalling near grazing contact) Powell's hybrid dogleg method
  /// (GSL hybridsj) restarts from the initial `x`. Returns the iteration count (both methods);
  /// `status`/`residual_norm` report convergence.
  int Newton(VectorX& x, double omega, Status* status, double* residual_norm);
  /// The residual tolerance of Newton at Ω: newton_tolerance·(1 + max_k ‖F̃_k‖∞), F̃_k the
  /// condensed forces [N] (a gear system's f₀ is in torques on the flexible coordinates, but its
  /// residual is in mesh forces: F̃_0 carries the mean mesh force).
  double ResidualTolerance(double omega);
  /// max_k ‖N_k‖∞ of the law's force harmonics at the x of the last Evaluate [force units]
  /// (0 before any): the size of the residual's largest term on a large-amplitude branch, where
  /// ResidualTolerance (set by the excitation) falls below the round-off of R.
  double LastLawForceNorm() const;
  /// Fills omega, harmonics, mean, rms, peak_to_peak, max, min, error_estimate of `point`.
  void Describe(const VectorX& x, double omega, NhbPoint& point);
  /// Floquet multiplier of largest modulus (method per options).
  double MaxMultiplier(const VectorX& x, double omega);
  /// The sample count S per base period for H harmonics: the AFT's (see "AFT" above), or
  /// max(64, 4H) for exact integration (the samples only bracket switches and extrema).
  static int SamplesFor(const NhbOptions& options, int harmonics, bool exact = false);
  /// Harmonics vector x re-sized for H' harmonics (zero-padded or truncated).
  static VectorX Resize(const VectorX& x, int n, int new_harmonics);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// @brief Periodic solution at one Ω, from the contact-branch guess (or `guess` when given for
/// the resolved H). With options.harmonics = 0, H doubles from 4 until the relative RMS change
/// from H to 2H is below options.harmonic_tolerance (reported as summary.error_estimate).
NhbSolveResult SolveNonlinearHarmonicBalance(const NhbProblem& problem, double omega,
                                             const NhbOptions& options = {});

/// @brief Frequency-response curve by pseudo-arclength continuation in Ω with step control,
/// fold detection, jump points and stability of every point. With options.harmonics = 0 the
/// curve is traced with H = 8, 16, … until its largest per-point error estimate (energy in the
/// top harmonics) is below options.harmonic_tolerance.
NhbCurve TraceNonlinearHarmonicBalance(const NhbProblem& problem, const NhbOptions& options,
                                       const NhbContinuationOptions& continuation);

}  // namespace geardyn
