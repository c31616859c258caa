// Tests of geardyn/numerics/linear_operator.hpp against independent truths: products summed
// entry by entry, residuals (K − σM) y − M x of the shift solves, matrices whose singularity is
// exact in floating point, and a diagonal matrix whose condition number is known.
#include "geardyn/numerics/linear_operator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

// Residuals of one factorized solve of a well-conditioned tridiagonal system: a few ulps times n.
constexpr double kSolveTol = 1e-12;

/// Spring–mass chain: n equal masses m, equal springs k between neighbours, and (fixed ends) a
/// spring to the ground at each end. K [N/m], M [kg].
MatrixX ChainStiffness(int n, double k, bool fixed_ends) {
  MatrixX K = MatrixX::Zero(n, n);
  for (int i = 0; i + 1 < n; ++i) {
    K(i, i) += k;
    K(i + 1, i + 1) += k;
    K(i, i + 1) -= k;
    K(i + 1, i) -= k;
  }
  if (fixed_ends) {
    K(0, 0) += k;
    K(n - 1, n - 1) += k;
  }
  return K;
}

VectorX TestVector(int n) {
  VectorX x(n);
  for (int i = 0; i < n; ++i) x(i) = std::sin(1.3 * i + 0.4) + 0.1 * i;
  return x;
}

/// max_i |(K − σM) y − M x|_i / (‖K − σM‖_max ‖y‖_max + ‖M x‖_max): relative backward residual.
double ShiftResidual(const MatrixX& K, const MatrixX& M, double sigma, const VectorX& x,
                     const VectorX& y) {
  const MatrixX A = K - sigma * M;
  const VectorX Mx = M * x;
  return (A * y - Mx).cwiseAbs().maxCoeff() /
         (A.cwiseAbs().maxCoeff() * y.cwiseAbs().maxCoeff() + Mx.cwiseAbs().maxCoeff());
}

struct NotAnOperator {
  Eigen::Index rows() const { return 1; }
};

static_assert(!LinearOperator<NotAnOperator>);
static_assert(!ShiftSolveOperator<DenseMatrixOperator>);

TEST(LinearOperatorTest, DenseAndSparseApplyEqualEntrywiseSums) {
  const int n = 7;
  MatrixX A(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      A(i, j) = (i == j) ? 4.0 : ((i + 2 * j) % 3 == 0 ? 0.0 : 0.5 * j - i);
  }
  const SparseMatrix As = A.sparseView();
  const VectorX x = TestVector(n);
  VectorX expected(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) sum += A(i, j) * x(j);
    expected(i) = sum;
  }
  const DenseMatrixOperator dense(A);
  const SparseMatrixOperator sparse(As);
  EXPECT_EQ(dense.rows(), n);
  EXPECT_EQ(sparse.rows(), n);
  VectorX y(n);
  dense.Apply(x, y);
  EXPECT_LE((y - expected).cwiseAbs().maxCoeff(), 1e-14 * expected.cwiseAbs().maxCoeff());
  y.setZero();
  sparse.Apply(x, y);
  EXPECT_LE((y - expected).cwiseAbs().maxCoeff(), 1e-14 * expected.cwiseAbs().maxCoeff());
}

TEST(LinearOperatorTest, MatrixOperatorsRejectNonSquareMatrices) {
  const MatrixX A = MatrixX::Ones(3, 4);
  EXPECT_THROWS_MESSAGE(DenseMatrixOperator{A}, InvalidInput, "A: must be square, got 3 × 4");
  const SparseMatrix As = A.sparseView();
  EXPECT_THROWS_MESSAGE(SparseMatrixOperator{As}, InvalidInput, "A: must be square");
}

// Free chain (one rigid mode, K singular) with σ < 0: K − σM is positive definite, so kAuto keeps
// the LDLᵀ factorization; Apply and Solve satisfy their defining equations.
TEST(LinearOperatorTest, NegativeShiftOnSingularStiffnessUsesLdlt) {
  const int n = 40;
  const MatrixX K = ChainStiffness(n, 2.5e6, /*fixed_ends=*/false);
  MatrixX M = MatrixX::Zero(n, n);
  for (int i = 0; i < n; ++i) M(i, i) = 1.0 + 0.05 * i;
  const double sigma = -1e-3 * 2.5e6;
  const VectorX x = TestVector(n);
  VectorX y(n);

  const DenseShiftSolveOperator dense(K, M, sigma);
  ASSERT_TRUE(dense.ok()) << dense.factorization().message;
  EXPECT_EQ(dense.factorization().used, ShiftFactorization::kLdlt);
  EXPECT_TRUE(dense.factorization().positive_definite);
  EXPECT_EQ(dense.factorization().num_factorizations, 1);
  EXPECT_DOUBLE_EQ(dense.sigma(), sigma);
  dense.Apply(x, y);
  EXPECT_LT(ShiftResidual(K, M, sigma, x, y), kSolveTol);

  const SparseMatrix Ks = K.sparseView();
  const SparseMatrix Ms = M.sparseView();
  const SparseShiftSolveOperator sparse(Ks, Ms, sigma);
  ASSERT_TRUE(sparse.ok()) << sparse.factorization().message;
  EXPECT_EQ(sparse.factorization().used, ShiftFactorization::kLdlt);
  EXPECT_EQ(sparse.rows(), n);
  y.setZero();
  sparse.Apply(x, y);
  EXPECT_LT(ShiftResidual(K, M, sigma, x, y), kSolveTol);
  // Solve(b) = (K − σM)⁻¹ b with b = M x gives the same y.
  VectorX y2(n);
  sparse.Solve(M * x, y2);
  EXPECT_LE((y2 - y).cwiseAbs().maxCoeff(), 1e-12 * y.cwiseAbs().maxCoeff());
}

// A shift inside the spectrum makes K − σM indefinite: kAuto rejects LDLᵀ (a negative pivot) and
// refactorizes with LU, whose solves are accurate.
TEST(LinearOperatorTest, InteriorShiftFallsBackToLu) {
  const int n = 30;
  const double k = 1.0e4, m = 3.0;
  const MatrixX K = ChainStiffness(n, k, /*fixed_ends=*/true);
  const MatrixX M = m * MatrixX::Identity(n, n);
  // Midway between λ_5 and λ_6 of the fixed chain, λ_j = (2k/m)(1 − cos(jπ/(n+1))).
  const auto lambda = [&](int j) { return 2.0 * k / m * (1.0 - std::cos(j * kPi / (n + 1))); };
  const double sigma = 0.5 * (lambda(5) + lambda(6));
  const VectorX x = TestVector(n);
  VectorX y(n);

  const DenseShiftSolveOperator dense(K, M, sigma);
  ASSERT_TRUE(dense.ok()) << dense.factorization().message;
  EXPECT_EQ(dense.factorization().used, ShiftFactorization::kLu);
  EXPECT_FALSE(dense.factorization().positive_definite);
  EXPECT_EQ(dense.factorization().num_factorizations, 2);
  dense.Apply(x, y);
  EXPECT_LT(ShiftResidual(K, M, sigma, x, y), kSolveTol);

  const SparseMatrix Ks = K.sparseView();
  const SparseMatrix Ms = M.sparseView();
  const SparseShiftSolveOperator sparse(Ks, Ms, sigma);
  ASSERT_TRUE(sparse.ok()) << sparse.factorization().message;
  EXPECT_EQ(sparse.factorization().used, ShiftFactorization::kLu);
  EXPECT_EQ(sparse.factorization().num_factorizations, 2);
  y.setZero();
  sparse.Apply(x, y);
  EXPECT_LT(ShiftResidual(K, M, sigma, x, y), kSolveTol);

  // Forcing the factorization is honoured.
  const SparseShiftSolveOperator forced_lu(Ks, Ms, -1.0, ShiftFactorization::kLu);
  EXPECT_EQ(forced_lu.factorization().used, ShiftFactorization::kLu);
  EXPECT_EQ(forced_lu.factorization().num_factorizations, 1);
  const DenseShiftSolveOperator forced_ldlt(K, M, sigma, ShiftFactorization::kLdlt);
  ASSERT_TRUE(forced_ldlt.ok());
  EXPECT_EQ(forced_ldlt.factorization().used, ShiftFactorization::kLdlt);
  forced_ldlt.Apply(x, y);
  EXPECT_LT(ShiftResidual(K, M, sigma, x, y), kSolveTol);
}

