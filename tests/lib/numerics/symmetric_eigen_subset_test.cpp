// Tests of geardyn/numerics/symmetric_eigen_subset.hpp (the few-modes dense solver) against
// independent truths: the closed-form spectrum of a fixed spring–mass chain
// (λ_j = (4k/m) sin²(jπ/(2(n+1))), symmetric_eigen_test.cpp), the full dense solve (tridiagonal
// QR with all vectors: a different algorithm) for the eigenvalues and, up to sign, the vectors,
// the residual ‖Kφ − λMφ‖/‖Kφ‖ and M-orthonormality, an exact rigid-body zero, and the M-
// projector onto a doubly repeated eigenspace (where single vectors are not unique).
#include "geardyn/numerics/symmetric_eigen_subset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"
#include "support/pencils.hpp"

namespace geardyn {
namespace {

using test::MakeChain;
using test::MakeRandomBanded;
using test::Pencil;

// Both solvers are backward stable: |δλ| ≤ c·n·ε·λ_max (Golub & Van Loan §8.1); n ≤ 120.
constexpr double kValueTol = 1e-12;  // × λ_max
// Vectors of eigenvalues separated by a relative gap g ≥ 1e-3 agree to ≈ ε·‖K‖/gap: 1e-9.
constexpr double kVectorTol = 1e-9;
// Residual and ‖ΦᵀMΦ − I‖_max: round-off of n-term sums.
constexpr double kResidualTol = 1e-10;

double FixedChainLambda(int j, int n, double k, double m) {
  const double s = std::sin(0.5 * j * std::numbers::pi / (n + 1));
  return 4.0 * k / m * s * s;
}

void ExpectResidualsAndOrthonormality(const MatrixX& K, const MatrixX& M,
                                      const GeneralizedEigenResult& r) {
  ASSERT_EQ(r.vectors.cols(), r.eigenvalues.size());
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    const VectorX phi = r.vectors.col(k);
    const VectorX Kphi = K * phi;
    if (r.eigenvalues(k) == 0.0) continue;  // rigid: checked by the caller
    EXPECT_LE((Kphi - r.eigenvalues(k) * (M * phi)).norm() / Kphi.norm(), kResidualTol)
        << "mode " << k;
  }
  const MatrixX gram = r.vectors.transpose() * M * r.vectors;
  EXPECT_LE((gram - MatrixX::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff(),
            kResidualTol);
}

// The subset equals columns [first, first + count) of the full solve: values to kValueTol·λ_max,
// vectors up to sign (|φ_aᵀ M φ_b| = 1 for M-unit vectors of the same simple eigenvalue).
void ExpectEqualsFullSolve(const MatrixX& K, const MatrixX& M, const GeneralizedEigenResult& sub,
                           Eigen::Index first) {
  const GeneralizedEigenResult full = SolveGeneralizedEigenDense(K, M);
  ASSERT_TRUE(full.summary.ok()) << full.summary.message;
  const double lambda_max = full.eigenvalues.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < sub.eigenvalues.size(); ++k) {
    EXPECT_NEAR(sub.eigenvalues(k), full.eigenvalues(first + k), kValueTol * lambda_max)
        << "mode " << k;
    const double overlap = sub.vectors.col(k).dot(M * full.vectors.col(first + k));
    EXPECT_NEAR(std::abs(overlap), 1.0, kVectorTol) << "mode " << k;
  }
  EXPECT_EQ(sub.num_rigid_body_modes,
            (full.eigenvalues.segment(first, sub.eigenvalues.size()).array() == 0.0).count());
}

TEST(SymmetricEigenSubsetTest, LowestModesOfAFixedChainMatchTheClosedForm) {
  const int n = 60, count = 8;
  const double k = 3.0e6, m = 2.5;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/true);
  const MatrixX K(p.K), M(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDenseSubset(K, M, count);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  ASSERT_EQ(r.eigenvalues.size(), count);
  EXPECT_EQ(r.summary.counters.at("subset_solver"), 1);
  for (int j = 1; j <= count; ++j) {
    EXPECT_NEAR(r.eigenvalues(j - 1), FixedChainLambda(j, n, k, m),
                kValueTol * FixedChainLambda(n, n, k, m));
  }
  ExpectResidualsAndOrthonormality(K, M, r);
  ExpectEqualsFullSolve(K, M, r, 0);
}

TEST(SymmetricEigenSubsetTest, ShiftReturnsTheNearestWindow) {
  const int n = 40, count = 5;
  const double k = 1.0e5, m = 1.0;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/true);
  const MatrixX K(p.K), M(p.M);
  // σ just above λ_20: the 5 nearest are λ_18 … λ_22 (the chain's spectrum is nearly evenly
  // spaced there, and σ is placed a quarter gap above λ_20).
  const double gap = FixedChainLambda(21, n, k, m) - FixedChainLambda(20, n, k, m);
  const double sigma = FixedChainLambda(20, n, k, m) + 0.25 * gap;
  const GeneralizedEigenResult r = SolveGeneralizedEigenDenseSubset(K, M, count, sigma);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  for (int i = 0; i < count; ++i) {
    EXPECT_NEAR(r.eigenvalues(i), FixedChainLambda(18 + i, n, k, m),
                kValueTol * FixedChainLambda(n, n, k, m));
  }
  ExpectResidualsAndOrthonormality(K, M, r);
  ExpectEqualsFullSolve(K, M, r, 17);
}

