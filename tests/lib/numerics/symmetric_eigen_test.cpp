// Tests of geardyn/numerics/symmetric_eigen.hpp against independent truths: closed-form spectra of
// spring–mass chains and of a consistent-mass rod (derived below), residuals ‖Kφ − λMφ‖/‖Kφ‖ and
// M-orthonormality (Spectra style), the dense solver as the reference for ARPACK on a random
// banded system, and the error paths (exceptions for bad input, statuses for numerical outcomes).
//
// Closed forms. (1) Chain of n equal masses m and springs k, both ends tied to the ground by a
// spring k ("fixed–fixed"): K = k·tridiag(−1, 2, −1), M = m·I. With φ_i = sin(iθ),
//   −φ_{i−1} + 2φ_i − φ_{i+1} = (2 − 2cos θ) φ_i   for every i = 1..n
// provided the ghost values φ_0 = φ_{n+1} = 0, i.e. sin((n+1)θ) = 0, θ_j = jπ/(n+1). Hence
//   λ_j = (2k/m)(1 − cos(jπ/(n+1))),  j = 1..n
// (the spectrum of the tridiagonal Toeplitz matrix; e.g. G. Strang, Computational Science and
// Engineering, Wellesley-Cambridge 2007, §1.5). (2) The same chain with free ends (n − 1 springs):
// φ_i = cos((i − ½)θ) satisfies the interior equation, the end equations need φ_0 = φ_1 (true for
// every θ) and φ_{n+1} = φ_n, i.e. sin(nθ)·sin(θ/2) = 0, θ_j = jπ/n:
//   λ_j = (2k/m)(1 − cos(jπ/n)),  j = 0..n−1,   exactly one zero (the rigid-body translation).
// (3) Rod of length L, N linear elements (h = L/N), fixed at both ends, consistent mass
// M_e = ρAh/6·[2 1; 1 2], K_e = EA/h·[1 −1; −1 1]; interior node i: with u_i = sin(iθ),
//   (EA/h)(2 − 2cos θ) = λ (ρAh/6)(4 + 2cos θ),  θ_j = jπ/N, j = 1..N−1:
//   λ_j = (6E/(ρh²))·(1 − cos θ_j)/(2 + cos θ_j)   (non-diagonal M).
#include "geardyn/numerics/symmetric_eigen.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"
#include "support/pencils.hpp"

namespace geardyn {
namespace {

using test::FromTriplets;
using test::MakeChain;
using test::MakeRandomBanded;
using test::Pencil;

// Dense symmetric eigenvalues are backward stable: |δλ| ≤ c·n·ε·λ_max (Golub & Van Loan §8.1).
constexpr double kDenseTol = 1e-13;  // × λ_max, n ≤ 50
// ARPACK shift-invert with tol = 1e-12 gives each λ near σ to a relative 1e-12-ish; margin 100.
constexpr double kArpackTol = 1e-10;  // × λ
// Residuals ‖Kφ − λMφ‖/‖Kφ‖ and ‖ΦᵀMΦ − I‖_max of computed eigenpairs: round-off of n-term sums
// amplified by the condition of the shifted solves.
constexpr double kResidualTol = 1e-9;
constexpr double kOrthoTol = 1e-9;

// 1 − cos θ is evaluated as 2 sin²(θ/2): for θ ~ 1e-3 the difference form loses 6 digits.
double FixedChainLambda(int j, int n, double k, double m) {
  const double s = std::sin(0.5 * j * kPi / (n + 1));
  return 4.0 * k / m * s * s;
}
double FreeChainLambda(int j, int n, double k, double m) {
  const double s = std::sin(0.5 * j * kPi / n);
  return 4.0 * k / m * s * s;
}

/// Fixed–fixed rod, N linear elements, consistent mass: N − 1 interior DOFs [m].
Pencil MakeConsistentRod(int N, double E, double rho, double area, double length) {
  const double h = length / N;
  const double ke = E * area / h, me = rho * area * h / 6.0;
  std::vector<Eigen::Triplet<double>> kt, mt;
  // Element e joins nodes e and e + 1 (0..N); DOF i is node i + 1 (the end nodes are fixed).
  const auto is_free = [N](int node) { return node >= 1 && node <= N - 1; };
  for (int e = 0; e < N; ++e) {
    for (const int node : {e, e + 1}) {
      if (!is_free(node)) continue;
      kt.emplace_back(node - 1, node - 1, ke);
      mt.emplace_back(node - 1, node - 1, 2.0 * me);
    }
    if (is_free(e) && is_free(e + 1)) {
      kt.emplace_back(e - 1, e, -ke);
      kt.emplace_back(e, e - 1, -ke);
      mt.emplace_back(e - 1, e, me);
      mt.emplace_back(e, e - 1, me);
    }
  }
  return {FromTriplets(N - 1, kt), FromTriplets(N - 1, mt)};
}

double ConsistentRodLambda(int j, int N, double E, double rho, double length) {
  const double h = length / N, theta = j * kPi / N;
  const double s = std::sin(0.5 * theta);
  return 6.0 * E / (rho * h * h) * (2.0 * s * s) / (2.0 + std::cos(theta));
}

int CountExactZeros(const VectorX& v) { return static_cast<int>((v.array() == 0.0).count()); }

/// Residual and M-orthonormality of every computed eigenpair (rigid modes: ‖Kφ‖/(‖K‖₁‖φ‖)).
void ExpectValidEigenpairs(const MatrixX& K, const MatrixX& M, const GeneralizedEigenResult& r) {
  ASSERT_EQ(r.vectors.cols(), r.eigenvalues.size());
  ASSERT_TRUE(r.eigenvalues.allFinite());
  ASSERT_TRUE(r.vectors.allFinite());
  for (Eigen::Index k = 1; k < r.eigenvalues.size(); ++k) {
    EXPECT_LE(r.eigenvalues(k - 1), r.eigenvalues(k)) << "not ascending at " << k;
  }
  const double k_norm = K.cwiseAbs().colwise().sum().maxCoeff();
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    const VectorX phi = r.vectors.col(k);
    const VectorX Kphi = K * phi;
    if (r.eigenvalues(k) == 0.0) {
      EXPECT_LE(Kphi.norm() / (k_norm * phi.norm()), kResidualTol) << "rigid mode " << k;
    } else {
      EXPECT_LE((Kphi - r.eigenvalues(k) * (M * phi)).norm() / Kphi.norm(), kResidualTol)
          << "mode " << k;
    }
    Eigen::Index largest = 0;
    phi.cwiseAbs().maxCoeff(&largest);
    EXPECT_GT(phi(largest), 0.0) << "sign convention, mode " << k;
  }
  const MatrixX gram = r.vectors.transpose() * M * r.vectors;
  const Eigen::Index m = gram.rows();
  EXPECT_LE((gram - MatrixX::Identity(m, m)).cwiseAbs().maxCoeff(), kOrthoTol);
}

// ------------------------------------------------------------------------------- dense solver

TEST(SymmetricEigenDenseTest, FixedChainMatchesClosedForm) {
  const int n = 12;
  const double k = 3.7e5, m = 2.3;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/true);
  const MatrixX K(p.K), M(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDense(K, M);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_EQ(r.eigenvalues.size(), n);
  const double lambda_max = FixedChainLambda(n, n, k, m);
  for (int j = 1; j <= n; ++j) {
    EXPECT_NEAR(r.eigenvalues(j - 1), FixedChainLambda(j, n, k, m), kDenseTol * lambda_max)
        << "j = " << j;
  }
  EXPECT_EQ(r.num_rigid_body_modes, 0);
  EXPECT_TRUE(r.summary.warnings.empty());
  EXPECT_DOUBLE_EQ(r.spectrum_scale, 2.0 * k / m);  // max K_ii/M_ii
  ExpectValidEigenpairs(K, M, r);
  // Mode shapes: φ_j ∝ sin(i jπ/(n+1)); the fundamental has all entries of one sign.
  EXPECT_GT(r.vectors.col(0).minCoeff(), 0.0);
}

TEST(SymmetricEigenDenseTest, FreeChainHasExactlyOneZeroEigenvalue) {
  const int n = 15;
  const double k = 8.1e6, m = 0.7;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/false);
  const MatrixX K(p.K), M(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDense(K, M);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.num_rigid_body_modes, 1);
  EXPECT_EQ(CountExactZeros(r.eigenvalues), 1);
  EXPECT_EQ(r.eigenvalues(0), 0.0);
  ASSERT_EQ(r.summary.warnings.size(), 1u);
  EXPECT_NE(r.summary.warnings[0].find("rigid-body"), std::string::npos);
  const double lambda_max = FreeChainLambda(n - 1, n, k, m);
  for (int j = 1; j < n; ++j) {
    EXPECT_NEAR(r.eigenvalues(j), FreeChainLambda(j, n, k, m), kDenseTol * lambda_max);
  }
  ExpectValidEigenpairs(K, M, r);
  // The rigid mode is the uniform translation, M-normalized: φ_i = 1/√(n m).
  EXPECT_LE((r.vectors.col(0).array() - 1.0 / std::sqrt(n * m)).abs().maxCoeff(), 1e-10);
}

// Two disconnected free chains: a block-diagonal K with a two-dimensional null space.
TEST(SymmetricEigenDenseTest, TwoFreeChainsGiveTwoExactZeros) {
  const Pencil a = MakeChain(6, 1.0e5, 1.0, false), b = MakeChain(9, 3.0e5, 2.0, false);
  MatrixX K = MatrixX::Zero(15, 15), M = MatrixX::Zero(15, 15);
  K.topLeftCorner(6, 6) = MatrixX(a.K);
  K.bottomRightCorner(9, 9) = MatrixX(b.K);
  M.topLeftCorner(6, 6) = MatrixX(a.M);
  M.bottomRightCorner(9, 9) = MatrixX(b.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDense(K, M);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.num_rigid_body_modes, 2);
  EXPECT_EQ(CountExactZeros(r.eigenvalues), 2);
  std::vector<double> expected;
  for (int j = 0; j < 6; ++j) expected.push_back(FreeChainLambda(j, 6, 1.0e5, 1.0));
  for (int j = 0; j < 9; ++j) expected.push_back(FreeChainLambda(j, 9, 3.0e5, 2.0));
  std::sort(expected.begin(), expected.end());
  for (int i = 2; i < 15; ++i) EXPECT_NEAR(r.eigenvalues(i), expected[i], kDenseTol * 6.0e5);
  ExpectValidEigenpairs(K, M, r);
}

TEST(SymmetricEigenDenseTest, ConsistentMassRodMatchesClosedForm) {
  const int N = 24;
  const double E = 2.1e11, rho = 7850.0, area = 3e-4, length = 0.8;
  const Pencil p = MakeConsistentRod(N, E, rho, area, length);
  const MatrixX K(p.K), M(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDense(K, M);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_EQ(r.eigenvalues.size(), N - 1);
  const double lambda_max = ConsistentRodLambda(N - 1, N, E, rho, length);
  for (int j = 1; j < N; ++j) {
    EXPECT_NEAR(r.eigenvalues(j - 1), ConsistentRodLambda(j, N, E, rho, length),
                kDenseTol * lambda_max);
  }
  ExpectValidEigenpairs(K, M, r);
}

// A random banded floating system with a non-diagonal M: one exact zero (the translation), valid
// eigenpairs, and the rigid mode M-normalized: φ_0 = ±1/√(1ᵀM1).
TEST(SymmetricEigenDenseTest, RandomBandedSystemHasOneRigidMode) {
  const int n = 80;
  const Pencil p = MakeRandomBanded(n, /*bandwidth=*/4, /*seed=*/99u);
  const MatrixX K(p.K), M(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDense(K, M);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.num_rigid_body_modes, 1);
  EXPECT_EQ(CountExactZeros(r.eigenvalues), 1);
  EXPECT_GT(r.eigenvalues(1), 1e-6 * r.spectrum_scale);
  const double total_mass = M.sum();
  EXPECT_LE((r.vectors.col(0).array() - 1.0 / std::sqrt(total_mass)).abs().maxCoeff(), 1e-9);
  ExpectValidEigenpairs(K, M, r);
}

TEST(SymmetricEigenDenseTest, VectorsOnlyWhenAsked) {
  const Pencil p = MakeChain(10, 1.0, 1.0, true);
  GeneralizedEigenOptions options;
  options.compute_vectors = false;
  const GeneralizedEigenResult r = SolveGeneralizedEigenDense(MatrixX(p.K), MatrixX(p.M), options);
  ASSERT_TRUE(r.summary.ok());
  EXPECT_EQ(r.vectors.size(), 0);
  const GeneralizedEigenResult with = SolveGeneralizedEigenDense(MatrixX(p.K), MatrixX(p.M));
  EXPECT_LE((r.eigenvalues - with.eigenvalues).cwiseAbs().maxCoeff(), 1e-14 * 4.0);
}

// K − c·M with c between λ_1 and λ_2 of a fixed chain has one clearly negative eigenvalue.
TEST(SymmetricEigenDenseTest, StiffnessNotPsdIsANumericalIssue) {
  const int n = 10;
  const Pencil p = MakeChain(n, 1.0e4, 2.0, true);
  const double c = 0.5 * (FixedChainLambda(1, n, 1.0e4, 2.0) + FixedChainLambda(2, n, 1.0e4, 2.0));
  const MatrixX K = MatrixX(p.K) - c * MatrixX(p.M);
  const GeneralizedEigenResult r = SolveGeneralizedEigenDense(K, MatrixX(p.M));
  EXPECT_EQ(r.summary.status, Status::kNumericalIssue);
  EXPECT_NE(r.summary.message.find("not positive semidefinite"), std::string::npos)
      << r.summary.message;
  ASSERT_EQ(r.eigenvalues.size(), n);  // the pairs are still returned, and finite
  EXPECT_TRUE(r.eigenvalues.allFinite());
  EXPECT_NEAR(r.eigenvalues(0), FixedChainLambda(1, n, 1.0e4, 2.0) - c, 1e-9 * c);
}

TEST(SymmetricEigenDenseTest, RejectsBadInputNamingTheArgument) {
  const MatrixX I3 = MatrixX::Identity(3, 3), I4 = MatrixX::Identity(4, 4);
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(MatrixX::Ones(3, 4), I3), InvalidInput,
                        "K: must be square, got 3 × 4");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(I3, MatrixX::Ones(3, 2)), InvalidInput,
                        "M: must be square");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(I3, I4), InvalidInput,
                        "M \\(rows, must match K\\): size 4 .* 3");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(MatrixX(0, 0), MatrixX(0, 0)), InvalidInput,
                        "K: must not be empty");
  MatrixX indefinite(2, 2);  // positive diagonal, eigenvalues 3 and −1
  indefinite << 1.0, 2.0, 2.0, 1.0;
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(MatrixX::Identity(2, 2), indefinite),
                        InvalidInput, "M: not positive definite");
  MatrixX zero_mass = I3;
  zero_mass(1, 1) = 0.0;
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(I3, zero_mass), InvalidInput,
                        "M: not positive definite, diagonal entry M\\(1, 1\\) = 0");
  MatrixX asymmetric = I3;
  asymmetric(0, 2) = 0.5;
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(asymmetric, I3), InvalidInput,
                        "K: not symmetric");
  MatrixX nan_k = I3;
  nan_k(2, 2) = std::nan("");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(nan_k, I3), InvalidInput,
                        "K: non-finite entry \\(2, 2\\)");
  GeneralizedEigenOptions options;
  options.zero_tol = -1.0;
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenDense(I3, I3, options), InvalidInput,
                        "GeneralizedEigenOptions.zero_tol: must be finite and ≥ 0, got -1");
}

// ------------------------------------------------------------------------------ ARPACK solver
#if defined(GEARDYN_WITH_ARPACK)

TEST(SymmetricEigenArpackTest, FixedChainLowestModesMatchClosedForm) {
  const int n = 400, modes = 20;
  const double k = 3.7e5, m = 2.3;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/true);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, modes);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_EQ(r.eigenvalues.size(), modes);
  for (int j = 1; j <= modes; ++j) {
    const double exact = FixedChainLambda(j, n, k, m);
    EXPECT_NEAR(r.eigenvalues(j - 1), exact, kArpackTol * exact) << "j = " << j;
  }
  EXPECT_EQ(r.num_rigid_body_modes, 0);
  EXPECT_LT(r.sigma, 0.0);
  EXPECT_DOUBLE_EQ(r.sigma, -kDefaultShiftFraction * r.spectrum_scale);
  EXPECT_EQ(r.summary.counters.at("converged"), modes);
  EXPECT_EQ(r.summary.counters.at("arpack_info"), 0);
  EXPECT_EQ(r.summary.counters.at("factorizations"), 2);  // Cholesky of M, LDLᵀ of K − σM
  EXPECT_GT(r.summary.counters.at("operator_applications"), 0);
  ExpectValidEigenpairs(MatrixX(p.K), MatrixX(p.M), r);
}

