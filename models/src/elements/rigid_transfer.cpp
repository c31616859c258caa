// Rigid-transfer maps (see rigid_transfer.hpp): u_p = t + θ × (p − c).
#include "geardyn/models/elements/rigid_transfer.hpp"

#include "elements/element_checks.hpp"

namespace geardyn {

Matrix3 CalcCrossProductMatrix(const Vector3& v) {
  Matrix3 s;
  s << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return s;
}

Matrix6 CalcRigidTransferMap(const Vector3& point, const Vector3& center) {
  internal::CheckFinite(point, "point", "m");
  internal::CheckFinite(center, "center", "m");
  Matrix6 T = Matrix6::Identity();
  // θ × r = −r × θ = −[r]_× θ
  T.block<3, 3>(0, 3) = -CalcCrossProductMatrix(point - center);
  return T;
}

Matrix6x12 CalcRelativeTransferMap(const Vector3& point, const Vector3& center_a,
                                   const Vector3& center_b) {
  internal::CheckFinite(point, "point", "m");
  internal::CheckFinite(center_a, "center_a", "m");
  internal::CheckFinite(center_b, "center_b", "m");
  Matrix6x12 T;
  T.leftCols<6>() = CalcRigidTransferMap(point, center_a);
  T.rightCols<6>() = -CalcRigidTransferMap(point, center_b);
  return T;
}

}  // namespace geardyn
