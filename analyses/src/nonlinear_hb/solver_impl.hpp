/// @file
/// @brief Private state of NhbSolver: FFTW plans, AFT buffers, the condensed linear part cache
/// and the Newton scratch (all sized once in the constructor).
#pragma once

#include <fftw3.h>

#include <Eigen/LU>
#include <utility>
#include <vector>

#include "geardyn/analyses/nonlinear_hb.hpp"

namespace geardyn {

struct NhbSolver::Impl {
  Impl(NhbProblem problem_in, const NhbOptions& options_in, int harmonics);
  ~Impl();
  Impl(const Impl&) = delete;
  /// The constructor's work (Impl() frees the FFTW resources when it throws).
  void Construct(int harmonics);
  /// Destroys the plans and frees the buffers (idempotent).
  void ReleaseFftw();
  Impl& operator=(const Impl&) = delete;

  NhbProblem problem;
  NhbOptions options;
  int n = 0;     ///< Nonlinear coordinates.
  int dofs = 0;  ///< N.
  int H = 0;
  int S = 0;  ///< AFT samples per base period.
  int m = 0;  ///< n(2H+1).
  int p = 1;  ///< Period multiple.

  // FFTW (plans on time_buf/freq_buf, made once).
  double* time_buf = nullptr;
  fftw_complex* freq_buf = nullptr;
  fftw_plan r2c = nullptr;
  fftw_plan c2r = nullptr;

  // AFT scratch.
  VectorX phase;                   ///< Ω t_s = p·2πs/S.
  MatrixX u;                       ///< n×S.
  MatrixX g;                       ///< n×S.
  MatrixX dg;                      ///< n²×S.
  MatrixXc g_h;                    ///< n×(H+1): N_k.
  std::vector<MatrixXc> dg_h;      ///< 2H+1 blocks n×n: G_j, j = 0..2H.
  VectorXc jacobian_coefficients;  ///< G_j, j = −2H..2H, flat: index (j + 2H)n² + a + nb.

  // Exact integration of a piecewise-linear law (exact_integration.cpp).
  bool exact = false;           ///< Force harmonics integrated exactly (options + law).
  NhbPiecewiseLinearForm form;  ///< The law's form when exact.
  int kappa_order = 0;          ///< P: highest θ-harmonic of the modulation κ̃(θ) = κ(pθ).
  MatrixX u_slope;              ///< n×S: du/dθ at the samples.
  VectorXc u_full;              ///< U_l, l = −H..H (index l + H).
  VectorXc kappa;               ///< κ̃_j, j = −P..P (index j + P).
  VectorXc ramp_product;        ///< q_m = κ̃(u − β), m = −(H+P)..H+P.
  VectorX q_re, q_im;           ///< Real and imaginary q_m, reversed.
  VectorX integrals_re, integrals_im;              ///< Real and imaginary I_j.
  VectorXc set_integrals;                          ///< I_j, j = −(2H+P)..2H+P (index j + 2H + P).
  std::vector<std::pair<double, bool>> crossings;  ///< (θ, entering the set u > β).
  std::vector<std::pair<double, double>> intervals;  ///< Ends of {u > β}, second > first.