// σ = 0 on a free chain (K exactly singular: its rows sum to zero) and σ = 2 on the unit fixed
// chain of 5 masses, whose K − 2M = tridiag(−1, 0, −1) is exactly singular (λ_3 = 2(1 − cos π/2)
// = 2): both must be reported, not factorized into garbage, for every factorization choice.
TEST(LinearOperatorTest, SingularShiftIsReportedNotThrown) {
  const MatrixX K_free = ChainStiffness(12, 7.0, /*fixed_ends=*/false);
  const MatrixX M_free = MatrixX::Identity(12, 12);
  const MatrixX K_fixed = ChainStiffness(5, 1.0, /*fixed_ends=*/true);
  const MatrixX M_fixed = MatrixX::Identity(5, 5);
  const SparseMatrix Ks_free = K_free.sparseView(), Ms_free = M_free.sparseView();
  const SparseMatrix Ks_fixed = K_fixed.sparseView(), Ms_fixed = M_fixed.sparseView();
  for (ShiftFactorization f :
       {ShiftFactorization::kAuto, ShiftFactorization::kLdlt, ShiftFactorization::kLu}) {
    SCOPED_TRACE(ShiftFactorizationName(f));
    const DenseShiftSolveOperator d1(K_free, M_free, 0.0, f);
    const DenseShiftSolveOperator d2(K_fixed, M_fixed, 2.0, f);
    const SparseShiftSolveOperator s1(Ks_free, Ms_free, 0.0, f);
    const SparseShiftSolveOperator s2(Ks_fixed, Ms_fixed, 2.0, f);
    for (const ShiftFactorizationReport* report :
         {&d1.factorization(), &d2.factorization(), &s1.factorization(), &s2.factorization()}) {
      EXPECT_FALSE(report->ok);
      EXPECT_NE(report->message.find("singular"), std::string::npos) << report->message;
    }
    EXPECT_FALSE(d1.ok());
    EXPECT_FALSE(s2.ok());
  }
  const DenseShiftSolveOperator singular(K_free, M_free, 0.0);
  VectorX x = VectorX::Ones(12), y(12);
  EXPECT_THROW(singular.Apply(x, y), InternalError);
  EXPECT_THROW(singular.Solve(x, y), InternalError);
}

// A = diag(1, 2, …, 100) (K diagonal, M = I, σ = 0): cond₁(A) = 100 exactly. The estimate is a
// lower bound that two inverse-iteration steps bring close to it.
TEST(LinearOperatorTest, ConditionEstimateOfADiagonalMatrix) {
  const int n = 100;
  MatrixX K = MatrixX::Zero(n, n);
  for (int i = 0; i < n; ++i) K(i, i) = i + 1.0;
  const MatrixX M = MatrixX::Identity(n, n);
  const DenseShiftSolveOperator dense(K, M, 0.0);
  ASSERT_TRUE(dense.ok());
  EXPECT_LE(dense.factorization().condition_estimate, 100.0 * (1.0 + 1e-12));
  EXPECT_GE(dense.factorization().condition_estimate, 30.0);
  const SparseMatrix Ks = K.sparseView(), Ms = M.sparseView();
  const SparseShiftSolveOperator sparse(Ks, Ms, 0.0);
  EXPECT_NEAR(sparse.factorization().condition_estimate, dense.factorization().condition_estimate,
              1e-9 * dense.factorization().condition_estimate);
}

TEST(LinearOperatorTest, ShiftSolveRejectsBadInput) {
  const MatrixX K = MatrixX::Identity(4, 4);
  const MatrixX M3 = MatrixX::Identity(3, 3);
  const MatrixX rect = MatrixX::Ones(4, 3);
  EXPECT_THROWS_MESSAGE(DenseShiftSolveOperator(rect, K, 0.0), InvalidInput, "K: must be square");
  EXPECT_THROWS_MESSAGE(DenseShiftSolveOperator(K, rect, 0.0), InvalidInput, "M: must be square");
  EXPECT_THROWS_MESSAGE(DenseShiftSolveOperator(K, M3, 0.0), InvalidInput,
                        "M \\(rows, must match K\\): size 3 .* 4");
  EXPECT_THROWS_MESSAGE(DenseShiftSolveOperator(K, K, std::nan("")), InvalidInput,
                        "sigma: must be finite");
  const SparseMatrix Ks = K.sparseView(), Ms3 = M3.sparseView();
  EXPECT_THROWS_MESSAGE(SparseShiftSolveOperator(Ks, Ms3, 0.0), InvalidInput, "M \\(rows");
  EXPECT_STREQ(ShiftFactorizationName(ShiftFactorization::kLu), "lu");
}

}  // namespace
}  // namespace geardyn
