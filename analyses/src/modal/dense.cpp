// Dense path of ComputeModes: every eigenpair of the dense pencil (K̄, M) (Cholesky of M and
// tridiagonal QR, SolveGeneralizedEigenDense), then the requested subset.
#include <algorithm>
#include <numeric>
#include <vector>

#include "geardyn/numerics/symmetric_eigen.hpp"
#include "modal/modal_internal.hpp"

namespace geardyn::internal {

GeneralizedEigenResult SolveModesDense(const MeanSystem& sys, const ModalOptions& options,
                                       bool compute_vectors) {
  GeneralizedEigenOptions eig_options;
  eig_options.compute_vectors = compute_vectors;
  eig_options.zero_tol = options.zero_tol;
  GeneralizedEigenResult result =
      SolveGeneralizedEigenDense(MatrixX(sys.K), MatrixX(sys.M), eig_options);
  const Eigen::Index n = result.eigenvalues.size();
  if (options.num_modes == 0 || options.num_modes >= n) return result;

  // Keep num_modes of them: the lowest, or the nearest the shift (then sorted ascending, as the
  // ARPACK path returns them).
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  if (options.shift.has_value()) {
    const double sigma = *options.shift;
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
      return std::abs(result.eigenvalues(a) - sigma) < std::abs(result.eigenvalues(b) - sigma);
    });
  }
  order.resize(static_cast<std::size_t>(options.num_modes));
  std::sort(order.begin(), order.end());
  VectorX values(options.num_modes);
  MatrixX vectors(compute_vectors ? result.vectors.rows() : 0,
                  compute_vectors ? options.num_modes : 0);
  int rigid = 0;
  for (int k = 0; k < options.num_modes; ++k) {
    values(k) = result.eigenvalues(order[k]);
    if (values(k) == 0.0) ++rigid;
    if (compute_vectors) vectors.col(k) = result.vectors.col(order[k]);
  }
  result.eigenvalues = std::move(values);
  result.vectors = std::move(vectors);
  result.num_rigid_body_modes = rigid;
  return result;
}

}  // namespace geardyn::internal
