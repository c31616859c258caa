/// @file
/// @brief Internal: the input checks and the result post-processing (sorting, rigid-body zeros,
/// K-not-PSD detection, M-normalization, sign convention) shared by the dense and ARPACK
/// generalized symmetric eigen solvers of geardyn/numerics/symmetric_eigen.hpp.
#pragma once

#include <functional>
#include <string>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/numerics/symmetric_eigen.hpp"

namespace geardyn::internal {

/// Relative asymmetry max|A − Aᵀ| / max|A| above which a matrix is rejected as non-symmetric.
inline constexpr double kSymmetryTol = 1e-10;

/// @brief Throws InvalidInput naming `K` or `M`: non-square, mismatched, empty, non-finite,
/// non-symmetric matrices, or M with a non-positive diagonal entry (then M is not PD).
void CheckPencil(const MatrixX& K, const MatrixX& M);
/// @copydoc CheckPencil(const MatrixX&, const MatrixX&)
void CheckPencil(const SparseMatrix& K, const SparseMatrix& M);

/// @brief Throws InvalidInput(why) unless options.IsValid(&why).
void CheckOptions(const GeneralizedEigenOptions& options);

/// @brief s = max_i |K_ii| / M_ii [units of λ]; 1 when that is 0. @pre M_ii > 0.
double SpectrumScale(const VectorX& K_diagonal, const VectorX& M_diagonal);

/// @brief Post-processing shared by both solvers, writing into `result`:
/// * non-finite λ or φ → kNumericalIssue naming `step`, empty eigenvalues and vectors;
/// * sorts ascending (vectors follow);
/// * each vector M-normalized with `M_vectors` = M·vectors (n × m; empty when the vectors are
///   already M-normalized) and its sign fixed so that its entry of largest magnitude is positive;
/// * the one rigid-body criterion of rigid_modes.hpp (D = RigidScaling(K_diagonal)): with
///   vectors (n × m), a pair with |λ| ≤ zero_tol·φᵀDφ (φᵀMφ = 1) is rigid; without vectors
///   (0 columns) the `rigid_count` ≥ 0 eigenvalues of smallest |λ| are, rigid_count being the
///   number of eigenvalues ≤ zero_tol of the unit-diagonal K̃ = D^{-1/2}KD^{-1/2} (the caller's
///   count). Rigid λ are set to 0 and reported in a warning;
/// * any other λ below −zero_tol·φᵀDφ (without vectors −zero_tol·s) → kNumericalIssue ("K is
///   not positive semidefinite") unless the status is already not kSuccess.
/// * `quadratic_form` (optional, φ ↦ φᵀKφ): with vectors, a pair whose λ fails the criterion
///   but lies within the solver's round-off of zero (|λ| ≤ 100·n·ε·max(s, max|λ|)) is tested
///   again on its Rayleigh quotient φᵀKφ, the quantity the criterion is defined on. An
///   eigensolver's λ carries an absolute error ~ n·ε·λ_max, while φᵀDφ of the rigid mode of a
///   heavy body is ~ k/M_heavy: with mass ratios of 1e12 the bare λ test called a rigid mode
///   "K not positive semidefinite" (stress suite, issue 16); the null vector itself is exact to
///   round-off, so φᵀKφ ~ ε²λ_max is far below the bound.
/// Expects result->spectrum_scale set; keeps an existing non-success status and message.
void FinalizeEigenpairs(VectorX values, MatrixX vectors, const MatrixX& M_vectors,
                        const VectorX& K_diagonal, int rigid_count, double zero_tol,
                        const std::string& step, GeneralizedEigenResult* result,
                        const std::function<double(const VectorX&)>& quadratic_form = {});

}  // namespace geardyn::internal
