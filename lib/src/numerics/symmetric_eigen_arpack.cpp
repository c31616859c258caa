// SolveGeneralizedEigenArpack: ARPACK dsaupd/dseupd in shift-invert mode (mode 3, bmat = 'G') on
// OP = (K − σM)⁻¹ M with the M-inner product (ARPACK Users' Guide §3.2.2 and §4.2, "dsdrv4").
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/linear_operator.hpp"
#include "geardyn/numerics/symmetric_eigen.hpp"
#include "numerics/symmetric_eigen_internal.hpp"

#if defined(GEARDYN_WITH_ARPACK)
#include "numerics/arpack_fortran.hpp"
#include "numerics/pseudo_random.hpp"
#endif

namespace geardyn {

#if defined(GEARDYN_WITH_ARPACK)
std::mutex& internal::ArpackMutex() {
  static std::mutex mutex;
  return mutex;
}
#endif

namespace {

#if defined(GEARDYN_WITH_ARPACK)

constexpr std::uint64_t kStartVectorSeed = 0x41525041434BULL;

/// Text of dsaupd's negative info codes (dsaupd.f header).
const char* DsaupdErrorText(int info) {
  switch (info) {
    case -1:
      return "N must be positive";
    case -2:
      return "NEV must be positive";
    case -3:
      return "NCV must satisfy NEV < NCV <= N";
    case -4:
      return "the maximum number of iterations must be positive";
    case -5:
      return "WHICH must be one of LM, SM, LA, SA or BE";
    case -6:
      return "BMAT must be I or G";
    case -7:
      return "LWORKL is too small";
    case -8:
      return "error from the LAPACK tridiagonal eigenvalue calculation";
    case -9:
      return "the starting vector is zero";
    case -10:
      return "IPARAM(7) must be 1, 2, 3, 4 or 5";
    case -11:
      return "IPARAM(7) = 1 and BMAT = G are incompatible";
    case -12:
      return "IPARAM(1) must be 0 or 1";
    case -13:
      return "NEV and WHICH = BE are incompatible";
    case -9999:
      return "could not build a Lanczos factorization";
    default:
      return "unknown error";
  }
}

/// Text of dseupd's negative info codes (dseupd.f header).
const char* DseupdErrorText(int info) {
  switch (info) {
    case -8:
      return "error from the LAPACK tridiagonal eigenvalue calculation";
    case -9:
      return "the starting vector is zero";
    case -14:
      return "dsaupd did not find any eigenvalues to sufficient accuracy";
    case -17:
      return "dseupd counted a different number of converged Ritz values than dsaupd";
    default:
      return DsaupdErrorText(info);
  }
}

/// What one run of the reverse-communication loop produced.
struct LanczosOutcome {
  int saupd_info = 0;
  int seupd_info = 0;
  int num_converged = 0;
  int iterations = 0;
  long operator_applications = 0;
  long mass_applications = 0;
  VectorX values;   // (num_converged) λ, unsorted
  MatrixX vectors;  // (n × num_converged) or empty
};

/// dsaupd/dseupd in mode 3 with B = M: OP x = (K − σM)⁻¹ M x, which = "LM" (λ nearest σ).
template <ShiftSolveOperator Op, LinearOperator MassOp>
LanczosOutcome RunShiftInvertLanczos(const Op& op, const MassOp& mass, int nev, int ncv, double tol,
                                     int max_iterations, bool want_vectors) {
  const std::lock_guard<std::mutex> lock(internal::ArpackMutex());
  LanczosOutcome outcome;
  const int n = static_cast<int>(op.rows());
  const char bmat = 'G';
  const char which[2] = {'L', 'M'};
  VectorX resid(n);  // a fixed start vector: results are reproducible run to run
  internal::FillPseudoRandom(kStartVectorSeed, &resid);
  MatrixX v(n, ncv);
  const int ldv = n;
  VectorX workd(3 * static_cast<Eigen::Index>(n));
  const int lworkl = ncv * (ncv + 8);
  VectorX workl(lworkl);
  std::array<int, 11> iparam{};
  iparam[0] = 1;               // exact shifts
  iparam[2] = max_iterations;  // maxit
  iparam[3] = 1;               // block size
  iparam[6] = 3;               // mode 3: shift-invert, OP = (K − σM)⁻¹ M, B = M
  std::array<int, 11> ipntr{};
  int ido = 0;
  int info = 1;  // use resid as the start vector
  const auto at = [&workd](int pointer) { return workd.data() + (pointer - 1); };

  while (true) {
    dsaupd_(&ido, &bmat, &n, which, &nev, &tol, resid.data(), &ncv, v.data(), &ldv, iparam.data(),
            ipntr.data(), workd.data(), workl.data(), &lworkl, &info, 1, 2);
    if (ido == -1) {  // y = OP x (initialization: M x is not available)
      op.Apply(Eigen::Map<const VectorX>(at(ipntr[0]), n), Eigen::Map<VectorX>(at(ipntr[1]), n));
      ++outcome.operator_applications;
      ++outcome.mass_applications;
    } else if (ido == 1) {  // y = OP x with M x already at ipntr[2]
      op.Solve(Eigen::Map<const VectorX>(at(ipntr[2]), n), Eigen::Map<VectorX>(at(ipntr[1]), n));
      ++outcome.operator_applications;
    } else if (ido == 2) {  // y = M x
      mass.Apply(Eigen::Map<const VectorX>(at(ipntr[0]), n), Eigen::Map<VectorX>(at(ipntr[1]), n));
      ++outcome.mass_applications;
    } else {
      GEARDYN_DEMAND(ido == 99);
      break;
    }
  }
  outcome.saupd_info = info;
  outcome.iterations = iparam[2];
  outcome.num_converged = std::min(iparam[4], nev);
  if (info < 0 || outcome.num_converged <= 0) {
    outcome.num_converged = std::max(outcome.num_converged, 0);
    return outcome;
  }

  const int rvec = want_vectors ? 1 : 0;
  const char howmny = 'A';
  std::vector<int> select(static_cast<std::size_t>(ncv), 0);
  VectorX d(nev);
  MatrixX z(n, nev);
  const int ldz = n;
  const double sigma = op.sigma();
  int seupd_info = 0;
  dseupd_(&rvec, &howmny, select.data(), d.data(), z.data(), &ldz, &sigma, &bmat, &n, which, &nev,
          &tol, resid.data(), &ncv, v.data(), &ldv, iparam.data(), ipntr.data(), workd.data(),
          workl.data(), &lworkl, &seupd_info, 1, 1, 2);
  outcome.seupd_info = seupd_info;
  if (seupd_info != 0) {
    outcome.num_converged = 0;
    return outcome;
  }
  outcome.values = d.head(outcome.num_converged);
  if (want_vectors) outcome.vectors = z.leftCols(outcome.num_converged);
  return outcome;
}

/// Number of eigenvalues of the pencil (K, M) below τ, M positive definite: the negative pivots of
/// the LDLᵀ factorization of K − τM (Sylvester's law of inertia; Parlett, The Symmetric Eigenvalue
/// Problem, 1998, §3.3). −1 when the factorization fails (a zero or non-finite pivot: τ on an
/// eigenvalue).
long CountEigenvaluesBelow(const SparseMatrix& K, const SparseMatrix& M, double tau) {
  const SparseMatrix shifted = K - tau * M;
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(shifted);
  if (ldlt.info() != Eigen::Success) return -1;
  const VectorX d = ldlt.vectorD();
  if (!d.allFinite() || (d.array() == 0.0).any()) return -1;
  return static_cast<long>((d.array() < 0.0).count());
}

/// Number of eigenvalues of (K, M) with |λ − σ| < r, from two inertia counts; −1 when a
/// factorization failed twice (τ nudged by 1e-7 between the tries).
long CountEigenvaluesInWindow(const SparseMatrix& K, const SparseMatrix& M, double sigma,
                              double radius) {
  long above = CountEigenvaluesBelow(K, M, sigma + radius);
  if (above < 0) above = CountEigenvaluesBelow(K, M, sigma + radius * (1.0 - 1e-7));
  long below = CountEigenvaluesBelow(K, M, sigma - radius);
  if (below < 0) below = CountEigenvaluesBelow(K, M, sigma - radius * (1.0 - 1e-7));
  if (above < 0 || below < 0) return -1;
  return above - below;
}

/// Lanczos from one start vector sees one direction per eigenspace, so ARPACK can return a
/// repeated eigenvalue once and the next eigenvalue in its place, with info = 0. The returned set
/// is the "nearest σ" set |λ − σ| ≤ r; every eigenvalue of the pencil strictly inside it, at
/// |λ − σ| < r(1 − δ), must have been returned. This compares the inertia count of that window
/// with the returned values in it (counter "inertia_count") and sets status kNumericalIssue when
/// the pencil has more (counter "missed_eigenvalues"). The band r(1 − δ) … r holds the values
/// that tie with the farthest one returned: keeping some copies of a repeated eigenvalue at the
/// edge is a legitimate truncation, not a miss. Successful results only.
void CheckNoEigenvalueMissed(const SparseMatrix& K, const SparseMatrix& M, double tol,
                             GeneralizedEigenResult* result) {
  Summary& summary = result->summary;
  const VectorX& values = result->eigenvalues;
  if (summary.status != Status::kSuccess || values.size() == 0) return;
  const VectorX distance = (values.array() - result->sigma).abs();
  // ARPACK's Ritz values are accurate to about tol·|λ| (tol = 0: machine precision).
  const double margin = std::max(1e-6, 100.0 * tol);
  const double inner = distance.maxCoeff() * (1.0 - margin);
  const long returned = static_cast<long>((distance.array() < inner).count());
  const long count = CountEigenvaluesInWindow(K, M, result->sigma, inner);
  summary.counters["inertia_count"] = count;
  if (count < 0) {
    summary.warnings.push_back(
        "ARPACK: the inertia check of the returned modes could not factorize K − τM; the "
        "modes are not checked for a missed repeated eigenvalue");
    return;
  }
  if (count > returned) {
    std::ostringstream out;
    out << "ARPACK returned " << returned << " eigenvalues with |λ − σ| < " << inner
        << " rad²/s² (σ = " << result->sigma << "), but the pencil has " << count
        << " there (Sylvester inertia of K − τM): Lanczos missed " << count - returned
        << " repeated or clustered eigenvalue(s); use the dense solver";
    summary.status = Status::kNumericalIssue;
    summary.message = out.str();
    summary.counters["missed_eigenvalues"] = count - returned;
  }
}

#endif  // GEARDYN_WITH_ARPACK

}  // namespace

GeneralizedEigenResult SolveGeneralizedEigenArpack(const SparseMatrix& K, const SparseMatrix& M,
                                                   int num_modes, std::optional<double> sigma,
                                                   const GeneralizedEigenOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  internal::CheckOptions(options);
  internal::CheckPencil(K, M);
  const Eigen::Index n = K.rows();
  GEARDYN_THROW_UNLESS(num_modes >= 1 && num_modes < n, "num_modes: must be in [1, n − 1] = [1, "
                                                            << n - 1 << "], got " << num_modes);
  const int ncv =
      options.num_lanczos_vectors > 0
          ? options.num_lanczos_vectors
          : static_cast<int>(std::min<Eigen::Index>(n, std::max(2 * num_modes + 1, 20)));
  GEARDYN_THROW_UNLESS(ncv > num_modes && ncv <= n,
                       "GeneralizedEigenOptions.num_lanczos_vectors: must be in (num_modes, n] = ("
                           << num_modes << ", " << n << "], got " << ncv);
  GEARDYN_THROW_UNLESS(!sigma.has_value() || std::isfinite(*sigma),
                       "sigma: must be finite, got " << sigma.value_or(0.0));
  // M positive definite: the M-inner product of mode 3 needs it.
  const Eigen::SimplicialLLT<SparseMatrix> mass_cholesky(M);
  GEARDYN_THROW_UNLESS(mass_cholesky.info() == Eigen::Success,
                       "M: not positive definite (its sparse Cholesky factorization failed)");

  GeneralizedEigenResult result;
  Summary& summary = result.summary;
  result.spectrum_scale = internal::SpectrumScale(VectorX(K.diagonal()), VectorX(M.diagonal()));
  result.sigma = sigma.value_or(-kDefaultShiftFraction * result.spectrum_scale);
  summary.counters["factorizations"] = 1;
  summary.counters["iterations"] = 0;
  summary.counters["operator_applications"] = 0;
  summary.counters["mass_applications"] = 0;
  summary.counters["converged"] = 0;

#if !defined(GEARDYN_WITH_ARPACK)
  summary.status = Status::kNumericalIssue;
  summary.message = "ARPACK unavailable (built with GEARDYN_WITH_ARPACK=OFF)";
#else
  const SparseShiftSolveOperator op(K, M, result.sigma, options.factorization);
  summary.counters["factorizations"] += op.factorization().num_factorizations;
  if (!op.ok()) {
    summary.status = Status::kNumericalIssue;
    summary.message = op.factorization().message;
  } else {
    const SparseMatrixOperator mass(M);
    // Ritz vectors always: the rigid-body criterion (rigid_modes.hpp) reads φᵀ diag(K) φ.
    LanczosOutcome run = RunShiftInvertLanczos(op, mass, num_modes, ncv, options.tol,
                                               options.max_iterations, /*want_vectors=*/true);
    summary.counters["iterations"] = run.iterations;
    summary.counters["operator_applications"] = run.operator_applications;
    summary.counters["mass_applications"] = run.mass_applications;
    summary.counters["converged"] = run.num_converged;
    summary.counters["arpack_info"] = run.saupd_info;
    std::ostringstream out;
    if (run.saupd_info < 0) {
      summary.status = Status::kNumericalIssue;
      out << "ARPACK dsaupd error info = " << run.saupd_info << ": "
          << DsaupdErrorText(run.saupd_info);
    } else if (run.seupd_info != 0) {
      summary.status = Status::kNumericalIssue;
      out << "ARPACK dseupd error info = " << run.seupd_info << ": "
          << DseupdErrorText(run.seupd_info);
    } else if (run.saupd_info == 1) {
      summary.status = Status::kNotConverged;
      out << "ARPACK dsaupd reached max_iterations = " << options.max_iterations << " with "
          << run.num_converged << " of " << num_modes << " modes converged (info = 1)";
    } else if (run.saupd_info == 3) {
      summary.status = Status::kNotConverged;
      out << "ARPACK dsaupd could not apply shifts during a restart (info = 3); "
          << run.num_converged << " of " << num_modes
          << " modes converged; increase num_lanczos_vectors (ncv = " << ncv << ")";
    } else if (run.saupd_info != 0) {
      summary.status = Status::kNotConverged;
      out << "ARPACK dsaupd returned info = " << run.saupd_info << " with " << run.num_converged
          << " of " << num_modes << " modes converged";
    }
    summary.message = out.str();

    if (run.vectors.cols() != run.values.size()) run.vectors.setZero(n, run.values.size());
    const MatrixX M_vectors = M * run.vectors;
    internal::FinalizeEigenpairs(std::move(run.values), std::move(run.vectors), M_vectors,
                                 VectorX(K.diagonal()), /*rigid_count=*/-1, options.zero_tol,
                                 "ARPACK shift-invert Lanczos", &result,
                                 [&K](const VectorX& phi) { return phi.dot(K * phi); });
    if (!options.compute_vectors) result.vectors.resize(0, 0);
    CheckNoEigenvalueMissed(K, M, options.tol, &result);
    // An indefinite K − σM at σ < 0 means the pencil has an eigenvalue below σ: K is not PSD,
    // even if that eigenvalue is not among the ones nearest σ.
    if (result.sigma < 0.0 && options.factorization != ShiftFactorization::kLu &&
        !op.factorization().positive_definite && summary.status == Status::kSuccess) {
      std::ostringstream why;
      why << "K is not positive semidefinite: K − σM is indefinite at sigma = " << result.sigma
          << " < 0, so (K, M) has an eigenvalue below σ";
      summary.status = Status::kNumericalIssue;
      summary.message = why.str();
    }
  }
#endif
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn
