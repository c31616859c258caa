// The mesh Jacobian G (spec 01 §3) and B–S's scaled relative-displacement map (B–S Eq. 41d).
#include "geardyn/models/mesh/mesh_jacobian.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "geardyn/common/check.hpp"
#include "geardyn/models/mesh/stiffness_core.hpp"

namespace geardyn {

Matrix2x12 CalcMeshJacobian(const MeshFrame& frame) {
  Matrix2x12 G = Matrix2x12::Zero();
  // δ_η = η·(t_i − t_j) + θ_i·(r_i × η) − θ_j·(r_j × η)   (spec 01 §3)
  G.block<1, 3>(0, 0) = frame.eta.transpose();
  G.block<1, 3>(0, 3) = frame.pinion_lever_arm.cross(frame.eta).transpose();
  G.block<1, 3>(0, 6) = -frame.eta.transpose();
  G.block<1, 3>(0, 9) = -frame.gear_lever_arm.cross(frame.eta).transpose();
  // δ_ζ = ζ·(θ_i − θ_j)
  G.block<1, 3>(1, 3) = frame.zeta.transpose();
  G.block<1, 3>(1, 9) = -frame.zeta.transpose();
  return G;
}

Matrix6x12 CalcBsRelativeDisplacementMap(const MeshFrame& frame, double half_face_width) {
  GEARDYN_THROW_UNLESS(
      std::isfinite(half_face_width) && half_face_width > 0.0,
      "half_face_width: must be positive and finite, got " << half_face_width << " m");
  const double b = half_face_width;
  const double s = static_cast<double>(frame.drive_sign);
  const double mate = frame.internal ? -1.0 : 1.0;  // ⊕ of B–S Eq. (22)
  const double a_i = frame.pinion_base_radius;
  const double a_j = frame.gear_base_radius;
  Matrix6x12 T = Matrix6x12::Zero();
  // Relative translation of the centres in the mesh frame, W = [u v w] (B–S Eq. 41d rows 1–3).
  T.block<1, 3>(0, 0) = frame.u.transpose();
  T.block<1, 3>(1, 0) = frame.v.transpose();
  T.block<1, 3>(2, 0) = frame.w.transpose();
  T.block<3, 3>(0, 6) = -T.block<3, 3>(0, 0);
  // Rocking: −b δ_ζ (B–S's δ_ζ has the opposite sign of ours, see the header).
  T.block<1, 3>(3, 3) = -b * frame.u.transpose();
  T.block<1, 3>(3, 9) = b * frame.u.transpose();
  // Tilt about v and torsion about w, arms a (B–S Eq. 24), pseudo-vector sign s = det W.
  T.block<1, 3>(4, 3) = s * a_i * frame.v.transpose();
  T.block<1, 3>(4, 9) = s * mate * a_j * frame.v.transpose();
  T.block<1, 3>(5, 3) = s * a_i * frame.w.transpose();
  T.block<1, 3>(5, 9) = s * mate * a_j * frame.w.transpose();
  return T;
}

Matrix2x12 CalcBsProjectedJacobian(const MeshFrame& frame, double half_face_width) {
  const Matrix6x12 T = CalcBsRelativeDisplacementMap(frame, half_face_width);
  const double psi = frame.signed_helix_angle;
  return CalcBsDeflectionProjection(std::cos(psi), std::sin(psi), half_face_width) * T;
}

}  // namespace geardyn