// K is singular (free chain): the default σ < 0 makes K − σM positive definite, and the rigid
// mode comes out as an exact zero, with the flexible modes after it.
TEST(SymmetricEigenArpackTest, FreeChainRigidModeIsExactlyZero) {
  const int n = 300, modes = 20;
  const double k = 8.1e6, m = 0.7;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/false);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, modes);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_EQ(r.eigenvalues.size(), modes);
  EXPECT_FALSE((r.eigenvalues.array() != r.eigenvalues.array()).any());  // no NaN
  EXPECT_EQ(r.num_rigid_body_modes, 1);
  EXPECT_EQ(CountExactZeros(r.eigenvalues), 1);
  EXPECT_EQ(r.eigenvalues(0), 0.0);
  ASSERT_EQ(r.summary.warnings.size(), 1u);
  for (int j = 1; j < modes; ++j) {
    const double exact = FreeChainLambda(j, n, k, m);
    EXPECT_NEAR(r.eigenvalues(j), exact, kArpackTol * exact) << "j = " << j;
  }
  ExpectValidEigenpairs(MatrixX(p.K), MatrixX(p.M), r);
}

// The issue's size: lowest 20 of a 5 000-DOF free chain. Here λ_1 ≈ 2e-7·s lies below |σ| =
// 1e-6·s, so the rigid and lowest flexible modes crowd near ν = 1/|σ|: they must still converge,
// to closed-form accuracy, in a few dozen operator applications (time: see docs/benchmarks.md).
TEST(SymmetricEigenArpackTest, LowestTwentyOfFiveThousandDofs) {
  const int n = 5000, modes = 20;
  const double k = 4.4e8, m = 0.35;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/false);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, modes);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.num_rigid_body_modes, 1);
  EXPECT_EQ(r.eigenvalues(0), 0.0);
  // Shift-invert solves with K − σM, whose condition number is ≈ λ_max/|σ| = 4e6 here: the
  // computed λ carry a relative round-off of about ε·λ_max/|σ| ≈ 2e-10 on top of ARPACK's tol.
  const double lambda_max = 4.0 * k / m;
  const double tol = std::max(
      kArpackTol, 10.0 * std::numeric_limits<double>::epsilon() * lambda_max / std::abs(r.sigma));
  for (int j = 1; j < modes; ++j) {
    const double exact = FreeChainLambda(j, n, k, m);
    EXPECT_NEAR(r.eigenvalues(j), exact, tol * exact) << "j = " << j;
  }
  EXPECT_LT(r.eigenvalues(1), -r.sigma);
  EXPECT_LE(r.summary.counters.at("operator_applications"), 200);
}

TEST(SymmetricEigenArpackTest, ConsistentMassRodMatchesClosedForm) {
  const int N = 600, modes = 15;
  const double E = 2.1e11, rho = 7850.0, area = 3e-4, length = 0.8;
  const Pencil p = MakeConsistentRod(N, E, rho, area, length);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, modes);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  for (int j = 1; j <= modes; ++j) {
    const double exact = ConsistentRodLambda(j, N, E, rho, length);
    EXPECT_NEAR(r.eigenvalues(j - 1), exact, kArpackTol * exact) << "j = " << j;
  }
  ExpectValidEigenpairs(MatrixX(p.K), MatrixX(p.M), r);
}

// ARPACK against the dense solver (an independent algorithm: Cholesky + tridiagonal QR) on a
// 2 000-DOF random banded system with a rigid mode and a non-diagonal M.
TEST(SymmetricEigenArpackTest, AgreesWithDenseOnRandomBandedSystem) {
  const int n = 2000, modes = 20;
  const Pencil p = MakeRandomBanded(n, /*bandwidth=*/8, /*seed=*/20240611u);
  const MatrixX K(p.K), M(p.M);
  GeneralizedEigenOptions dense_options;
  dense_options.compute_vectors = false;
  const GeneralizedEigenResult dense = SolveGeneralizedEigenDense(K, M, dense_options);
  ASSERT_TRUE(dense.summary.ok()) << dense.summary.BriefReport();
  const GeneralizedEigenResult arpack = SolveGeneralizedEigenArpack(p.K, p.M, modes);
  ASSERT_TRUE(arpack.summary.ok()) << arpack.summary.BriefReport();
  EXPECT_EQ(dense.num_rigid_body_modes, 1);
  EXPECT_EQ(arpack.num_rigid_body_modes, 1);
  EXPECT_EQ(arpack.eigenvalues(0), 0.0);
  EXPECT_EQ(dense.eigenvalues(0), 0.0);
  double worst = 0.0;
  for (int j = 1; j < modes; ++j) {
    worst = std::max(worst,
                     std::abs(arpack.eigenvalues(j) - dense.eigenvalues(j)) / dense.eigenvalues(j));
  }
  EXPECT_LE(worst, 1e-9) << "worst relative difference of the lowest 20 eigenvalues";
  ExpectValidEigenpairs(K, M, arpack);
}

// A σ inside the spectrum: K − σM is indefinite (LU path) and ARPACK returns the eigenvalues
// nearest σ, ascending.
TEST(SymmetricEigenArpackTest, InteriorShiftReturnsTheNearestEigenvalues) {
  const int n = 200, modes = 8;
  const double k = 1.0e6, m = 1.0;
  const Pencil p = MakeChain(n, k, m, /*fixed_ends=*/true);
  const double sigma = 0.3 * FixedChainLambda(40, n, k, m) + 0.7 * FixedChainLambda(41, n, k, m);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, modes, sigma);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.sigma, sigma);
  EXPECT_EQ(r.summary.counters.at("factorizations"), 3);  // M, rejected LDLᵀ, LU
  std::vector<double> exact;
  for (int j = 1; j <= n; ++j) exact.push_back(FixedChainLambda(j, n, k, m));
  std::sort(exact.begin(), exact.end(),
            [sigma](double a, double b) { return std::abs(a - sigma) < std::abs(b - sigma); });
  exact.resize(modes);
  std::sort(exact.begin(), exact.end());
  for (int i = 0; i < modes; ++i) EXPECT_NEAR(r.eigenvalues(i), exact[i], kArpackTol * exact[i]);
  ExpectValidEigenpairs(MatrixX(p.K), MatrixX(p.M), r);
}

TEST(SymmetricEigenArpackTest, SingularShiftIsReportedNotThrown) {
  const Pencil p = MakeChain(50, 1.0e3, 1.0, /*fixed_ends=*/false);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, 5, 0.0);
  EXPECT_EQ(r.summary.status, Status::kNumericalIssue);
  EXPECT_NE(r.summary.message.find("singular"), std::string::npos) << r.summary.message;
  EXPECT_EQ(r.eigenvalues.size(), 0);
}

TEST(SymmetricEigenArpackTest, MaxIterationsOneIsNotConvergedNotAnAbort) {
  const int n = 2000, modes = 20;
  const Pencil p = MakeChain(n, 1.0e6, 1.0, /*fixed_ends=*/false);
  // One restart with the smallest Krylov space ARPACK accepts (ncv = num_modes + 1): far too
  // little to converge 20 modes (the default ncv = 41 converges this chain in two restarts).
  GeneralizedEigenOptions options;
  options.max_iterations = 1;
  options.num_lanczos_vectors = modes + 1;
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, modes, {}, options);
  EXPECT_EQ(r.summary.status, Status::kNotConverged);
  EXPECT_NE(r.summary.message.find("max_iterations = 1"), std::string::npos) << r.summary.message;
  EXPECT_NE(r.summary.message.find("info = 1"), std::string::npos) << r.summary.message;
  EXPECT_EQ(r.summary.counters.at("arpack_info"), 1);
  const long converged = r.summary.counters.at("converged");
  EXPECT_LT(converged, modes);
  EXPECT_EQ(r.eigenvalues.size(), converged);  // only the converged modes are returned
  EXPECT_TRUE(r.eigenvalues.allFinite());
  EXPECT_TRUE(r.vectors.allFinite());
}

TEST(SymmetricEigenArpackTest, StiffnessNotPsdIsANumericalIssue) {
  const int n = 100;
  const Pencil p = MakeChain(n, 1.0e4, 2.0, true);
  const double c = 0.5 * (FixedChainLambda(1, n, 1.0e4, 2.0) + FixedChainLambda(2, n, 1.0e4, 2.0));
  const SparseMatrix K = p.K - c * p.M;
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(K, p.M, 4);
  EXPECT_EQ(r.summary.status, Status::kNumericalIssue);
  EXPECT_NE(r.summary.message.find("not positive semidefinite"), std::string::npos)
      << r.summary.message;
  EXPECT_TRUE(r.eigenvalues.allFinite());
}

TEST(SymmetricEigenArpackTest, ResultsAreReproducibleAndVectorsOptional) {
  const Pencil p = MakeRandomBanded(500, 3, 7u);
  const GeneralizedEigenResult a = SolveGeneralizedEigenArpack(p.K, p.M, 10);
  const GeneralizedEigenResult b = SolveGeneralizedEigenArpack(p.K, p.M, 10);
  ASSERT_TRUE(a.summary.ok() && b.summary.ok());
  EXPECT_EQ(a.eigenvalues, b.eigenvalues);  // fixed start vector: bitwise identical
  EXPECT_EQ(a.vectors, b.vectors);
  GeneralizedEigenOptions options;
  options.compute_vectors = false;
  const GeneralizedEigenResult c = SolveGeneralizedEigenArpack(p.K, p.M, 10, {}, options);
  ASSERT_TRUE(c.summary.ok());
  EXPECT_EQ(c.vectors.size(), 0);
  EXPECT_LE((c.eigenvalues - a.eigenvalues).cwiseAbs().maxCoeff(),
            1e-12 * a.eigenvalues.cwiseAbs().maxCoeff());
}

// Two uncoupled identical chains: every eigenvalue of the fixed chain (closed form) is double.
// Lanczos from one start vector sees one direction of each two-dimensional eigenspace, so ARPACK
// can return each value once and the next ones in their place with info = 0. The truth: the
// lowest 2m eigenvalues are λ_1, λ_1, λ_2, λ_2, … Either ARPACK returns exactly those, or the
// inertia count (Sylvester) flags the result; never a wrong set with status success.
TEST(SymmetricEigenArpackTest, MissedRepeatedEigenvaluesAreFlaggedByTheInertiaCount) {
  const int n = 150, modes = 8;
  const double k = 3.7e5, m = 2.3;
  const Pencil one = MakeChain(n, k, m, /*fixed_ends=*/true);
  std::vector<Eigen::Triplet<double>> kt, mt;
  for (int copy = 0; copy < 2; ++copy) {
    for (int c = 0; c < n; ++c) {
      for (SparseMatrix::InnerIterator it(one.K, c); it; ++it) {
        kt.emplace_back(copy * n + it.row(), copy * n + it.col(), it.value());
      }
      for (SparseMatrix::InnerIterator it(one.M, c); it; ++it) {
        mt.emplace_back(copy * n + it.row(), copy * n + it.col(), it.value());
      }
    }
  }
  const SparseMatrix K = FromTriplets(2 * n, kt), M = FromTriplets(2 * n, mt);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(K, M, modes);
  ASSERT_EQ(r.summary.counters.count("inertia_count"), 1u) << r.summary.BriefReport();
  if (r.summary.status == Status::kSuccess) {
    ASSERT_EQ(r.eigenvalues.size(), modes);
    for (int i = 0; i < modes; ++i) {
      const double exact = FixedChainLambda(i / 2 + 1, n, k, m);
      EXPECT_NEAR(r.eigenvalues(i), exact, kArpackTol * exact) << "i = " << i;
    }
  } else {
    EXPECT_EQ(r.summary.status, Status::kNumericalIssue);
    EXPECT_GT(r.summary.counters.at("missed_eigenvalues"), 0);
    EXPECT_NE(r.summary.message.find("Lanczos missed"), std::string::npos) << r.summary.message;
  }
}

