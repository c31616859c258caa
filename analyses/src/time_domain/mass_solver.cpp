/// @file
/// @brief MassSolver: the block (Schur complement) solve of the arrow-shaped tooth-body mass and
/// the dense fallback.
#include "mass_solver.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace geardyn::internal {
namespace {

/// Root of i in the union–find forest (path halving).
int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

/// Sparse matrix of the nonzero entries of a dense block.
SparseMatrixRowMajor SparseOf(const MatrixX& a) {
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (a(i, j) != 0.0) t.emplace_back(static_cast<int>(i), static_cast<int>(j), a(i, j));
  SparseMatrixRowMajor s(a.rows(), a.cols());
  s.setFromTriplets(t.begin(), t.end());
  s.makeCompressed();
  return s;
}

}  // namespace

MassSolver::MassSolver(const MatrixX& mass, int num_system)
    : n_(static_cast<int>(mass.rows())), ns_(num_system) {
  const int ni = n_ - ns_;
  // Blocks of M_ii: connected components of its nonzero pattern.
  std::vector<int> parent(static_cast<std::size_t>(std::max(ni, 0)));
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < ni; ++i)
    for (int j = i + 1; j < ni; ++j)
      if (mass(ns_ + i, ns_ + j) != 0.0 || mass(ns_ + j, ns_ + i) != 0.0) {
        parent[Find(parent, i)] = Find(parent, j);
      }
  std::vector<std::vector<int>> blocks;
  std::vector<int> block_of(parent.size(), -1);
  bool small = ni > 0;
  for (int i = 0; i < ni; ++i) {
    const int r = Find(parent, i);
    if (block_of[r] < 0) {
      block_of[r] = static_cast<int>(blocks.size());
      blocks.emplace_back();
    }
    auto& b = blocks[static_cast<std::size_t>(block_of[r])];
    b.push_back(i);
    if (static_cast<int>(b.size()) > kMaxBlock) small = false;
  }
  if (small) {
    // M_ii⁻¹ block by block (each block SPD: LDLT, checked positive).
    std::vector<Eigen::Triplet<double>> inv;
    bool blocks_ok = true;
    for (const auto& b : blocks) {
      const auto m = static_cast<Eigen::Index>(b.size());
      MatrixX a(m, m);
      for (Eigen::Index r = 0; r < m; ++r)
        for (Eigen::Index c = 0; c < m; ++c) a(r, c) = mass(ns_ + b[r], ns_ + b[c]);
      const Eigen::LDLT<MatrixX> f(a);
      if (f.info() != Eigen::Success || !f.isPositive() || !(f.vectorD().minCoeff() > 0.0)) {
        blocks_ok = false;
        break;
      }
      const MatrixX ai = f.solve(MatrixX::Identity(m, m));
      for (Eigen::Index r = 0; r < m; ++r)
        for (Eigen::Index c = 0; c < m; ++c) inv.emplace_back(b[r], b[c], ai(r, c));
    }
    if (blocks_ok) {
      inv_ii_.resize(ni, ni);
      inv_ii_.setFromTriplets(inv.begin(), inv.end());
      inv_ii_.makeCompressed();
      coupling_ = SparseOf(mass.topRightCorner(ns_, ni));
      const SparseMatrixRowMajor coupling_t = SparseOf(mass.bottomLeftCorner(ni, ns_));
      inv_ii_is_ = SparseMatrixRowMajor(inv_ii_ * coupling_t);
      // S = M_ss − M_si (M_ii⁻¹ M_is): dense N×N (N small next to n).
      const MatrixX schur = mass.topLeftCorner(ns_, ns_) - MatrixX(coupling_ * MatrixX(inv_ii_is_));
      dense_.compute(schur);
      ok_ = dense_.info() == Eigen::Success && dense_.isPositive();
      block_ = true;
      num_blocks_ = static_cast<int>(blocks.size());
      return;
    }
  }
  dense_.compute(mass);
  ok_ = dense_.info() == Eigen::Success && dense_.isPositive();
}

void MassSolver::Solve(const Eigen::Ref<const VectorX>& f, VectorX* a) const {
  if (a->size() != n_) a->resize(n_);
  if (!block_) {
    *a = f;
    dense_.solveInPlace(*a);
    return;
  }
  const int ni = n_ - ns_;
  auto ai = a->tail(ni);
  auto as = a->head(ns_);
  ai.noalias() = inv_ii_ * f.tail(ni);          // M_ii⁻¹ f_i
  as.noalias() = f.head(ns_) - coupling_ * ai;  // f_s − M_si M_ii⁻¹ f_i
  dense_.solveInPlace(as);                      // a_s = S⁻¹ (…)
  ai.noalias() -= inv_ii_is_ * as;              // a_i = M_ii⁻¹ f_i − M_ii⁻¹ M_is a_s
}

}  // namespace geardyn::internal
