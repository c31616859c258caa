/// @file
/// @brief Test pencils (K, M) with known spectra for the generalized symmetric eigen solvers:
/// spring–mass chains (closed form in symmetric_eigen_test.cpp's file comment) and a seeded
/// random banded floating system (one rigid mode).
#pragma once

#include <random>
#include <vector>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn::test {

struct Pencil {
  SparseMatrix K;  // [N/m]
  SparseMatrix M;  // [kg]
};

inline void AddSpring(std::vector<Eigen::Triplet<double>>* t, int i, int j, double k) {
  t->emplace_back(i, i, k);
  t->emplace_back(j, j, k);
  t->emplace_back(i, j, -k);
  t->emplace_back(j, i, -k);
}

inline SparseMatrix FromTriplets(int n, const std::vector<Eigen::Triplet<double>>& t) {
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}

/// Chain of n masses m [kg] and springs k [N/m]; fixed ends add a ground spring at both ends.
inline Pencil MakeChain(int n, double k, double m, bool fixed_ends) {
  std::vector<Eigen::Triplet<double>> kt, mt;
  for (int i = 0; i + 1 < n; ++i) AddSpring(&kt, i, i + 1, k);
  if (fixed_ends) {
    kt.emplace_back(0, 0, k);
    kt.emplace_back(n - 1, n - 1, k);
  }
  for (int i = 0; i < n; ++i) mt.emplace_back(i, i, m);
  return {FromTriplets(n, kt), FromTriplets(n, mt)};
}

/// Seeded random banded system with one rigid mode: springs k·U(0.5, 1.5) [N/m] between every
/// pair at distance 1..bandwidth (connected, floating: K·1 = 0), lumped masses m·U(0.5, 2) plus a
/// consistent coupling μ/6·[2 1; 1 2] between neighbours [kg] (M banded SPD).
inline Pencil MakeRandomBanded(int n, int bandwidth, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double k = 2.0e7, m = 1.5;
  std::vector<Eigen::Triplet<double>> kt, mt;
  for (int i = 0; i < n; ++i) {
    for (int d = 1; d <= bandwidth && i + d < n; ++d)
      AddSpring(&kt, i, i + d, k * (0.5 + unit(rng)));
  }
  for (int i = 0; i < n; ++i) mt.emplace_back(i, i, m * (0.5 + 1.5 * unit(rng)));
  for (int i = 0; i + 1 < n; ++i) {
    const double mu = 0.3 * m * unit(rng) / 6.0;
    mt.emplace_back(i, i, 2.0 * mu);
    mt.emplace_back(i + 1, i + 1, 2.0 * mu);
    mt.emplace_back(i, i + 1, mu);
    mt.emplace_back(i + 1, i, mu);
  }
  return {FromTriplets(n, kt), FromTriplets(n, mt)};
}

}  // namespace geardyn::test