  // Exact integration of a projected law (projected_integration.cpp).
  bool projected = false;  ///< exact via the law's NhbProjectedForm.
  /// Eigen-decomposition of the balanced state matrix A' = [0 ω₀I; −M⁻¹(K + Pᵀ G P)/ω₀ −M⁻¹C]
  /// of one value of ∂g/∂u = G (the projected monodromy's pieces take few distinct values):
  /// exp(A'h) = Re(V e^{Λh} V⁻¹) per piece with two real products instead of a Padé exponential.
  struct PieceExponential {
    MatrixX G;                             ///< n×n key.
    bool ok = false;                       ///< V well conditioned (else Padé for this G).
    MatrixX v_re, v_im, vinv_re, vinv_im;  ///< Re/Im of V and V⁻¹ (2N×2N).
    VectorXc lambda;                       ///< Eigenvalues (2N).
  };
  std::vector<PieceExponential> piece_exponentials;  ///< At most kMaxPieceExponentials.
  double monodromy_w0 = 0.0;                         ///< ω₀ of the balancing (0: not set).
  /// The entry of G, made when new (nullptr: the cache is full).
  const PieceExponential* FindPieceExponential(const MatrixX& G);
  /// The balanced first-order matrix A' = [0 ω₀I; −M⁻¹(K + PᵀGP)/ω₀ −M⁻¹C] of one piece (state
  /// [q; q̇/ω₀], ω₀ = monodromy_w0).
  MatrixX BalancedPieceMatrix(const MatrixX& G) const;
  /// x of the last IntegrateProjected (g_h, dg_h, switch_angles are its results); valid only
  /// while integrated_valid. The monodromy and the description of an accepted point reuse the
  /// corrector's last integration instead of repeating it.
  VectorX integrated_x;
  bool integrated_valid = false;
  NhbProjectedForm pform;            ///< The law's projected form when projected.
  VectorXc poly;                     ///< (H+1) harmonics c_k of the scalar polynomial v(θ).
  VectorX poly_values, poly_slopes;  ///< (S) v and dv/dθ at the samples.
  VectorXc weighted_integrals;       ///< I_j, j = 0..2H (index j).
  VectorX inverse_j;                 ///< 1/j, j = 0..2H (entry 0 unused).
  /// Two-sided G_j (j = −2H..2H) and U_l (l = −H..H), real and imaginary parts, for the
  /// Toeplitz product N_k = Σ_l G_{k−l} U_l.
  std::vector<double> toeplitz_g_re, toeplitz_g_im, toeplitz_u_re, toeplitz_u_im;
  VectorXc poly_full;                 ///< V_m − β δ_m, m = −H..H (index m + H).
  std::vector<double> switch_angles;  ///< Set ends of the last IntegrateProjected [rad].
  MatrixXc projected_offsets;         ///< n×(H+1): b_k of IntegrateProjected.

  // Condensed linear part, cached per Ω.
  double cached_omega;
  bool uncondensed = false;                 ///< P = I: Z_k = D_k directly.
  MatrixXc mass_c, damping_c, stiffness_c;  ///< M, C, K as complex (made once).
  std::vector<MatrixXc> Z, dZ;              ///< k = 0..H.
  std::vector<VectorXc> F, dF;              ///< k = 0..H.
  double force_scale = 1.0;  ///< 1 + max ‖F̃_k‖∞ + ‖f₀‖∞ (Newton tolerance scale).
  /// Smallest estimated 1/cond of D_k and P D_k⁻¹ Pᵀ over k at cached_omega (1 uncondensed).
  double linear_rcond = 1.0;

  // Pole–residue form of the receptance (nonlinear_hb.hpp, "Condensation"; linear_part.cpp).
  bool pole_residue = false;  ///< Z_k from the form below instead of an LU of D_k.
  VectorXc poles;             ///< λ_r (2N): eigenvalues of A = [0 I; −M⁻¹K −M⁻¹C].
  MatrixXc residues;          ///< (n·n)×2N: column r is (P v_r)(w_rᵀ Pᵀ), column-major n×n.
  MatrixXc force_residues;  ///< n×2N per load: (P v_r)(w_rᵀ F) for F_0 = f₀ (first n rows) and
                            ///< F_p = f₁/2 (next n rows), i.e. (2n)×2N.
  MatrixXc modal_top;       ///< N×2N: v_r (SolveLinear).
  MatrixXc modal_left;      ///< 2N×N: w_rᵀ (SolveLinear).
  VectorX residue_norms;    ///< ‖v_r‖₁ ‖w_r‖∞ (2N): bound of ‖D⁻¹‖₁ (rcond).
  double norm_k = 0, norm_c = 0, norm_m = 0;  ///< 1-norms of K, C, M.
  VectorXc pole_weights, pole_weights2;       ///< 1/(s − λ_r), 1/(s − λ_r)² (scratch).
  MatrixXc receptance, d_receptance;          ///< n×n scratch: R_k, dR_k/dΩ.
  /// Builds the pole–residue form; false (then the direct LU) when M is not SPD or V is ill
  /// conditioned.
  bool BuildPoleResidueForm();

  // Newton scratch.
  MatrixX J;
  VectorX R, dx, x_trial, R_trial, x_start;
  Eigen::PartialPivLU<MatrixX> lu;

