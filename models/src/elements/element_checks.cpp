// Input checks shared by the element library (see element_checks.hpp).
#include "elements/element_checks.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "geardyn/common/check.hpp"

namespace geardyn::internal {
namespace {

// Relative symmetry tolerance: entries of a symmetric input differ by a few roundings at most.
constexpr double kSymmetryTolerance = 1e-12;
// Smallest eigenvalue of the Jacobi-scaled matrix (diagonal ≈ 1) still accepted as ≥ 0.
constexpr double kSemiDefiniteTolerance = 1e-10;

Eigen::IOFormat RowFormat() {
  return Eigen::IOFormat(Eigen::StreamPrecision, Eigen::DontAlignCols, ", ", "; ", "", "", "[",
                         "]");
}

template <int N>
void CheckMatrix(const Eigen::Matrix<double, N, N>& a, bool definite, std::string_view name,
                 std::string_view unit) {
  GEARDYN_THROW_UNLESS(a.allFinite(),
                       name << ": must be finite, got " << a.format(RowFormat()) << " " << unit);
  const double scale = a.cwiseAbs().maxCoeff();
  const double asymmetry = (a - a.transpose()).cwiseAbs().maxCoeff();
  GEARDYN_THROW_UNLESS(asymmetry <= kSymmetryTolerance * scale,
                       name << ": must be symmetric, got " << a.format(RowFormat()) << " " << unit
                            << " (max |A - A^T| = " << asymmetry << ")");
  // Jacobi scaling makes the test independent of the units of each row.
  Eigen::Matrix<double, N, 1> s;
  for (int i = 0; i < N; ++i) s(i) = a(i, i) > 0.0 ? 1.0 / std::sqrt(a(i, i)) : 1.0;
  const Eigen::Matrix<double, N, N> scaled = s.asDiagonal() * a * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(
      0.5 * (scaled + scaled.transpose()), Eigen::EigenvaluesOnly);
  const double smallest = eig.eigenvalues().minCoeff();
  const double bound = kSemiDefiniteTolerance * std::max(1.0, eig.eigenvalues().maxCoeff());
  if (definite) {
    GEARDYN_THROW_UNLESS(smallest > bound,
                         name << ": must be positive definite, got " << a.format(RowFormat()) << " "
                              << unit << " (smallest scaled eigenvalue " << smallest << ")");
  } else {
    GEARDYN_THROW_UNLESS(smallest >= -bound,
                         name << ": must be positive semi-definite, got " << a.format(RowFormat())
                              << " " << unit << " (smallest scaled eigenvalue " << smallest << ")");
  }
}

}  // namespace

void CheckPositive(double value, std::string_view name, std::string_view unit) {
  GEARDYN_THROW_UNLESS(std::isfinite(value) && value > 0.0,
                       name << ": must be positive and finite, got " << value << " " << unit);
}

void CheckNonNegative(double value, std::string_view name, std::string_view unit) {
  GEARDYN_THROW_UNLESS(std::isfinite(value) && value >= 0.0,
                       name << ": must be non-negative and finite, got " << value << " " << unit);
}

void CheckFinite(const Vector3& v, std::string_view name, std::string_view unit) {
  GEARDYN_THROW_UNLESS(v.allFinite(), name << ": must be finite, got (" << v.x() << ", " << v.y()
                                           << ", " << v.z() << ") " << unit);
}

void CheckUnitAxis(const Vector3& axis, std::string_view name) {
  const double norm = axis.norm();
  GEARDYN_THROW_UNLESS(axis.allFinite() && std::abs(norm - 1.0) <= kUnitAxisTolerance,
                       name << ": must be a unit vector, got (" << axis.x() << ", " << axis.y()
                            << ", " << axis.z() << ") with norm " << norm);
}

void CheckSymmetricSemiDefinite(const Matrix3& matrix, bool definite, std::string_view name,
                                std::string_view unit) {
  CheckMatrix<3>(matrix, definite, name, unit);
}

void CheckSymmetricSemiDefinite(const Matrix6& matrix, bool definite, std::string_view name,
                                std::string_view unit) {
  CheckMatrix<6>(matrix, definite, name, unit);
}

}  // namespace geardyn::internal
