/// @file
/// @brief CompareMatrices / EXPECT_MATRIX_NEAR: relative matrix comparison that names the worst
/// entry (Drake's CompareMatrices).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <sstream>

namespace geardyn::test {

enum class MatrixCompareType { kAbsolute, kRelative };

/// Passes when max|a−b| ≤ tol (kAbsolute) or ≤ tol·max(1, max|a|, max|b|) (kRelative).
template <typename DerivedA, typename DerivedB>
::testing::AssertionResult CompareMatrices(const Eigen::MatrixBase<DerivedA>& a,
                                           const Eigen::MatrixBase<DerivedB>& b, double tol,
                                           MatrixCompareType type = MatrixCompareType::kRelative) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure() << "size mismatch: " << a.rows() << "x" << a.cols()
                                         << " vs " << b.rows() << "x" << b.cols();
  }
  double scale = 1.0;
  if (type == MatrixCompareType::kRelative && a.size() > 0) {
    scale = std::max({1.0, a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff()});
  }
  Eigen::Index worst_r = 0, worst_c = 0;
  double worst = 0.0;
  for (Eigen::Index c = 0; c < a.cols(); ++c) {
    for (Eigen::Index r = 0; r < a.rows(); ++r) {
      const double d = std::abs(a(r, c) - b(r, c));
      if (!(d <= worst) || d != d) {
        worst = d;
        worst_r = r;
        worst_c = c;
      }
    }
  }
  if (worst <= tol * scale) return ::testing::AssertionSuccess();
  std::ostringstream out;
  out << "worst entry (" << worst_r << ", " << worst_c << "): " << a(worst_r, worst_c) << " vs "
      << b(worst_r, worst_c) << ", difference " << worst << " > " << tol * scale;
  return ::testing::AssertionFailure() << out.str();
}

}  // namespace geardyn::test

#define EXPECT_MATRIX_NEAR(a, b, tol) EXPECT_TRUE(::geardyn::test::CompareMatrices((a), (b), (tol)))
