/// @file
/// @brief System-level damping added to C0 of a built model: Rayleigh C_R = α M + β K̄ or modal
/// C_ζ = M Φ diag(2 ζ_r ω_r) Φᵀ M (one ζ for every mode, or one per mode).
///
/// **K̄** is the MEAN stiffness K0 + Σ_k G_kᵀ K̄2_k G_k (meshes included, AssembleMeanStiffness),
/// so that the undamped modes of the mean system stay classical modes of the damped one.
///
/// **Modal damping.** (Φ, ω_r) are the M-orthonormal modes of (K̄, M) (Φᵀ M Φ = I), computed
/// per decoupled DOF block by SolveGeneralizedEigenDense (O(n³): small and medium systems). Then
/// Φᵀ C_ζ Φ = diag(2 ζ_r ω_r): mode r of the mean system decays as e^{−ζ_r ω_r t} with the damped
/// frequency ω_r √(1 − ζ_r²). Rigid-body modes (ω_r = 0 by the solvers' one criterion
/// |λ| ≤ zero_tol·s, symmetric_eigen.hpp) get no damping. The per-mode list applies to the
/// flexible modes of the whole system in ascending frequency; the modes beyond it take
/// `modal_ratio` (0 if not given).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Rayleigh or modal system damping (at most one of the two kinds).
struct SystemDamping {
  double rayleigh_alpha = 0.0;        ///< α ≥ 0 [1/s]
  double rayleigh_beta = 0.0;         ///< β ≥ 0 [s]
  std::optional<double> modal_ratio;  ///< ζ ∈ [0, 1) of every flexible mode [-]
  /// ζ_r ∈ [0, 1) of the lowest flexible modes, ascending frequency (overrides modal_ratio) [-].
  std::vector<double> modal_ratios;

  /// True when Rayleigh coefficients are given (α or β > 0).
  bool has_rayleigh() const { return rayleigh_alpha > 0.0 || rayleigh_beta > 0.0; }
  /// True when a modal ratio or a per-mode list is given.
  bool has_modal() const { return modal_ratio.has_value() || !modal_ratios.empty(); }
  /// @brief False (with field, value and bound in `why`) on a negative or non-finite α or β, a
  /// ratio outside [0, 1), or both kinds at once.
  bool IsValid(std::string* why) const;
};

/// @brief `model` with `damping` added to its C0 (see the @file); the model's rayleigh_alpha,
/// rayleigh_beta and modal_damping_ratio report it.
/// @param[in] model a built model (its K̄ and M are used as they are, e.g. after RestrictToPlanar).
/// @throws InvalidInput if !damping.IsValid(), or if the dense eigen-decomposition of the mean
///   system fails (not converged, K̄ not positive semi-definite).
SystemModel AddSystemDamping(const SystemModel& model, const SystemDamping& damping);

}  // namespace geardyn
