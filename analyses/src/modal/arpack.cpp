// ARPACK path of ComputeModes: the lowest (or nearest-shift) eigenpairs of the sparse pencil
// (K̄, M) by shift-invert Lanczos (SolveGeneralizedEigenArpack; K̄ is never inverted).
#include <optional>

#include "geardyn/numerics/symmetric_eigen.hpp"
#include "modal/modal_internal.hpp"

namespace geardyn::internal {

GeneralizedEigenResult SolveModesArpack(const MeanSystem& sys, const ModalOptions& options,
                                        int num_modes, bool compute_vectors) {
  GeneralizedEigenOptions eig_options;
  eig_options.compute_vectors = compute_vectors;
  eig_options.zero_tol = options.zero_tol;
  eig_options.tol = options.arpack_tol;
  return SolveGeneralizedEigenArpack(sys.K, sys.M, num_modes, options.shift, eig_options);
}

}  // namespace geardyn::internal
