// The options of the generalized symmetric eigen solvers and the dense solver (the ARPACK one is in
// symmetric_eigen_arpack.cpp).
#include "geardyn/numerics/symmetric_eigen.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <sstream>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "numerics/symmetric_eigen_internal.hpp"

namespace geardyn {

bool GeneralizedEigenOptions::IsValid(std::string* why) const {
  std::ostringstream out;
  if (!(zero_tol >= 0.0 && std::isfinite(zero_tol))) {
    out << "GeneralizedEigenOptions.zero_tol: must be finite and ≥ 0, got " << zero_tol;
  } else if (!(tol >= 0.0 && tol < 1.0)) {
    out << "GeneralizedEigenOptions.tol: must be in [0, 1), got " << tol;
  } else if (max_iterations < 1) {
    out << "GeneralizedEigenOptions.max_iterations: must be ≥ 1, got " << max_iterations;
  } else if (num_lanczos_vectors < 0) {
    out << "GeneralizedEigenOptions.num_lanczos_vectors: must be ≥ 0 (0 = automatic), got "
        << num_lanczos_vectors;
  } else {
    return true;
  }
  if (why != nullptr) *why = out.str();
  return false;
}

GeneralizedEigenResult SolveGeneralizedEigenDense(const MatrixX& K, const MatrixX& M,
                                                  const GeneralizedEigenOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  internal::CheckOptions(options);
  internal::CheckPencil(K, M);

  GeneralizedEigenResult result;
  result.spectrum_scale = internal::SpectrumScale(K.diagonal(), M.diagonal());
  Summary& summary = result.summary;

  // M = L Lᵀ; C = L⁻¹ K L⁻ᵀ has the eigenvalues of the pencil, and φ = L⁻ᵀ y is M-orthonormal
  // when the y are orthonormal (Golub & Van Loan, Matrix Computations, 4th ed., §8.7.2).
  const Eigen::LLT<MatrixX> cholesky(M);
  summary.counters["factorizations"] = 1;
  GEARDYN_THROW_UNLESS(cholesky.info() == Eigen::Success,
                       "M: not positive definite (its Cholesky factorization failed)");
  MatrixX C = K;
  cholesky.matrixL().solveInPlace<Eigen::OnTheLeft>(C);
  cholesky.matrixU().solveInPlace<Eigen::OnTheRight>(C);
  const Eigen::SelfAdjointEigenSolver<MatrixX> eigen(
      C, options.compute_vectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  summary.counters["iterations"] = 0;
  summary.counters["operator_applications"] = 0;
  summary.counters["mass_applications"] = 0;

  if (eigen.info() != Eigen::Success) {
    summary.status = Status::kNotConverged;
    summary.message = "the tridiagonal QR iteration of L⁻¹KL⁻ᵀ did not converge";
  } else {
    MatrixX vectors;
    int rigid_count = -1;
    if (options.compute_vectors) {
      vectors = eigen.eigenvectors();
      cholesky.matrixU().solveInPlace(vectors);  // already M-orthonormal: no renormalization
    } else {
      // Without vectors, the rigid-body criterion (rigid_modes.hpp) as a count: the eigenvalues
      // ≤ zero_tol of the unit-diagonal K̃ = D^{-1/2} K D^{-1/2} (values only, O(n³) like C's).
      const VectorX inv_sqrt_d = RigidScaling(K.diagonal()).cwiseSqrt().cwiseInverse();
      const MatrixX k_scaled = inv_sqrt_d.asDiagonal() * K * inv_sqrt_d.asDiagonal();
      const Eigen::SelfAdjointEigenSolver<MatrixX> scaled(k_scaled, Eigen::EigenvaluesOnly);
      if (scaled.info() != Eigen::Success) {
        summary.status = Status::kNotConverged;
        summary.message = "the tridiagonal QR iteration of D^{-1/2}KD^{-1/2} did not converge";
        summary.wall_time_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return result;
      }
      rigid_count =
          static_cast<int>((scaled.eigenvalues().array().abs() <= options.zero_tol).count());
    }
    internal::FinalizeEigenpairs(eigen.eigenvalues(), std::move(vectors), MatrixX(), K.diagonal(),
                                 rigid_count, options.zero_tol, "the dense symmetric eigensolver",
                                 &result, [&K](const VectorX& phi) { return phi.dot(K * phi); });
  }
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn
