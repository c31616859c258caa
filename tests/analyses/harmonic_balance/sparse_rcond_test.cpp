// The sparse reciprocal-condition estimator of the linear HB (EstimateSparseRcond, Hager's
// method as refined by Higham 1988) against the exact 1-norm condition number κ₁ = ‖A‖₁‖A⁻¹‖₁ of
// small matrices: A⁻¹ in closed form (Hilbert) or by a dense full-pivoting LU inverse (an
// independent path: no sparse LU, no iteration). The estimate of ‖A⁻¹‖₁ is ‖A⁻¹x‖₁ for some
// ‖x‖₁ = 1, so it never exceeds the true norm: the estimated rcond is ≥ the true one, and Higham
// (1988, ACM TOMS 14(4), §4 and Table 4.1) finds it exact or within a factor 3 on his test sets.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <cmath>
#include <complex>
#include <random>

#include "../../../analyses/src/harmonic_balance/hb_internal.hpp"

namespace geardyn {
namespace {

using internal::Complex;
using internal::ComplexSparse;

// Higham's reported factor between ‖A⁻¹‖₁ and its estimate (see the file comment).
constexpr double kEstimatorFactor = 3.0;
// Relative slack for the round-off of the solves (the 8 × 8 Hilbert case loses κε ≈ 1e-5).
constexpr double kRoundOff = 1e-5;

double OneNorm(const MatrixXc& a) { return a.cwiseAbs().colwise().sum().maxCoeff(); }

// Factorizes A (sparse LU, as the HB does) and returns the estimated 1/κ₁.
double Estimate(const MatrixXc& dense) {
  ComplexSparse A = dense.sparseView();
  A.makeCompressed();
  Eigen::SparseLU<ComplexSparse> lu;
  lu.compute(A);
  EXPECT_EQ(lu.info(), Eigen::Success);
  return internal::EstimateSparseRcond(A, lu);
}

// The estimate lies in [true, factor·true] (up to round-off), true = 1/(‖A‖₁‖A⁻¹‖₁).
void ExpectWithinEstimatorFactor(const MatrixXc& A, const MatrixXc& A_inverse, const char* what) {
  const double exact = 1.0 / (OneNorm(A) * OneNorm(A_inverse));
  const double estimate = Estimate(A);
  SCOPED_TRACE(what);
  EXPECT_GE(estimate, exact * (1.0 - kRoundOff)) << "exact " << exact;
  EXPECT_LE(estimate, kEstimatorFactor * exact * (1.0 + kRoundOff)) << "exact " << exact;
}

MatrixXc RandomComplex(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixXc a(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) a(i, j) = Complex(u(gen), u(gen));
  }
  return a;
}

TEST(SparseRcondTest, RandomSpdMatrices) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const int n = 12 + 4 * static_cast<int>(seed);
    const MatrixX b = RandomComplex(n, seed).real();
    // BᵀB + 0.01 n I: SPD (B square random, so BᵀB is nearly singular and the shift sets κ).
    const MatrixX spd = b.transpose() * b + 0.01 * n * MatrixX::Identity(n, n);
    const MatrixXc A = spd.cast<Complex>();
    ExpectWithinEstimatorFactor(A, A.fullPivLu().inverse(), "random SPD");
  }
}

// Hilbert H_ij = 1/(i + j − 1) with its closed-form integer inverse (Choi 1983, Amer. Math.
// Monthly 90(5) 301–312): (H⁻¹)_ij = (−1)^{i+j} (i+j−1) C(n+i−1, n−j) C(n+j−1, n−i) C(i+j−2, i−1)².
double Binomial(int n, int k) {
  return std::round(
      std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0)));
}

TEST(SparseRcondTest, IllConditionedHilbertMatrices) {
  for (int n : {4, 6, 8}) {
    MatrixXc H(n, n), H_inverse(n, n);
    for (int i = 1; i <= n; ++i) {
      for (int j = 1; j <= n; ++j) {
        H(i - 1, j - 1) = 1.0 / (i + j - 1);
        const double c = Binomial(i + j - 2, i - 1);
        H_inverse(i - 1, j - 1) = ((i + j) % 2 == 0 ? 1.0 : -1.0) * (i + j - 1) *
                                  Binomial(n + i - 1, n - j) * Binomial(n + j - 1, n - i) * c * c;
      }
    }
    // The closed form is the inverse (a check of the formula itself, to the conditioning).
    EXPECT_LT(OneNorm(H * H_inverse - MatrixXc::Identity(n, n)),
              1e-14 * OneNorm(H) * OneNorm(H_inverse));
    ExpectWithinEstimatorFactor(H, H_inverse, "Hilbert");
  }
}

TEST(SparseRcondTest, NonsymmetricComplexSparseMatrices) {
  for (unsigned seed = 11; seed <= 15; ++seed) {
    const int n = 30;
    MatrixXc A = RandomComplex(n, seed);
    // Keep a band plus a few far entries (a sparse nonsymmetric pattern) and a dominant diagonal
    // of varying size, then scale one row down by 1e-6 (ill-conditioned: κ₁ grows by ≈ 1e6).
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        if (std::abs(i - j) > 2 && (i * 7 + j * 3) % 11 != 0) A(i, j) = 0.0;
      }
      A(j, j) += Complex(1.0 + j % 5, 0.5);
    }
    A.row(static_cast<int>(seed) % n) *= 1e-6;
    ExpectWithinEstimatorFactor(A, A.fullPivLu().inverse(), "nonsymmetric complex");
  }
}

TEST(SparseRcondTest, NearlySingularMatrixGivesATinyEstimate) {
  // Two columns equal up to ~1e-15: 1/κ₁ ≲ 1e-14, and the estimate is within a factor 3 of it.
  MatrixXc A = RandomComplex(10, 99);
  A.col(3) = A.col(7) * Complex(1.0 + 1e-15, 0.0);
  A.col(3)(0) += 1e-15;
  EXPECT_LT(Estimate(A), 1e-13);
}

}  // namespace
}  // namespace geardyn
