#include "numerics/symmetric_eigen_internal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <vector>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/rigid_modes.hpp"

namespace geardyn::internal {
namespace {

void CheckShapes(Eigen::Index k_rows, Eigen::Index k_cols, Eigen::Index m_rows,
                 Eigen::Index m_cols) {
  GEARDYN_THROW_UNLESS(k_rows == k_cols, "K: must be square, got " << k_rows << " × " << k_cols);
  GEARDYN_THROW_UNLESS(m_rows == m_cols, "M: must be square, got " << m_rows << " × " << m_cols);
  GEARDYN_CHECK_SIZE(m_rows, k_rows, "M (rows, must match K)");
  GEARDYN_THROW_UNLESS(k_rows >= 1, "K: must not be empty");
}

void CheckSymmetry(double asymmetry, double magnitude, const char* name) {
  GEARDYN_THROW_UNLESS(asymmetry <= kSymmetryTol * magnitude,
                       name << ": not symmetric, max|" << name << " − " << name
                            << "ᵀ| = " << asymmetry << " > " << kSymmetryTol << "·max|" << name
                            << "| = " << kSymmetryTol * magnitude);
}

void CheckMassDiagonal(const VectorX& M_diagonal) {
  for (Eigen::Index i = 0; i < M_diagonal.size(); ++i) {
    GEARDYN_THROW_UNLESS(M_diagonal(i) > 0.0, "M: not positive definite, diagonal entry M("
                                                  << i << ", " << i << ") = " << M_diagonal(i)
                                                  << " ≤ 0");
  }
}

void CheckSparseMatrix(const SparseMatrix& A, const char* name) {
  const SparseMatrix At = A.transpose();
  const SparseMatrix difference = A - At;
  double magnitude = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      GEARDYN_THROW_UNLESS(std::isfinite(it.value()), name << ": non-finite entry (" << it.row()
                                                           << ", " << it.col()
                                                           << ") = " << it.value());
      magnitude = std::max(magnitude, std::abs(it.value()));
    }
  }
  double asymmetry = 0.0;
  for (Eigen::Index j = 0; j < difference.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(difference, j); it; ++it) {
      asymmetry = std::max(asymmetry, std::abs(it.value()));
    }
  }
  CheckSymmetry(asymmetry, magnitude, name);
}

void CheckDenseMatrix(const MatrixX& A, const char* name) {
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      GEARDYN_THROW_UNLESS(std::isfinite(A(i, j)),
                           name << ": non-finite entry (" << i << ", " << j << ") = " << A(i, j));
    }
  }
  CheckSymmetry((A - A.transpose()).cwiseAbs().maxCoeff(), A.cwiseAbs().maxCoeff(), name);
}

}  // namespace

void CheckPencil(const MatrixX& K, const MatrixX& M) {
  CheckShapes(K.rows(), K.cols(), M.rows(), M.cols());
  CheckDenseMatrix(K, "K");
  CheckDenseMatrix(M, "M");
  CheckMassDiagonal(M.diagonal());
}

void CheckPencil(const SparseMatrix& K, const SparseMatrix& M) {
  CheckShapes(K.rows(), K.cols(), M.rows(), M.cols());
  CheckSparseMatrix(K, "K");
  CheckSparseMatrix(M, "M");
  CheckMassDiagonal(VectorX(M.diagonal()));
}

void CheckOptions(const GeneralizedEigenOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
}

double SpectrumScale(const VectorX& K_diagonal, const VectorX& M_diagonal) {
  double scale = 0.0;
  for (Eigen::Index i = 0; i < K_diagonal.size(); ++i) {
    scale = std::max(scale, std::abs(K_diagonal(i)) / M_diagonal(i));
  }
  return scale > 0.0 && std::isfinite(scale) ? scale : 1.0;
}