  // Contact switches (switches.cpp).
  bool has_switch_function = false;  ///< The law provides SwitchFunction.
  MatrixX sw;                        ///< n×S switching function at the samples.
  MatrixX u1, du1, sw1;              ///< One-column scratch for the root finder.
  VectorX theta1, phase1;

  /// Index of Re U_k (k ≥ 1) of coordinate i in x; U_0 at i; Im U_k right after Re U_k block.
  int Re(int k, int i) const { return k == 0 ? i : n * (2 * k - 1) + i; }
  int Im(int k, int i) const { return n * 2 * k + i; }

  void UpdateLinear(double omega);
  /// g_h (and dg_h when `jacobian`) from x: sampled AFT or exact integration per `exact`.
  void ForceHarmonics(const VectorX& x, bool jacobian);
  /// Exact g_h and dg_h of the piecewise-linear form (needs Synthesize(x) first).
  void IntegrateExactly(const VectorX& x);
  /// u_i(θ), du_i/dθ, d²u_i/dθ² of coordinate i at base angle θ from x.
  void EvaluateCoordinate(const VectorX& x, int i, double theta, double out[3]) const;
  /// The set {θ ∈ [0, 2π) : u_i(θ) > level} as `intervals` (needs u and u_slope at the samples).
  void FindSuperlevelSet(const VectorX& x, int i, double level);
  /// The set {θ : v(θ) > level} of v from `poly`, `poly_values`, `poly_slopes` as `intervals`.
  void FindPolynomialSuperlevelSet(double level);
  /// v(θ), v′, v″ of the trigonometric polynomial with one-sided harmonics c (H+1).
  void EvaluatePolynomial(const VectorXc& c, double theta, double out[3]) const;
  /// u_slope = du/dθ at the samples (c2r).
  void SynthesizeSlope(const VectorX& x);
  /// Exact g_h and dg_h of the projected form (needs Synthesize(x) first); the set ends go to
  /// switch_angles.
  void IntegrateProjected(const VectorX& x);
  /// Exact monodromy of a projected law: Π expm(A_j h_j) over the pieces between the switches
  /// and the weights' breakpoints (A constant on each).
  double ProjectedMonodromyMaxMultiplier(const VectorX& x, double omega);
  /// Largest (sign = +1) or smallest (−1) value of u_i over the period: the extreme sample
  /// refined to the stationary point of the trigonometric polynomial (needs Synthesize(x)).
  double ExtremeValue(const VectorX& x, int i, double sign);
  void Synthesize(const VectorX& x);
  void AnalyseForce();
  void AnalyseJacobian();
  /// Residual (and Jacobian, Ω-derivative when non-null) from the current x.
  void Evaluate(const VectorX& x, double omega, VectorX* residual, MatrixX* jacobian,
                VectorX* d_omega);
  /// u(θ) and du/dθ (n×T each, du may be null) at base angles θ = ωt [rad] from x.
  void SynthesizeAt(const VectorX& x, const VectorX& theta, MatrixX& uu, MatrixX* du) const;
  /// Switching function of coordinate i at base angle θ (law->SwitchFunction on one column).
  double SwitchValueAt(const VectorX& x, int i, double theta);
  /// Root of the switching function of coordinate i in [a, b] (values fa, fb of opposite
  /// sign, "positive" = fa > 0) by the Illinois method to ~1e-14 relative in θ.
  double LocateSwitch(const VectorX& x, int i, double a, double fa, double b, double fb);
  /// Adds the Euler–Maclaurin kink terms to g_h (nonlinear_hb.hpp "AFT"); needs u, dg, g_h.
  void CorrectForceAtSwitches(const VectorX& x);
  /// Powell's hybrid method (GSL hybridsj) from x, overwritten with its last iterate; at most
  /// options.max_newton_iterations iterations (returned), final ‖R‖∞ in residual_norm.
  int PowellHybrid(VectorX& x, double omega, double tol, double* residual_norm);
  double MonodromyMaxMultiplier(const VectorX& x, double omega);
  double HillMaxMultiplier(const VectorX& x, double omega);
};

}  // namespace geardyn
