/// @file
/// @brief Solves M a = f for the time-domain mass (internal to the time-domain analyses).
///
/// M = [M_ss, M_si; M_is, M_ii] has the N system DOFs first and the internal coordinates of the
/// nonlinear cores after them. For tooth bodies (tooth_body.hpp AssembleToothMass) M_ii is block
/// diagonal (per type-A tooth one 1×1 block; per type-B tooth a 1×1 for u_r and a 2×2 for
/// (u_t, φ)) and M_si couples each tooth with its trunk's θz only: an arrow matrix. Its solve by
/// blocks (Schur complement onto the system coordinates), \f[ S = M_{ss} - M_{si} M_{ii}^{-1}
/// M_{is},\quad a_s = S^{-1}(f_s - M_{si} M_{ii}^{-1} f_i),
///     \quad a_i = M_{ii}^{-1} f_i - (M_{ii}^{-1} M_{is})\, a_s, \f]
/// costs O(N² + nnz) per solve instead of the O(n²) of a dense factorization of the whole M (for
/// the rig with type-A teeth N = 12, n = 112). When M_ii is not block diagonal with small blocks
/// (a general core's InternalMass), the dense LDLT of the whole M is used.
#pragma once

#include <Eigen/Cholesky>
#include <vector>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn::internal {

/// Row-major sparse matrix: the fast layout for matrix–vector products.
using SparseMatrixRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

/// @brief Factorization of the time-domain mass (see the @file). Immutable after construction:
/// Solve may be called from several threads at once.
class MassSolver {
 public:
  /// Largest diagonal block of M_ii solved by blocks; larger ones take the dense path.
  static constexpr int kMaxBlock = 16;

  /// @param[in] mass (n×n) symmetric positive definite. @param[in] num_system N ≤ n.
  MassSolver(const MatrixX& mass, int num_system);

  /// True when the factorization succeeded (M numerically positive definite).
  bool ok() const { return ok_; }
  /// True when the block (Schur) path is used.
  bool is_block() const { return block_; }
  /// Number of diagonal blocks of M_ii (block path; 0 otherwise).
  int num_blocks() const { return num_blocks_; }

  /// a = M⁻¹ f (a is resized to n; no allocation when it already has that size).
  void Solve(const Eigen::Ref<const VectorX>& f, VectorX* a) const;

 private:
  int n_ = 0, ns_ = 0;
  bool ok_ = false, block_ = false;
  int num_blocks_ = 0;
  Eigen::LDLT<MatrixX> dense_;      // whole M (dense path) or S (block path)
  SparseMatrixRowMajor coupling_;   // M_si (N × I)
  SparseMatrixRowMajor inv_ii_;     // M_ii⁻¹ (I × I, block diagonal)
  SparseMatrixRowMajor inv_ii_is_;  // M_ii⁻¹ M_is (I × N)
};

}  // namespace geardyn::internal
