/// @file
/// @brief The exact (large-motion) approach of a mesh's material contact point, computed
/// geometrically: the truth the mesh Jacobian tests differentiate (parallel-axis and bevel).
#pragma once

#include <Eigen/Geometry>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"

namespace geardyn::test {

/// The finite rotation exp([θ×]) of a rotation vector θ [rad].
inline Matrix3 RotationFromVector(const Vector3& theta) {
  const double angle = theta.norm();
  if (angle == 0.0) return Matrix3::Identity();
  return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

/// Exact approach at the contact-line point x0 = p0 + σ σ̂ after the rigid displacements q =
/// [t_i, θ_i, t_j, θ_j]: each body carries its material point x0 and its flank normal η rigidly
/// (finite rotation about its centre, then translation); the approach is the pinion point minus
/// the gear point along the mean of the two carried normals. Independent of CalcMeshJacobian's
/// formulas.
inline double ExactMaterialApproach(const MeshFrame& f, const Vector12& q, double sigma) {
  const Vector3 x0 = f.reference_point + sigma * f.sigma;
  const Matrix3 R_i = RotationFromVector(q.segment<3>(3));
  const Matrix3 R_j = RotationFromVector(q.segment<3>(9));
  const Vector3 x_i = f.pinion_center + q.segment<3>(0) + R_i * (x0 - f.pinion_center);
  const Vector3 x_j = f.gear_center + q.segment<3>(6) + R_j * (x0 - f.gear_center);
  const Vector3 n = (R_i * f.eta + R_j * f.eta).normalized();
  return n.dot(x_i - x_j);
}

}  // namespace geardyn::test
