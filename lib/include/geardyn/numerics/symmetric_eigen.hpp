/// @file
/// @brief Generalized symmetric eigen solvers K φ = λ M φ for the undamped modes of the mean
/// (LTI) system (spec 02 "Eigen (LTI)"): a dense solver for small systems and ARPACK's
/// shift-invert Lanczos for the lowest modes of large sparse ones.
///
/// **Problem.** K (n × n) symmetric positive semidefinite, possibly singular (free rigid-body
/// motion); M (n × n) symmetric positive definite. The eigenvalues are λ = ω² [rad²/s² when K is
/// in N/m, N·m/rad and M in kg, kg·m²]; the vectors are M-orthonormal: Φᵀ M Φ = I.
///
/// **Spectrum scale.** s = max_i |K_ii| / M_ii (a Rayleigh quotient, hence a lower bound of
/// λ_max, and in the units of λ whatever the units of the individual DOFs; s = 1 when K has a
/// zero diagonal). The default ARPACK shift is measured against it.
///
/// **Rigid-body modes** (spec 02; architecture §3.7): the one criterion of rigid_modes.hpp. A
/// computed pair with |λ| ≤ zero_tol·φᵀDφ (φᵀMφ = 1, D = diag K) is round-off around an exact
/// zero — a null vector of K in the diagonally scaled coordinates, whatever the masses and the
/// units; it is set to exactly 0, counted in `num_rigid_body_modes` and reported as a warning,
/// not a failure. ARPACK always computes the Ritz vectors for this test; the dense solver without
/// vectors applies the same criterion as a count (the eigenvalues ≤ zero_tol of the unit-diagonal
/// D^{-1/2}KD^{-1/2}, values only) and zeroes that many eigenvalues of smallest |λ|. A
/// λ < −zero_tol·φᵀDφ means K is not positive semidefinite:
/// status kNumericalIssue with the offending value (the eigenpairs are still returned). Results
/// never contain NaN: non-finite values give kNumericalIssue and empty results.
///
/// **ARPACK shift.** `SolveGeneralizedEigenArpack` runs ARPACK's dsaupd/dseupd in mode 3
/// (shift-invert, bmat = 'G', M-inner product) on OP = (K − σM)⁻¹ M, which = "LM": the λ nearest
/// σ. The default σ = −kDefaultShiftFraction·s is slightly below zero, so that
/// * K − σM = K + |σ| M is positive definite even when K is singular (K is never inverted, and
///   the sparse LDLᵀ path of linear_operator.hpp applies);
/// * the rigid-body zeros are the eigenvalues nearest σ, hence found first, with the rest of the
///   lowest modes in ascending order;
/// * |σ| stays small against the lowest flexible eigenvalues of typical systems, so that
///   ν = 1/(λ − σ) keeps them well separated (convergence) and λ = σ + 1/ν loses no accuracy.
/// A σ inside the spectrum returns the num_modes eigenvalues nearest σ (LU path). A σ that is an
/// eigenvalue to working precision is reported as kNumericalIssue ("numerically singular").
///
/// **Thread safety.** ARPACK's reverse-communication routines keep state in Fortran SAVE
/// variables; calls to SolveGeneralizedEigenArpack are serialized by a process-wide mutex.
#pragma once

#include <optional>
#include <string>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/numerics/linear_operator.hpp"
#include "geardyn/numerics/rigid_modes.hpp"

namespace geardyn {

/// Default ARPACK shift as a fraction of the spectrum scale s: σ = −1e-6·s.
inline constexpr double kDefaultShiftFraction = 1e-6;

/// @brief Options of the generalized symmetric eigen solvers.
struct GeneralizedEigenOptions {
  /// Return the M-orthonormal eigenvectors (pay only if asked).
  bool compute_vectors = true;
  /// |λ| ≤ zero_tol·φᵀDφ is a rigid-body zero; λ < −zero_tol·φᵀDφ an error (K not PSD) [-].
  double zero_tol = kRigidNullTol;
  /// ARPACK: relative accuracy of the Ritz values ν = 1/(λ − σ); 0 → machine ε [-].
  double tol = 1e-12;
  /// ARPACK: maximum number of implicit restarts (iparam[2], "maxit"), ≥ 1.
  int max_iterations = 1000;
  /// ARPACK: number of Lanczos vectors ncv, num_modes < ncv ≤ n; 0 → min(n, max(2·num_modes+1,
  /// 20)).
  int num_lanczos_vectors = 0;
  /// ARPACK: factorization of K − σM (see linear_operator.hpp).
  ShiftFactorization factorization = ShiftFactorization::kAuto;