TEST(SymmetricEigenSubsetTest, RandomBandedPencilWithARigidModeEqualsTheFullSolve) {
  const Pencil p = MakeRandomBanded(120, /*bandwidth=*/6, /*seed=*/20251125u);
  const MatrixX K(p.K), M(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDenseSubset(K, M, 12);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.num_rigid_body_modes, 1);
  EXPECT_EQ(r.eigenvalues(0), 0.0);  // exactly zero: the rigid rule of rigid_modes.hpp
  // The rigid vector is the uniform translation (K·1 = 0), M-normalized.
  const VectorX ones = VectorX::Ones(K.rows());
  const VectorX rigid = ones / std::sqrt(ones.dot(M * ones));
  EXPECT_NEAR(std::abs(r.vectors.col(0).dot(M * rigid)), 1.0, kVectorTol);
  ExpectResidualsAndOrthonormality(K, M, r);
  ExpectEqualsFullSolve(K, M, r, 0);
}

TEST(SymmetricEigenSubsetTest, RepeatedEigenvaluesSpanTheSameEigenspace) {
  // Two identical uncoupled chains: every eigenvalue is double. The M-projector Φ_g Φ_gᵀ M onto
  // each eigenspace is unique even though the vectors are not.
  const int half = 15;
  const Pencil a = MakeChain(half, 2.0e4, 1.0, /*fixed_ends=*/true);
  const int n = 2 * half;
  MatrixX K = MatrixX::Zero(n, n), M = MatrixX::Zero(n, n);
  K.topLeftCorner(half, half) = K.bottomRightCorner(half, half) = MatrixX(a.K);
  M.topLeftCorner(half, half) = M.bottomRightCorner(half, half) = MatrixX(a.M);
  const int count = 6;  // three double eigenvalues
  const GeneralizedEigenResult r = SolveGeneralizedEigenDenseSubset(K, M, count);
  const GeneralizedEigenResult full = SolveGeneralizedEigenDense(K, M);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  ExpectResidualsAndOrthonormality(K, M, r);
  for (int g = 0; g < count; g += 2) {
    EXPECT_NEAR(r.eigenvalues(g), FixedChainLambda(g / 2 + 1, half, 2.0e4, 1.0), 1e-9);
    EXPECT_NEAR(r.eigenvalues(g + 1), r.eigenvalues(g), 1e-9);
    const MatrixX P_sub = r.vectors.middleCols(g, 2) * r.vectors.middleCols(g, 2).transpose() * M;
    const MatrixX P_full =
        full.vectors.middleCols(g, 2) * full.vectors.middleCols(g, 2).transpose() * M;
    EXPECT_LE((P_sub - P_full).cwiseAbs().maxCoeff(), kVectorTol) << "eigenspace " << g / 2;
  }
}

TEST(SymmetricEigenSubsetTest, AllModesEqualTheFullSolve) {
  const Pencil p = MakeRandomBanded(30, /*bandwidth=*/3, /*seed=*/7u);
  const MatrixX K(p.K), M(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDenseSubset(K, M, 30);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  ExpectResidualsAndOrthonormality(K, M, r);
  ExpectEqualsFullSolve(K, M, r, 0);
}

TEST(SymmetricEigenSubsetTest, RejectsBadInputNamingTheArgument) {
  const Pencil p = MakeChain(10, 1.0, 1.0, /*fixed_ends=*/true);
  const MatrixX K(p.K), M(p.M);
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDenseSubset(K, M, 0), InvalidInput,
                        "count: must be in \\[1, n = 10\\], got 0");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDenseSubset(K, M, 11), InvalidInput,
                        "count: .*got 11");
  EXPECT_THROWS_MESSAGE(
      SolveGeneralizedEigenDenseSubset(K, M, 3, std::numeric_limits<double>::infinity()),
      InvalidInput, "sigma: must be finite");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDenseSubset(K, MatrixX(-M), 3), InvalidInput, "M:");
}

}  // namespace
}  // namespace geardyn
