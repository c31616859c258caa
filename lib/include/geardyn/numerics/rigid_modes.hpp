/// @file
/// @brief Rigid-body modes of a mean (LTI) stiffness: the null space of K̄ measured in the
/// coordinates scaled by √diag(K̄), so that mixed units (m, rad) do not decide what "zero" is.
/// Shared by the static deflection, the linear harmonic balance (k = 0 penalty) and the
/// nonlinear system harmonic balance (reduction to the flexible coordinates).
///
/// **The one rigid-body criterion** (architecture §3.7; used by modes, linear and nonlinear HB,
/// Floquet's deflation and the static deflection): a displacement pattern φ is a rigid-body mode
/// of K̄ when its Rayleigh quotient in the diagonally scaled coordinates is round-off,
/// \f[ \mu(\varphi) = \frac{|\varphi^T \bar K \varphi|}{\varphi^T D \varphi}
///      \le \tau = 10^{-10}, \qquad D = \mathrm{diag}\,\bar K. \f]
/// μ is dimensionless and independent of the DOF units and of the masses: a support of stiffness
/// k on a DOF whose diagonal is k_ii gives μ ≈ k/k_ii, so a real soft mode (an axial bearing of
/// 0.3 N/m beside a 2e7 N/m helical mesh: μ ≈ 1e-8) stays flexible, while the round-off of an
/// exact null vector is μ ~ n·ε ≈ 1e-15. For the eigenvectors of K̃ below, μ is the eigenvalue;
/// for a generalized eigenpair (λ, φ) of (K̄, M), μ = |λ|·φᵀMφ / φᵀDφ.
///
/// **Scaling.** D = diag(K̄) (a zero diagonal entry — an unsupported, uncoupled coordinate, whose
/// row and column of a PSD K̄ are then zero — is replaced by max diag, which leaves the null space
/// unchanged); K̃ = D^{-1/2} K̄ D^{-1/2} = V Λ Vᵀ; the rigid modes are the eigenvectors with
/// |λ| ≤ null_tol (K̃ has a unit diagonal, so this is the criterion μ ≤ τ above). In the original
/// coordinates a rigid mode is r = D^{-1/2} v (K̄ r = 0) and the matching "unit torque" direction is
/// D^{1/2} v.
#pragma once

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief The rigid-body modes of K̄ (see the file comment).
struct RigidBodyModes {
  MatrixX scaled;        ///< (n × r) V: orthonormal null vectors of K̃
  MatrixX modes;         ///< (n × r) D^{-1/2} V: K̄ · modes = 0 [m, rad per unit]
  MatrixX loads;         ///< (n × r) D^{1/2} V: the load directions the supports cannot react
  VectorX sqrt_d;        ///< (n) D^{1/2}
  VectorX inv_sqrt_d;    ///< (n) D^{-1/2}
  VectorX eigenvalues;   ///< (n) λ of K̃, ascending
  MatrixX eigenvectors;  ///< (n × n) all eigenvectors of K̃ (the first r are `scaled`)
  bool ok = true;        ///< false when the eigen-solve failed (then r = 0)
  /// Number r of rigid-body modes.
  int count() const { return static_cast<int>(scaled.cols()); }
  /// @brief The part of a load f along the rigid modes, in the scaled measure ‖Vᵀ D^{-1/2} f‖
  /// relative to ‖D^{-1/2} f‖ (0 for f = 0): how unbalanced f is [-].
  double UnbalancedFraction(const VectorX& f) const;
  /// @brief f minus its unbalanced part: f − D^{1/2} V Vᵀ D^{-1/2} f.
  VectorX Balance(const VectorX& f) const;
};

/// The threshold τ of the rigid-body criterion (file comment) [-].
inline constexpr double kRigidNullTol = 1e-10;

/// @brief The scaling D of the criterion: |diag K̄|, with entries ≤ 1e-14·max (unsupported,
/// uncoupled coordinates) replaced by max (1 when K̄ = 0).
/// @param[in] stiffness_diagonal (n) diag K̄ [N/m, N·m/rad].
/// @return (n) D [N/m, N·m/rad].
VectorX RigidScaling(const VectorX& stiffness_diagonal);

/// @brief μ(φ) = |φᵀK̄φ| / φᵀDφ of the file comment [-] (φ = 0: 0 if φᵀK̄φ = 0, else ∞).
/// @param[in] phi_k_phi φᵀK̄φ (for an eigenpair of (K̄, M): λ·φᵀMφ) [J-like].
/// @param[in] scaling (n) D from RigidScaling.
/// @param[in] phi (n) the pattern [m, rad].
double ScaledStiffnessQuotient(double phi_k_phi, const VectorX& scaling, const VectorX& phi);

/// @brief True when φ is a rigid-body pattern of K̄: ScaledStiffnessQuotient ≤ null_tol.
bool IsRigidBodyPattern(double phi_k_phi, const VectorX& scaling, const VectorX& phi,
                        double null_tol = kRigidNullTol);

/// @brief Rigid-body modes of a symmetric PSD mean stiffness (dense eigen-solve).
/// @param[in] mean_stiffness K̄ (n × n) [N/m, N, N·m].
/// @param[in] null_tol eigenvalues of K̃ (unit diagonal) ≤ null_tol count as zero, in (0, 1).
RigidBodyModes ComputeRigidBodyModes(const MatrixX& mean_stiffness,
                                     double null_tol = kRigidNullTol);

}  // namespace geardyn
