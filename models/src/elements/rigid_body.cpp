// Rigid-body mass matrix about a reference node offset from the centre of mass (see
// rigid_body.hpp for the derivation from the kinetic energy).
#include "geardyn/models/elements/rigid_body.hpp"

#include "elements/element_checks.hpp"
#include "geardyn/models/elements/rigid_transfer.hpp"

namespace geardyn {

Matrix3 CalcAxisymmetricInertiaTensor(const RigidBodyInertia& body) {
  internal::CheckPositive(body.polar_inertia, "polar_inertia", "kg*m^2");
  internal::CheckPositive(body.diametral_inertia, "diametral_inertia", "kg*m^2");
  internal::CheckUnitAxis(body.axis, "axis");
  const Vector3 a = body.axis.normalized();
  const Matrix3 along = a * a.transpose();
  return body.polar_inertia * along + body.diametral_inertia * (Matrix3::Identity() - along);
}

Matrix6 CalcRigidBodyMassMatrix(const RigidBodyInertia& body) {
  internal::CheckPositive(body.mass, "mass", "kg");
  return CalcRigidBodyMassMatrix(body.mass, CalcAxisymmetricInertiaTensor(body), body.com_offset);
}

Matrix6 CalcRigidBodyMassMatrix(double mass, const Matrix3& inertia_at_com,
                                const Vector3& com_offset) {
  internal::CheckPositive(mass, "mass", "kg");
  internal::CheckSymmetricSemiDefinite(inertia_at_com, /*definite=*/true, "inertia_at_com",
                                       "kg*m^2");
  internal::CheckFinite(com_offset, "com_offset", "m");
  const Matrix3 S = CalcCrossProductMatrix(com_offset);  // [r]_×
  Matrix6 M;
  // v_G = ṫ − [r]_× θ̇ ⇒ T = ½ m |ṫ − [r]_× θ̇|² + ½ θ̇ᵀ I_G θ̇
  M.topLeftCorner<3, 3>() = mass * Matrix3::Identity();
  M.topRightCorner<3, 3>() = -mass * S;
  M.bottomLeftCorner<3, 3>() = mass * S;  // (−m [r]_×)ᵀ = m [r]_×
  // Parallel-axis theorem: I_c = I_G + m (|r|² I − r rᵀ) = I_G + m [r]_×ᵀ [r]_×.
  const Matrix3 I_c = inertia_at_com + mass * (S.transpose() * S);
  M.bottomRightCorner<3, 3>() = 0.5 * (I_c + I_c.transpose());
  return M;
}

}  // namespace geardyn
