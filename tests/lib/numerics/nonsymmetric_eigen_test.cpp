// Tests of geardyn/numerics/nonsymmetric_eigen.hpp (ARPACK dnaupd/dneupd, largest |θ|) against a
// matrix built with a known spectrum: A = S B S⁻¹ with B block diagonal — 2×2 rotation–scaling
// blocks r[cos φ, −sin φ; sin φ, cos φ] (eigenvalues r e^{±iφ}) and real 1×1 blocks — and S a
// fixed, well-conditioned random matrix (I + 0.3·uniform(−1, 1)/√n). The nev largest eigenvalues
// are the chosen ones; the Ritz pairs must also satisfy ‖Av − θv‖ ≤ tol·|θ|·‖A‖-ish.
#include "geardyn/numerics/nonsymmetric_eigen.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

namespace geardyn {
namespace {

using C = std::complex<double>;

struct KnownSpectrum {
  MatrixX a;
  std::vector<C> largest;  // the eigenvalues of largest modulus, in decreasing |λ|
};

KnownSpectrum Build(int n) {
  MatrixX b = MatrixX::Zero(n, n);
  std::vector<C> all;
  auto rotation = [&](int i, double r, double phi) {
    b(i, i) = b(i + 1, i + 1) = r * std::cos(phi);
    b(i, i + 1) = -r * std::sin(phi);
    b(i + 1, i) = r * std::sin(phi);
    all.push_back(std::polar(r, phi));
    all.push_back(std::polar(r, -phi));
  };
  rotation(0, 0.95, 0.3);
  rotation(2, 0.85, 1.1);
  b(4, 4) = -0.75;
  all.push_back(-0.75);
  // The rest well below: |λ| ≤ 0.5.
  for (int i = 5; i < n; ++i) {
    b(i, i) = 0.5 * std::cos(0.37 * i);
    all.push_back(b(i, i));
  }
  std::mt19937 rng(20261121);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  MatrixX s = MatrixX::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) s(i, j) += 0.3 * uniform(rng) / std::sqrt(double(n));
  }
  KnownSpectrum k;
  k.a = s * b * s.inverse();
  std::sort(all.begin(), all.end(), [](C x, C y) { return std::abs(x) > std::abs(y); });
  k.largest.assign(all.begin(), all.begin() + 5);
  return k;
}

/// ARPACK on y = A x.
ArnoldiOutcome Arnoldi(const MatrixX& a, int nev, int ncv, double tol, int max_iterations) {
  const int n = static_cast<int>(a.rows());
  const auto apply = [&](const double* x, double* y) {
    Eigen::Map<VectorX>(y, n) = a * Eigen::Map<const VectorX>(x, n);
  };
  return RunArnoldiLargestMagnitude(apply, n, nev, ncv, tol, max_iterations);
}

TEST(NonsymmetricEigen, LargestEigenvaluesOfAMatrixWithKnownSpectrum) {
#if !defined(GEARDYN_WITH_ARPACK)
  GTEST_SKIP() << "built without ARPACK";
#endif
  const KnownSpectrum k = Build(80);
  const ArnoldiOutcome out = Arnoldi(k.a, 5, 20, 1e-12, 300);
  ASSERT_TRUE(out.ok) << out.message;
  ASSERT_GE(out.num_converged, 5);
  EXPECT_GT(out.applications, 0);
  for (const C& expected : k.largest) {
    double best = 1e300;
    for (Eigen::Index j = 0; j < out.values.size(); ++j) {
      best = std::min(best, std::abs(out.values[j] - expected));
    }
    EXPECT_LT(best, 1e-10) << "eigenvalue " << expected;
  }
  const double norm_a = k.a.norm();
  for (Eigen::Index j = 0; j < out.values.size(); ++j) {
    const VectorXc v = out.vectors.col(j);
    const VectorXc r = k.a.cast<C>() * v - out.values[j] * v;
    EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    EXPECT_LT(r.norm(), 1e-10 * norm_a) << "Ritz pair " << j;
  }
}

TEST(NonsymmetricEigen, IterationLimitIsReportedNotFatal) {
#if !defined(GEARDYN_WITH_ARPACK)
  GTEST_SKIP() << "built without ARPACK";
#endif
  // One restart with a minimal basis cannot converge five pairs to 1e-14.
  const ArnoldiOutcome out = Arnoldi(Build(80).a, 5, 7, 1e-14, 1);
  EXPECT_LT(out.num_converged, 5);
  EXPECT_FALSE(out.message.empty());
}

}  // namespace
}  // namespace geardyn
