// SolveGeneralizedEigenDenseSubset: Cholesky of M, Householder tridiagonalization of L⁻¹KL⁻ᵀ
// (Eigen) and LAPACK dstemr for the wanted index range (symmetric_eigen_subset.hpp).
#include "geardyn/numerics/symmetric_eigen_subset.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/common/check.hpp"
#include "numerics/lapack_fortran.hpp"
#include "numerics/symmetric_eigen_internal.hpp"

namespace geardyn {
namespace {

// First index (0-based) of the `count` consecutive sorted values nearest sigma: slide the
// window right while the value entering is nearer σ than the one leaving.
Eigen::Index NearestWindow(const VectorX& sorted, int count, double sigma) {
  Eigen::Index first = 0;
  while (first + count < sorted.size() &&
         std::abs(sorted(first + count) - sigma) < std::abs(sorted(first) - sigma)) {
    ++first;
  }
  return first;
}

}  // namespace

GeneralizedEigenResult SolveGeneralizedEigenDenseSubset(const MatrixX& K, const MatrixX& M,
                                                        int count, std::optional<double> sigma,
                                                        const GeneralizedEigenOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  internal::CheckOptions(options);
  internal::CheckPencil(K, M);
  const int n = static_cast<int>(K.rows());
  GEARDYN_THROW_UNLESS(count >= 1 && count <= n,
                       "count: must be in [1, n = " << n << "], got " << count);
  GEARDYN_THROW_UNLESS(!sigma.has_value() || std::isfinite(*sigma),
                       "sigma: must be finite, got " << *sigma);

  GeneralizedEigenResult result;
  result.spectrum_scale = internal::SpectrumScale(K.diagonal(), M.diagonal());
  Summary& summary = result.summary;
  summary.counters["subset_solver"] = 1;
  summary.counters["factorizations"] = 1;
  summary.counters["iterations"] = 0;
  summary.counters["operator_applications"] = 0;
  summary.counters["mass_applications"] = 0;
  const auto finish = [&]() -> GeneralizedEigenResult {
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(result);
  };

  // M = L Lᵀ; C = L⁻¹ K L⁻ᵀ (Golub & Van Loan, Matrix Computations, 4th ed., §8.7.2).
  const Eigen::LLT<MatrixX> cholesky(M);
  GEARDYN_THROW_UNLESS(cholesky.info() == Eigen::Success,
                       "M: not positive definite (its Cholesky factorization failed)");
  MatrixX C = K;
  cholesky.matrixL().solveInPlace<Eigen::OnTheLeft>(C);
  cholesky.matrixU().solveInPlace<Eigen::OnTheRight>(C);
  // C = Q T Qᵀ; T's diagonal d and subdiagonal e (dstemr overwrites both; e has n entries).
  const Eigen::Tridiagonalization<MatrixX> tridiagonal(C);
  VectorX d = tridiagonal.diagonal();
  VectorX e = VectorX::Zero(n);
  e.head(n - 1) = tridiagonal.subDiagonal();

  // Index range il…iu (1-based) of the wanted eigenvalues of T.
  int il = 1;
  if (sigma.has_value() && count < n) {
    Eigen::SelfAdjointEigenSolver<MatrixX> values;
    values.computeFromTridiagonal(d, e.head(n - 1), Eigen::EigenvaluesOnly);
    if (values.info() != Eigen::Success) {
      summary.status = Status::kNotConverged;
      summary.message = "the tridiagonal QR iteration (eigenvalues of T) did not converge";
      return finish();
    }
    il = static_cast<int>(NearestWindow(values.eigenvalues(), count, *sigma)) + 1;
  }
  const int iu = il + count - 1;

  // dstemr: JOBZ = 'V', RANGE = 'I'; workspace query first (lwork = liwork = −1).
  const char jobz = 'V', range = 'I';
  const double vl = 0.0, vu = 0.0;
  int found = 0, info = 0, tryrac = 1;
  VectorX w(n);
  MatrixX z(n, count);
  std::vector<int> isuppz(static_cast<std::size_t>(2 * count));
  const int ldz = n, nzc = count;
  double work_query = 0.0;
  int iwork_query = 0;
  const int query = -1;
  dstemr_(&jobz, &range, &n, d.data(), e.data(), &vl, &vu, &il, &iu, &found, w.data(), z.data(),
          &ldz, &nzc, isuppz.data(), &tryrac, &work_query, &query, &iwork_query, &query, &info, 1,
          1);
  if (info == 0) {
    const int lwork = std::max(static_cast<int>(work_query), 18 * n);
    const int liwork = std::max(iwork_query, 10 * n);
    std::vector<double> work(static_cast<std::size_t>(lwork));
    std::vector<int> iwork(static_cast<std::size_t>(liwork));
    dstemr_(&jobz, &range, &n, d.data(), e.data(), &vl, &vu, &il, &iu, &found, w.data(), z.data(),
            &ldz, &nzc, isuppz.data(), &tryrac, work.data(), &lwork, iwork.data(), &liwork, &info,
            1, 1);
  }
  summary.counters["dstemr_info"] = info;
  if (info != 0 || found != count) {
    summary.status = Status::kNotConverged;
    summary.message = "LAPACK dstemr (eigenpairs " + std::to_string(il) + "…" + std::to_string(iu) +
                      " of the tridiagonal T) failed: info " + std::to_string(info) + ", " +
                      std::to_string(found) + " of " + std::to_string(count) + " found";
    return finish();
  }

  // y = Q z (the Householder reflectors applied to the count columns), φ = L⁻ᵀ y: M-orthonormal
  // because the z are orthonormal.
  MatrixX vectors = tridiagonal.matrixQ() * z;
  cholesky.matrixU().solveInPlace(vectors);
  internal::FinalizeEigenpairs(w.head(count), std::move(vectors), MatrixX(), K.diagonal(),
                               /*rigid_count=*/-1, options.zero_tol,
                               "the dense subset eigensolver (dstemr)", &result,
                               [&K](const VectorX& phi) { return phi.dot(K * phi); });
  return finish();
}

}  // namespace geardyn