void FinalizeEigenpairs(VectorX values, MatrixX vectors, const MatrixX& M_vectors,
                        const VectorX& K_diagonal, int rigid_count, double zero_tol,
                        const std::string& step, GeneralizedEigenResult* result,
                        const std::function<double(const VectorX&)>& quadratic_form) {
  Summary& summary = result->summary;
  if (!values.allFinite() || !vectors.allFinite()) {
    summary.status = Status::kNumericalIssue;
    summary.message = "non-finite eigenvalue or eigenvector from " + step;
    result->eigenvalues.resize(0);
    result->vectors.resize(0, 0);
    result->num_rigid_body_modes = 0;
    return;
  }
  const Eigen::Index m = values.size();
  const bool have_vectors = vectors.cols() == m && m > 0;
  GEARDYN_DEMAND(have_vectors || rigid_count >= 0 || m == 0);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(m));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(),
                   [&values](Eigen::Index a, Eigen::Index b) { return values(a) < values(b); });

  // M-normalize and fix the sign of every vector (in the sorted order).
  MatrixX sorted(have_vectors ? vectors.rows() : 0, have_vectors ? m : 0);
  for (Eigen::Index k = 0; k < sorted.cols(); ++k) {
    const Eigen::Index source = order[static_cast<std::size_t>(k)];
    double factor = 1.0;
    if (M_vectors.size() > 0) {
      const double m_norm_squared = vectors.col(source).dot(M_vectors.col(source));
      if (m_norm_squared > 0.0) factor = 1.0 / std::sqrt(m_norm_squared);
    }
    Eigen::Index largest = 0;
    vectors.col(source).cwiseAbs().maxCoeff(&largest);
    const double sign = vectors(largest, source) < 0.0 ? -1.0 : 1.0;
    sorted.col(k) = (sign * factor) * vectors.col(source);
  }

  // The one rigid-body criterion (rigid_modes.hpp). With vectors, per pair: φᵀMφ = 1 and
  // φᵀK̄φ = λ, rigid when |λ| ≤ zero_tol·φᵀDφ, not PSD below −zero_tol·φᵀDφ. Without them, the
  // caller counted the eigenvalues ≤ zero_tol of the unit-diagonal K̃ (the same criterion on the
  // null space): the rigid_count smallest |λ| are the rigid ones, and "not PSD" falls back to
  // −zero_tol·s.
  const VectorX scaling = RigidScaling(K_diagonal);
  std::vector<char> rigid(static_cast<std::size_t>(m), 0);
  if (!have_vectors && m > 0) {
    std::vector<Eigen::Index> by_magnitude(static_cast<std::size_t>(m));
    std::iota(by_magnitude.begin(), by_magnitude.end(), Eigen::Index{0});
    std::stable_sort(by_magnitude.begin(), by_magnitude.end(), [&](Eigen::Index a, Eigen::Index b) {
      return std::abs(values(order[static_cast<std::size_t>(a)])) <
             std::abs(values(order[static_cast<std::size_t>(b)]));
    });
    for (int i = 0; i < std::min<Eigen::Index>(rigid_count, m); ++i) {
      rigid[static_cast<std::size_t>(by_magnitude[static_cast<std::size_t>(i)])] = 1;
    }
  }
  result->eigenvalues.resize(m);
  result->num_rigid_body_modes = 0;
  double most_negative = 0.0, negative_bound = 0.0;
  // Round-off of the eigensolver's λ (absolute, ~ n·ε·λ_max): below it, λ says nothing about
  // φᵀKφ, so the criterion is applied to the Rayleigh quotient (header).
  const double lambda_roundoff =
      100.0 * static_cast<double>(std::max<Eigen::Index>(sorted.rows(), 1)) *
      std::numeric_limits<double>::epsilon() *
      std::max(result->spectrum_scale, m > 0 ? values.cwiseAbs().maxCoeff() : 0.0);
  for (Eigen::Index k = 0; k < m; ++k) {
    double lambda = values(order[static_cast<std::size_t>(k)]);
    bool is_rigid = have_vectors ? IsRigidBodyPattern(lambda, scaling, sorted.col(k), zero_tol)
                                 : rigid[static_cast<std::size_t>(k)] != 0;
    // A λ within round-off of zero is judged by φᵀKφ: rigid if that passes the criterion, and
    // not evidence of an indefinite K unless φᵀKφ is negative beyond the bound too.
    bool negative_is_roundoff = false;
    if (have_vectors && !is_rigid && quadratic_form && std::abs(lambda) <= lambda_roundoff) {
      const VectorX phi = sorted.col(k);
      const double q = quadratic_form(phi);
      if (std::isfinite(q) && IsRigidBodyPattern(q, scaling, phi, zero_tol)) is_rigid = true;
      negative_is_roundoff =
          std::isfinite(q) && q >= -zero_tol * phi.dot(scaling.cwiseProduct(phi));
    }
    const double bound = have_vectors
                             ? zero_tol * sorted.col(k).dot(scaling.cwiseProduct(sorted.col(k)))
                             : zero_tol * result->spectrum_scale;
    if (is_rigid) {
      lambda = 0.0;
      ++result->num_rigid_body_modes;
    } else if (lambda < -bound && lambda < most_negative && !negative_is_roundoff) {
      most_negative = lambda;
      negative_bound = bound;
    }
    result->eigenvalues(k) = lambda;
  }
  result->vectors = std::move(sorted);

  if (result->num_rigid_body_modes > 0) {
    std::ostringstream out;
    out << result->num_rigid_body_modes
        << " rigid-body mode(s): zero frequency (|φᵀK̄φ| ≤ zero_tol·φᵀ diag(K̄) φ, zero_tol = "
        << zero_tol << ")";
    summary.warnings.push_back(out.str());
  }
  if (most_negative < 0.0) {
    std::ostringstream out;
    out << "K is not positive semidefinite: eigenvalue λ = " << most_negative << " < −"
        << negative_bound << " (zero_tol times φᵀ diag(K) φ, or times s without "
        << "vectors; from " << step << ")";
    if (summary.status == Status::kSuccess) {
      summary.status = Status::kNumericalIssue;
      summary.message = out.str();
    } else {
      summary.warnings.push_back(out.str());
    }
  }
}

}  // namespace geardyn::internal