// A triple eigenvalue cut by the requested count (lowest 8 of 1,1,1,2,2,2,3,3,3,… ×10⁶, M = I:
// the closed form of a diagonal pencil) is a legitimate truncation: success, not a "miss".
TEST(SymmetricEigenArpackTest, RepeatedEigenvalueAtTheEdgeOfTheSetIsNotAMiss) {
  const int n = 300, modes = 8;
  std::vector<Eigen::Triplet<double>> kt, mt;
  for (int i = 0; i < n; ++i) {
    kt.emplace_back(i, i, 1e6 * (1 + i / 3));
    mt.emplace_back(i, i, 1.0);
  }
  const GeneralizedEigenResult r =
      SolveGeneralizedEigenArpack(FromTriplets(n, kt), FromTriplets(n, mt), modes);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_EQ(r.eigenvalues.size(), modes);
  for (int i = 0; i < modes; ++i) {
    EXPECT_NEAR(r.eigenvalues(i), 1e6 * (1 + i / 3), kArpackTol * 1e6 * 3) << "i = " << i;
  }
}

// The inertia count agrees with the closed form when nothing is repeated: success, and the count
// equals the number of modes returned.
TEST(SymmetricEigenArpackTest, InertiaCountEqualsTheModesReturnedWithoutRepeats) {
  const int n = 300, modes = 12;
  const Pencil p = MakeChain(n, 2.0e6, 1.5, /*fixed_ends=*/true);
  for (const bool shifted : {false, true}) {
    const std::optional<double> sigma =
        shifted ? std::optional<double>(0.5 * (FixedChainLambda(40, n, 2.0e6, 1.5) +
                                               FixedChainLambda(41, n, 2.0e6, 1.5)))
                : std::nullopt;
    const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, modes, sigma);
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    // The strict interior of the window holds every returned value but the farthest.
    EXPECT_EQ(r.summary.counters.at("inertia_count"), modes - 1) << "shifted = " << shifted;
  }
}

#else  // !GEARDYN_WITH_ARPACK

TEST(SymmetricEigenArpackTest, UnavailableWithoutArpack) {
  const Pencil p = MakeChain(30, 1.0, 1.0, true);
  const GeneralizedEigenResult r = SolveGeneralizedEigenArpack(p.K, p.M, 5);
  EXPECT_EQ(r.summary.status, Status::kNumericalIssue);
  EXPECT_EQ(r.summary.message, "ARPACK unavailable (built with GEARDYN_WITH_ARPACK=OFF)");
  EXPECT_EQ(r.eigenvalues.size(), 0);
}

#endif  // GEARDYN_WITH_ARPACK

// Input checks come before the ARPACK availability check: the same with and without ARPACK.
TEST(SymmetricEigenArpackTest, RejectsBadInputNamingTheArgument) {
  const Pencil p = MakeChain(10, 1.0, 1.0, true);
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(p.K, p.M, 10), InvalidInput,
                        "num_modes: must be in \\[1, n − 1\\] = \\[1, 9\\], got 10");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(p.K, p.M, 0), InvalidInput, "num_modes");
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(p.K, p.M, 3, std::nan("")), InvalidInput,
                        "sigma: must be finite");
  GeneralizedEigenOptions options;
  options.num_lanczos_vectors = 3;
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(p.K, p.M, 3, {}, options), InvalidInput,
                        "num_lanczos_vectors: must be in \\(num_modes, n\\] = \\(3, 10\\], got 3");
  options = {};
  options.max_iterations = 0;
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(p.K, p.M, 3, {}, options), InvalidInput,
                        "GeneralizedEigenOptions.max_iterations: must be ≥ 1, got 0");
  const Pencil q = MakeChain(11, 1.0, 1.0, true);
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(p.K, q.M, 3), InvalidInput,
                        "M \\(rows, must match K\\): size 11 .* 10");
  const SparseMatrix rect = MatrixX::Ones(10, 9).sparseView();
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(rect, p.M, 3), InvalidInput,
                        "K: must be square");
  // M symmetric with a positive diagonal but indefinite: [[1, 2], [2, 1]] blocks.
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 10; i += 2) {
    t.emplace_back(i, i, 1.0), t.emplace_back(i + 1, i + 1, 1.0);
    t.emplace_back(i, i + 1, 2.0), t.emplace_back(i + 1, i, 2.0);
  }
  const SparseMatrix indefinite = FromTriplets(10, t);
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(p.K, indefinite, 3), InvalidInput,
                        "M: not positive definite");
  SparseMatrix asymmetric = p.K;
  asymmetric.coeffRef(0, 1) += 0.5;
  EXPECT_THROWS_MESSAGE(SolveGeneralizedEigenArpack(asymmetric, p.M, 3), InvalidInput,
                        "K: not symmetric");
}

}  // namespace
}  // namespace geardyn
