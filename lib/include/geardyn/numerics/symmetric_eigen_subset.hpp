/// @file
/// @brief The dense generalized symmetric eigen solver for a few eigenpairs: the `count` lowest
/// of K φ = λ M φ, or the `count` nearest a shift σ, with their M-orthonormal vectors, without
/// computing the other n − count vectors.
///
/// **Method.** M = L Lᵀ (Cholesky), C = L⁻¹ K L⁻ᵀ, C = Q T Qᵀ (Householder tridiagonalization,
/// Eigen), then the wanted eigenpairs (index range il…iu) of the tridiagonal T by LAPACK's
/// multiple relatively robust representations (dstemr, Dhillon & Parlett 2004: O(n·count) for
/// the vectors), and φ = L⁻ᵀ Q z. Cost ≈ (1/3 + 2 + 4/3) n³ flops plus O(n² count), against
/// ≈ 9 n³ for all vectors (tridiagonal QR with accumulated rotations plus the formation of Q:
/// Golub & Van Loan, Matrix Computations, 4th ed., §8.3.6 and Table 8.3.1). The eigenvalues and
/// the rigid-body rule are those of SolveGeneralizedEigenDense (symmetric_eigen.hpp); the
/// window of the `count` eigenvalues nearest σ is contiguous in the sorted spectrum, so it is an
/// index range too (found from all the eigenvalues of T, O(n²)).
#pragma once

#include <optional>

#include "geardyn/numerics/symmetric_eigen.hpp"

namespace geardyn {

/// @brief The `count` lowest eigenpairs of the dense pencil (K, M), or the `count` nearest
/// `sigma`, with M-orthonormal vectors (always computed; options.compute_vectors is ignored).
/// @param[in] K (n × n) symmetric positive semidefinite stiffness [N/m, N·m/rad], n ≥ 1.
/// @param[in] M (n × n) symmetric positive definite mass [kg, kg·m²].
/// @param[in] count number of eigenpairs wanted, 1 ≤ count ≤ n.
/// @param[in] sigma shift σ [rad²/s²] (finite); std::nullopt → the lowest eigenpairs.
/// @param[in] options zero_tol as in SolveGeneralizedEigenDense (the ARPACK fields are ignored).
/// @return `count` eigenpairs, ascending, counter "subset_solver" = 1; status kSuccess,
/// kNumericalIssue if K is not PSD, or kNotConverged when the tridiagonal solver (dstemr) fails
/// (its info in the message and counter "dstemr_info"; the caller may fall back to the full
/// solve).
/// @throws InvalidInput naming `K`, `M`, `count` or `sigma`: as SolveGeneralizedEigenDense, and
/// count outside [1, n] or a non-finite σ.
GeneralizedEigenResult SolveGeneralizedEigenDenseSubset(
    const MatrixX& K, const MatrixX& M, int count, std::optional<double> sigma = std::nullopt,
    const GeneralizedEigenOptions& options = {});

}  // namespace geardyn
