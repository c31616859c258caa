#include "numerics/symmetric_eigen_internal.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <vector>

#include "geardyn/common/check.hpp"

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

void FinalizeEigenpairs(VectorX values, MatrixX vectors, const MatrixX& M_vectors, double zero_tol,
                        const std::string& step, GeneralizedEigenResult* result) {
  Summary& summary = result->summary;
  const bool want_vectors = vectors.size() > 0;
  if (!values.allFinite() || (want_vectors && !vectors.allFinite())) {
    summary.status = Status::kNumericalIssue;
    summary.message = "non-finite eigenvalue or eigenvector from " + step;
    result->eigenvalues.resize(0);
    result->vectors.resize(0, 0);
    result->num_rigid_body_modes = 0;
    return;
  }
  const Eigen::Index m = values.size();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(m));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(),
                   [&values](Eigen::Index a, Eigen::Index b) { return values(a) < values(b); });

  const double zero_bound = zero_tol * result->spectrum_scale;
  result->eigenvalues.resize(m);
  result->num_rigid_body_modes = 0;
  double most_negative = 0.0;
  for (Eigen::Index k = 0; k < m; ++k) {
    double lambda = values(order[static_cast<std::size_t>(k)]);
    if (std::abs(lambda) <= zero_bound) {
      lambda = 0.0;
      ++result->num_rigid_body_modes;
    } else if (lambda < 0.0) {
      most_negative = std::min(most_negative, lambda);
    }
    result->eigenvalues(k) = lambda;
  }

  if (want_vectors) {
    result->vectors.resize(vectors.rows(), m);
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index source = order[static_cast<std::size_t>(k)];
      double factor = 1.0;
      if (M_vectors.size() > 0) {
        const double m_norm_squared = vectors.col(source).dot(M_vectors.col(source));
        if (m_norm_squared > 0.0) factor = 1.0 / std::sqrt(m_norm_squared);
      }
      Eigen::Index largest = 0;
      vectors.col(source).cwiseAbs().maxCoeff(&largest);
      const double sign = vectors(largest, source) < 0.0 ? -1.0 : 1.0;
      result->vectors.col(k) = (sign * factor) * vectors.col(source);
    }
  } else {
    result->vectors.resize(0, 0);
  }

  if (result->num_rigid_body_modes > 0) {
    std::ostringstream out;
    out << result->num_rigid_body_modes
        << " rigid-body mode(s): zero frequency (|λ| ≤ zero_tol·s = " << zero_bound << ")";
    summary.warnings.push_back(out.str());
  }
  if (most_negative < 0.0) {
    std::ostringstream out;
    out << "K is not positive semidefinite: eigenvalue λ = " << most_negative
        << " < −zero_tol·s = " << -zero_bound << " (from " << step << ")";
    if (summary.status == Status::kSuccess) {
      summary.status = Status::kNumericalIssue;
      summary.message = out.str();
    } else {
      summary.warnings.push_back(out.str());
    }
  }
}

}  // namespace geardyn::internal
