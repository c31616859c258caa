// Bearings: TᵀK_bT with the rigid-transfer map T of rigid_transfer.hpp (see bearing.hpp).
#include "geardyn/models/elements/bearing.hpp"

#include <cmath>

#include "elements/element_checks.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/models/elements/rigid_transfer.hpp"

namespace geardyn {
namespace {

void CheckCoefficients(const Matrix6& coefficients) {
  internal::CheckSymmetricSemiDefinite(coefficients, /*definite=*/false, "coefficients",
                                       "[N/m, N*m/rad]");
}

}  // namespace

Matrix6 CalcDiagonalBearingMatrix(const Vector6& diagonal) {
  for (int i = 0; i < 6; ++i) {
    GEARDYN_THROW_UNLESS(std::isfinite(diagonal(i)) && diagonal(i) >= 0.0,
                         "diagonal(" << i << "): must be non-negative and finite, got "
                                     << diagonal(i) << (i < 3 ? " N/m" : " N*m/rad"));
  }
  return diagonal.asDiagonal();
}

Matrix6 CalcAxisymmetricBearingMatrix(double radial, double axial, double tilt, double torsional,
                                      const Vector3& axis) {
  internal::CheckNonNegative(radial, "radial", "N/m");
  internal::CheckNonNegative(axial, "axial", "N/m");
  internal::CheckNonNegative(tilt, "tilt", "N*m/rad");
  internal::CheckNonNegative(torsional, "torsional", "N*m/rad");
  internal::CheckUnitAxis(axis, "axis");
  const Vector3 a = axis.normalized();
  const Matrix3 along = a * a.transpose();             // projector on the axis
  const Matrix3 across = Matrix3::Identity() - along;  // projector on the radial plane
  Matrix6 K = Matrix6::Zero();
  K.topLeftCorner<3, 3>() = radial * across + axial * along;
  K.bottomRightCorner<3, 3>() = tilt * across + torsional * along;
  return K;
}

Matrix6 CalcGroundedBearingMatrix(const Matrix6& coefficients, const Vector3& point,
                                  const Vector3& center) {
  CheckCoefficients(coefficients);
  const Matrix6 T = CalcRigidTransferMap(point, center);
  Matrix6 K = T.transpose() * coefficients * T;
  return 0.5 * (K + K.transpose());  // exact symmetry despite rounding
}

Matrix12 CalcBearingMatrix(const Matrix6& coefficients, const Vector3& point,
                           const Vector3& center_a, const Vector3& center_b) {
  CheckCoefficients(coefficients);
  const Matrix6x12 T = CalcRelativeTransferMap(point, center_a, center_b);
  Matrix12 K = T.transpose() * coefficients * T;
  return 0.5 * (K + K.transpose());
}

}  // namespace geardyn
