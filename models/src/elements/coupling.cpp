// Torsional couplings and grounded torsional springs (see coupling.hpp): k gᵀg.
#include "geardyn/models/elements/coupling.hpp"

#include "elements/element_checks.hpp"

namespace geardyn {

Matrix12 CalcTorsionalCouplingMatrix(double coefficient, const Vector3& axis) {
  internal::CheckNonNegative(coefficient, "coefficient", "N*m/rad");
  internal::CheckUnitAxis(axis, "axis");
  const Vector3 a = axis.normalized();
  Vector12 g = Vector12::Zero();  // δ = a·(θ_A − θ_B)
  g.segment<3>(3) = a;
  g.segment<3>(9) = -a;
  return coefficient * g * g.transpose();
}

Matrix6 CalcGroundedTorsionalSpringMatrix(double coefficient, const Vector3& axis) {
  internal::CheckNonNegative(coefficient, "coefficient", "N*m/rad");
  internal::CheckUnitAxis(axis, "axis");
  const Vector3 a = axis.normalized();
  Matrix6 K = Matrix6::Zero();
  K.bottomRightCorner<3, 3>() = coefficient * a * a.transpose();
  return K;
}

}  // namespace geardyn
