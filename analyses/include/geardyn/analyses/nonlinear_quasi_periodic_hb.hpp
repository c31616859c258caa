/// @file
/// @brief Nonlinear harmonic balance of a gear system whose meshes run at several frequencies
/// (issue 18): the quasi-periodic steady state with contact loss and back-flank contact of the
/// slice meshes, on the torus of the independent mesh frequencies — the nonlinear counterpart of
/// quasi_periodic_hb.hpp, on the equation of system_nonlinear_hb.hpp.
///
/// **Equation** (system_nonlinear_hb.hpp, "Mapping onto NhbProblem"): in the flexible
/// coordinates z (q = T z + static part), M_z z̈ + C̄_z ż + K̄_z z + P_zᵀ g̃(P_z z, θ_1 … θ_m) =
/// f0_z + Re(f1_z e^{iω_m t}), g̃ the mesh-force law (slice force with clearance, or a linear
/// core's K2(θ_k)(δ − ε)) minus K̄2 u, each mesh at its own phase θ_k = r_k ω_m t + φ_k.
///
/// **Torus.** The bases are those of FindQuasiPeriodicBases (one per distinct phase ratio,
/// Ω_b = r_b ω_m / P_b); u(t) = Σ_{κ ∈ S} U_κ e^{iκ·ψ}, ψ_b = Ω_b t, S = {|κ|_1 ≤ H}, U_{−κ} =
/// conj(U_κ). A mesh of base b has θ_k = P_b ψ_b (r_k/r_b) + φ_k: its force is a function of
/// ψ_b alone, and the nonlinearity couples the bases only through the structure.
///
/// **Condensation** (as the single-frequency engine, nonlinear_hb.hpp): per κ, D_κ = −w_κ² M_z +
/// i w_κ C̄_z + K̄_z (w_κ = κ·Ω), R_κ = P_z D_κ⁻¹ P_zᵀ, Z_κ = R_κ⁻¹ and F̃_κ = Z_κ P_z D_κ⁻¹ F_κ;
/// the residual on the nonlinear coordinates is r_κ = Z_κ U_κ + N_κ(U) − F̃_κ for the κ of the
/// half set S⁺ (κ = 0 and the κ whose first non-zero order is positive).
///
/// **AFT on the torus.** u is synthesized on an N^d grid ψ = 2π j / N by FFTW's d-dimensional
/// backward c2c transform, the law is evaluated per base at its meshes' phases, and N_κ and the
/// Fourier coefficients Ĵ_j of ∂g̃/∂u are the forward transforms / N^d. The Newton Jacobian is
/// ∂N_κ/∂U_κ' = Ĵ_{κ−κ'} with the indices taken modulo N per axis: the exact derivative of the
/// sampled residual for any N > 2H (no Toeplitz bound), real-ified for U_{−κ'} = conj(U_κ').
/// The kinks of the clearance alias as O(N⁻²) (trapezoidal rule; no switch correction here):
/// N defaults to the smallest power of two ≥ max(32, 8H).
///
/// **Solve.** Newton with a backtracking line search on ‖r‖ from an initial guess: the caller's
/// (a neighbouring frequency's solution: NonlinearQuasiPeriodicHbResult::coordinate_harmonics),
/// else the linear quasi-periodic solution with every slice loaded (quasi_periodic_hb.hpp; exact
/// when no contact is lost), else the static contact-branch guess. Converged when
/// ‖r‖∞ ≤ newton_tolerance·(1 + ‖F̃‖∞ + max ‖N‖∞); otherwise status kNotConverged with the
/// residual. With one base the equations are those of SolveSystemNonlinearHb at period
/// multiple 1 with sampled AFT on N samples: the same answer to the Newton tolerance.
///
/// **Outputs** as QuasiPeriodicHbResult (the DTE δ_η − ε_η and the mesh force F_η sampled on the
/// grid: mean, torus RMS, peak-to-peak, spectral lines), plus per mesh the minimum and maximum
/// force, the torus fraction without drive-flank contact and whether the back flank was hit, and
/// the response Q_κ of every DOF. No stability verdict: Floquet theory needs a period; the
/// caller says so. Error estimate: the RMS of the DTE lines with |κ|_1 > 3H/4 relative to the
/// largest RMS DTE.
///
/// **Memory.** The dense Newton matrix has n_u(2|S⁺| − 1) real rows (n_u the nonlinear
/// coordinates); an H whose matrix and grid exceed memory_limit_bytes is refused with
/// InvalidInput naming total_order, the estimate and the limit.
#pragma once

#include <string>
#include <vector>

#include "geardyn/analyses/quasi_periodic_hb.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Options of SolveNonlinearQuasiPeriodicHb.
struct NonlinearQuasiPeriodicHbOptions {
  /// Total order H, ratio tolerance, memory limit (samples_per_base: the AFT grid per axis,
  /// 0 = the smallest power of two ≥ max(32, 8H)).
  QuasiPeriodicHbOptions torus;
  double newton_tolerance = 1e-9;  ///< relative residual (see @file "Solve"), in [1e-14, 1e-3]
  int max_newton_iterations = 60;  ///< in [1, 1000]
  /// False (with the field, value and bound in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief What the nonlinear model adds per mesh to QuasiPeriodicMeshOutput [N, -].
struct NonlinearQuasiPeriodicMeshContact {
  double min_force = 0.0;              ///< min of F_η on the grid [N] (< 0: back flank)
  double max_force = 0.0;              ///< [N]
  double contact_loss_fraction = 0.0;  ///< torus fraction without drive-flank contact [-]
  bool back_contact = false;           ///< the back flank carried load at some grid point
};

/// @brief Result at one mesh frequency.
struct NonlinearQuasiPeriodicHbResult {
  /// Bases, orders, response Q_κ of every DOF (n × |S|), DTE and force outputs per mesh, grid
  /// size (samples_per_base), summary (status, message, error estimate, counters: unknowns,
  /// harmonics, bases, newton_iterations, grid_points; warnings).
  QuasiPeriodicHbResult torus;
  std::vector<NonlinearQuasiPeriodicMeshContact> contact;  ///< per mesh, model order
  /// (n_u × |S|) U_κ of the nonlinear coordinates in the order of torus.orders: the initial
  /// guess of a neighbouring frequency.
  MatrixXc coordinate_harmonics;
  int newton_iterations = 0;
  double residual_norm = 0.0;  ///< final ‖r‖∞ [N]
  /// "caller", "linear" or "contact": where the converged Newton started.
  std::string initial_guess;
};

/// @brief The quasi-periodic nonlinear steady state at mesh frequency f_m [Hz] (of the ratio-1
/// phase), see the @file.
/// @param[in] initial optional U_κ (n_u × |S|, the torus.orders of the same model and options):
///   the first guess; on failure the linear and contact guesses are tried.
/// @throws InvalidInput on f_m ≤ 0 or non-finite, invalid options, a model without meshes or
///   with a NonlinearMeshCore, harmonic loads of order ≠ 1, an `initial` of the wrong size, or an
///   H over the memory limit.
NonlinearQuasiPeriodicHbResult SolveNonlinearQuasiPeriodicHb(
    const SystemModel& model, double mesh_frequency_hz,
    const NonlinearQuasiPeriodicHbOptions& options = {}, const MatrixXc* initial = nullptr);

/// @brief Estimated working memory of one solve (dense Newton matrix, its LU, the grid) [bytes].
double EstimateNonlinearQuasiPeriodicHbBytes(const SystemModel& model,
                                             const NonlinearQuasiPeriodicHbOptions& options);

}  // namespace geardyn
