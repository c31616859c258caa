/// @file
/// @brief Rigid-body modes of a mean (LTI) stiffness: the null space of K̄ measured in the
/// coordinates scaled by √diag(K̄), so that mixed units (m, rad) do not decide what "zero" is.
/// Shared by the static deflection, the linear harmonic balance (k = 0 penalty) and the
/// nonlinear system harmonic balance (reduction to the flexible coordinates).
///
/// **Scaling.** D = diag(K̄) (a zero diagonal entry — an unsupported, uncoupled coordinate, whose
/// row and column of a PSD K̄ are then zero — is replaced by max diag, which leaves the null space
/// unchanged); K̃ = D^{-1/2} K̄ D^{-1/2} = V Λ Vᵀ; the rigid modes are the eigenvectors with
/// |λ| < null_tol·max|λ|. In the original coordinates a rigid mode is r = D^{-1/2} v (K̄ r = 0)
/// and the matching "unit torque" direction is D^{1/2} v.
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

/// @brief Rigid-body modes of a symmetric PSD mean stiffness (dense eigen-solve).
/// @param[in] mean_stiffness K̄ (n × n) [N/m, N, N·m].
/// @param[in] null_tol eigenvalues of K̃ below null_tol·max count as zero, in (0, 1).
RigidBodyModes ComputeRigidBodyModes(const MatrixX& mean_stiffness, double null_tol = 1e-10);

}  // namespace geardyn