  /// @brief True when every field is in range; otherwise `why` names the field, value and bound.
  bool IsValid(std::string* why) const;
};

/// @brief Eigenpairs of K φ = λ M φ, ascending, with a status.
struct GeneralizedEigenResult {
  /// (m) λ = ω², ascending [rad²/s²]; exact zeros for the rigid-body modes. m = n (dense) or
  /// the number of converged modes (ARPACK; num_modes on success).
  VectorX eigenvalues;
  /// (n × m) M-orthonormal eigenvectors, column k for eigenvalues(k), sign fixed so that the
  /// entry of largest magnitude is positive; empty unless options.compute_vectors.
  MatrixX vectors;
  /// Number of eigenvalues set to zero as rigid-body modes [-].
  int num_rigid_body_modes = 0;
  /// Shift σ used by ARPACK [rad²/s²]; 0 for the dense solver (no shift).
  double sigma = 0.0;
  /// Spectrum scale s = max_i |K_ii|/M_ii that the default σ refers to [rad²/s²].
  double spectrum_scale = 0.0;
  /// Status and message; counters "iterations" (ARPACK restarts), "operator_applications"
  /// (OP = (K − σM)⁻¹M), "mass_applications" (M x), "factorizations" (Cholesky of M and of
  /// K − σM), "converged" and "arpack_info" (ARPACK only); warnings list the rigid-body modes.
  Summary summary;
};

/// @brief All eigenpairs of the dense pencil (K, M): Cholesky M = L Lᵀ, then the symmetric
/// eigenproblem of L⁻¹ K L⁻ᵀ (Eigen's tridiagonal QR), φ = L⁻ᵀ y. O(n³) time, O(n²) memory.
/// @param[in] K (n × n) symmetric positive semidefinite stiffness [N/m, N·m/rad], n ≥ 1.
/// @param[in] M (n × n) symmetric positive definite mass [kg, kg·m²].
/// @param[in] options see GeneralizedEigenOptions (the ARPACK fields are ignored).
/// @return n eigenpairs, ascending; status kSuccess, or kNumericalIssue if K is not PSD (clearly
/// negative λ), or kNotConverged if the QR iteration failed.
/// @throws InvalidInput naming `K`, `M` or the options field: non-square or mismatched sizes,
/// empty, non-finite or non-symmetric matrices, M not positive definite.
GeneralizedEigenResult SolveGeneralizedEigenDense(const MatrixX& K, const MatrixX& M,
                                                  const GeneralizedEigenOptions& options = {});

/// @brief The num_modes eigenpairs of the sparse pencil (K, M) nearest σ (by default the lowest
/// ones, rigid-body zeros included), by ARPACK shift-invert Lanczos (see the file comment).
/// @param[in] K (n × n) symmetric positive semidefinite stiffness [N/m, N·m/rad], both triangles
/// stored; K need not be invertible.
/// @param[in] M (n × n) symmetric positive definite mass [kg, kg·m²], both triangles stored.
/// @param[in] num_modes number of eigenpairs wanted, 1 ≤ num_modes < n.
/// @param[in] sigma shift σ [rad²/s²]; std::nullopt → −kDefaultShiftFraction·s.
/// @param[in] options see GeneralizedEigenOptions.
/// @return on success num_modes eigenpairs, ascending. kNotConverged (ARPACK info 1: max
/// iterations, or 3: no shifts could be applied) returns the modes that did converge and puts
/// the ARPACK info code and the number converged in the message and counters. kNumericalIssue for
/// a singular shift, another ARPACK error, K not PSD, or when built with GEARDYN_WITH_ARPACK=OFF
/// (message "ARPACK unavailable (built with GEARDYN_WITH_ARPACK=OFF)").
/// @throws InvalidInput naming `K`, `M`, `num_modes`, `sigma` or the options field: non-square or
/// mismatched sizes, non-finite or non-symmetric matrices, M not positive definite, num_modes
/// outside [1, n − 1], ncv outside (num_modes, n].
GeneralizedEigenResult SolveGeneralizedEigenArpack(const SparseMatrix& K, const SparseMatrix& M,
                                                   int num_modes,
                                                   std::optional<double> sigma = std::nullopt,
                                                   const GeneralizedEigenOptions& options = {});

}  // namespace geardyn
