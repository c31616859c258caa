#include "geardyn/numerics/linear_operator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "geardyn/common/check.hpp"
#include "numerics/pseudo_random.hpp"

namespace geardyn {
namespace {

constexpr std::uint64_t kConditionSeed = 0x6765617264796EULL;

/// Checks K and M square and of the same size, σ finite (the constructors' user input).
template <class Matrix>
void CheckShiftInputs(const Matrix& K, const Matrix& M, double sigma) {
  GEARDYN_THROW_UNLESS(K.rows() == K.cols(),
                       "K: must be square, got " << K.rows() << " × " << K.cols());
  GEARDYN_THROW_UNLESS(M.rows() == M.cols(),
                       "M: must be square, got " << M.rows() << " × " << M.cols());
  GEARDYN_CHECK_SIZE(M.rows(), K.rows(), "M (rows, must match K)");
  GEARDYN_THROW_UNLESS(std::isfinite(sigma), "sigma: must be finite, got " << sigma);
}

/// Lower-bound estimate of cond₁(A) = ‖A‖₁‖A⁻¹‖₁ from two steps of inverse iteration started
/// from a fixed pseudo-random vector; +∞ when a solve returns non-finite values.
template <class SolveFn>
double EstimateCondition(double norm1, Eigen::Index n, const SolveFn& solve) {
  VectorX b(n);
  internal::FillPseudoRandom(kConditionSeed, &b);
  VectorX x1(n);
  solve(b, x1);
  if (!x1.allFinite()) return std::numeric_limits<double>::infinity();
  const double x1_norm = x1.lpNorm<1>();
  double inverse_norm = x1_norm / b.lpNorm<1>();
  if (x1_norm > 0.0) {
    const VectorX v = x1 / x1_norm;
    VectorX x2(n);
    solve(v, x2);
    if (!x2.allFinite()) return std::numeric_limits<double>::infinity();
    inverse_norm = std::max(inverse_norm, x2.lpNorm<1>());
  }
  return norm1 * inverse_norm;
}

/// Fills report->condition_estimate, ok and message after a successful factorization.
template <class SolveFn>
void FinishReport(double norm1, Eigen::Index n, double sigma, const SolveFn& solve,
                  ShiftFactorizationReport* report) {
  report->condition_estimate = EstimateCondition(norm1, n, solve);
  if (std::isfinite(report->condition_estimate) &&
      report->condition_estimate <= kSingularShiftCondition) {
    report->ok = true;
    return;
  }
  std::ostringstream out;
  out << "K − σM is numerically singular at sigma = " << sigma << ": condition estimate "
      << report->condition_estimate << " > " << kSingularShiftCondition
      << " (σ is an eigenvalue of (K, M) to working precision; move the shift)";
  report->ok = false;
  report->message = out.str();
}

void ReportFailedFactorization(const char* what, double sigma, const std::string& detail,
                               ShiftFactorizationReport* report) {
  std::ostringstream out;
  out << what << " of K − σM failed at sigma = " << sigma;
  if (!detail.empty()) out << " (" << detail << ")";
  out << ": K − σM is singular (σ is an eigenvalue of (K, M); move the shift)";
  report->ok = false;
  report->message = out.str();
}

}  // namespace

const char* ShiftFactorizationName(ShiftFactorization factorization) {
  switch (factorization) {
    case ShiftFactorization::kAuto:
      return "auto";
    case ShiftFactorization::kLdlt:
      return "ldlt";
    case ShiftFactorization::kLu:
      return "lu";
  }
  return "unknown";
}

// ------------------------------------------------------------------------ matrix operators

DenseMatrixOperator::DenseMatrixOperator(const MatrixX& A) : A_(&A) {
  GEARDYN_THROW_UNLESS(A.rows() == A.cols(),
                       "A: must be square, got " << A.rows() << " × " << A.cols());
}

void DenseMatrixOperator::Apply(const Eigen::Ref<const VectorX>& x, Eigen::Ref<VectorX> y) const {
  GEARDYN_ASSERT(x.size() == A_->cols() && y.size() == A_->rows());
  y.noalias() = (*A_) * x;
}

SparseMatrixOperator::SparseMatrixOperator(const SparseMatrix& A) : A_(&A) {
  GEARDYN_THROW_UNLESS(A.rows() == A.cols(),
                       "A: must be square, got " << A.rows() << " × " << A.cols());
}

void SparseMatrixOperator::Apply(const Eigen::Ref<const VectorX>& x, Eigen::Ref<VectorX> y) const {
  GEARDYN_ASSERT(x.size() == A_->cols() && y.size() == A_->rows());
  y.noalias() = (*A_) * x;
}

// ------------------------------------------------------------------------ shared shift-solve

namespace internal {

template <class Matrix, class Ldlt, class Lu>
bool ShiftSolveOperatorBase<Matrix, Ldlt, Lu>::RecordLdlt(const Ldlt& ldlt,
                                                          ShiftFactorization factorization,
                                                          const char* name) {
  ++report_.num_factorizations;
  const bool factored = ldlt.info() == Eigen::Success && ldlt.vectorD().allFinite();
  report_.positive_definite = factored && (ldlt.vectorD().array() > 0.0).all();
  if (factorization == ShiftFactorization::kLdlt) {
    report_.used = ShiftFactorization::kLdlt;
    if (!factored) {
      ReportFailedFactorization(name, sigma_, "zero pivot", &report_);
      return false;
    }
  } else if (report_.positive_definite) {
    report_.used = ShiftFactorization::kLdlt;
  }
  return true;
}

template <class Matrix, class Ldlt, class Lu>
void ShiftSolveOperatorBase<Matrix, Ldlt, Lu>::FinishFactorization(double norm1) {
  const auto solve = [this](const VectorX& b, VectorX& x) {
    if (report_.used == ShiftFactorization::kLdlt) {
      x = ldlt_.solve(b);
    } else {
      x = lu_.solve(b);
    }
  };
  geardyn::FinishReport(norm1, M_->rows(), sigma_, solve, &report_);
}

template <class Matrix, class Ldlt, class Lu>
void ShiftSolveOperatorBase<Matrix, Ldlt, Lu>::Solve(const Eigen::Ref<const VectorX>& b,
                                                     Eigen::Ref<VectorX> y) const {
  GEARDYN_DEMAND(report_.ok);
  GEARDYN_ASSERT(b.size() == rows() && y.size() == rows());
  if (report_.used == ShiftFactorization::kLdlt) {
    y = ldlt_.solve(b);
  } else {
    y = lu_.solve(b);
  }
}

template <class Matrix, class Ldlt, class Lu>
void ShiftSolveOperatorBase<Matrix, Ldlt, Lu>::Apply(const Eigen::Ref<const VectorX>& x,
                                                     Eigen::Ref<VectorX> y) const {
  GEARDYN_DEMAND(report_.ok);
  GEARDYN_ASSERT(x.size() == rows() && y.size() == rows());
  scratch_.noalias() = (*M_) * x;
  Solve(scratch_, y);
}

template class ShiftSolveOperatorBase<MatrixX, Eigen::LDLT<MatrixX>, Eigen::PartialPivLU<MatrixX>>;
template class ShiftSolveOperatorBase<SparseMatrix, Eigen::SimplicialLDLT<SparseMatrix>,
                                      Eigen::SparseLU<SparseMatrix>>;

}  // namespace internal

// ------------------------------------------------------------------------ dense shift-solve

DenseShiftSolveOperator::DenseShiftSolveOperator(const MatrixX& K, const MatrixX& M, double sigma,
                                                 ShiftFactorization factorization)
    : ShiftSolveOperatorBase(M, sigma) {
  CheckShiftInputs(K, M, sigma);
  const MatrixX A = K - sigma * M;
  const Eigen::Index n = A.rows();
  if (!A.allFinite()) {
    report_.message = "K − σM has non-finite entries";
    return;
  }
  const double norm1 = n > 0 ? A.cwiseAbs().colwise().sum().maxCoeff() : 0.0;
  report_.used = ShiftFactorization::kLu;
  if (factorization != ShiftFactorization::kLu) {
    Eigen::LDLT<MatrixX> ldlt(A);  // kept only if chosen, so a rejected one frees its memory
    if (!RecordLdlt(ldlt, factorization, "LDLᵀ")) return;
    if (report_.used == ShiftFactorization::kLdlt) ldlt_ = std::move(ldlt);
  }
  if (report_.used == ShiftFactorization::kLu) {
    lu_.compute(A);
    ++report_.num_factorizations;
  }
  FinishFactorization(norm1);
}

// ------------------------------------------------------------------------ sparse shift-solve

SparseShiftSolveOperator::SparseShiftSolveOperator(const SparseMatrix& K, const SparseMatrix& M,
                                                   double sigma, ShiftFactorization factorization)
    : ShiftSolveOperatorBase(M, sigma) {
  CheckShiftInputs(K, M, sigma);
  SparseMatrix A = K - sigma * M;
  A.makeCompressed();
  const Eigen::Map<const VectorX> values(A.valuePtr(), A.nonZeros());
  if (!values.allFinite()) {
    report_.message = "K − σM has non-finite entries";
    return;
  }
  double norm1 = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    double column = 0.0;
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) column += std::abs(it.value());
    norm1 = std::max(norm1, column);
  }
  report_.used = ShiftFactorization::kLu;
  if (factorization != ShiftFactorization::kLu) {
    ldlt_.compute(A);
    if (!RecordLdlt(ldlt_, factorization, "SimplicialLDLT")) return;
  }
  if (report_.used == ShiftFactorization::kLu) {
    lu_.analyzePattern(A);
    lu_.factorize(A);
    ++report_.num_factorizations;
    if (lu_.info() != Eigen::Success) {
      ReportFailedFactorization("SparseLU", sigma, lu_.lastErrorMessage(), &report_);
      return;
    }
  }
  FinishFactorization(norm1);
}

}  // namespace geardyn
