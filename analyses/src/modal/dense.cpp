// Dense path of ComputeModes: with vectors and 0 < num_modes < n, only the wanted eigenpairs
// (SolveGeneralizedEigenDenseSubset: tridiagonalization and LAPACK dstemr, ≈ 3.7 n³ flops instead
// of ≈ 9 n³; docs/benchmarks.md "Dense few modes"), falling back to the full solve if dstemr
// fails; otherwise every eigenpair (Cholesky of M and tridiagonal QR,
// SolveGeneralizedEigenDense), then the requested subset.
#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "geardyn/numerics/symmetric_eigen.hpp"
#include "geardyn/numerics/symmetric_eigen_subset.hpp"
#include "modal/modal_internal.hpp"

namespace geardyn::internal {

GeneralizedEigenResult SolveModesDense(const MeanSystem& sys, const ModalOptions& options,
                                       bool compute_vectors) {
  GeneralizedEigenOptions eig_options;
  eig_options.compute_vectors = compute_vectors;
  eig_options.zero_tol = options.zero_tol;
  const MatrixX K(sys.K), M(sys.M);
  std::string subset_failure;
  if (compute_vectors && options.num_modes > 0 && options.num_modes < K.rows()) {
    GeneralizedEigenResult subset =
        SolveGeneralizedEigenDenseSubset(K, M, options.num_modes, options.shift, eig_options);
    if (subset.summary.status != Status::kNotConverged) return subset;
    subset_failure = subset.summary.message;
  }
  GeneralizedEigenResult result = SolveGeneralizedEigenDense(K, M, eig_options);
  if (!subset_failure.empty()) {
    result.summary.warnings.push_back(subset_failure + "; used the full dense solve");
  }
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
