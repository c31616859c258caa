// The tangent stiffness of a preloaded involute mesh (mesh_preload_stiffness.hpp).
#include "geardyn/models/mesh/mesh_preload_stiffness.hpp"

#include <cmath>

#include "geardyn/common/check.hpp"

namespace geardyn {

double CalcMeshPreloadCoefficient(const MeshFrame& frame, double normal_force) {
  GEARDYN_THROW_UNLESS(
      std::isfinite(normal_force),
      "mesh preload: the static mesh force is not finite (" << normal_force << " N)");
  if (frame.rack) return 0.0;  // the rack's flank plane keeps its direction: L → ∞
  // L_s = (c_j − c_i)·v: +C sin φ external, −C sin φ internal (the transverse part only: v ⊥ Z).
  const double signed_length = (frame.gear_center - frame.pinion_center).dot(frame.v);
  return -normal_force * std::cos(frame.base_helix_angle) / signed_length;
}

Matrix12 CalcMeshPreloadStiffness(const MeshFrame& frame, double normal_force) {
  const double kappa = CalcMeshPreloadCoefficient(frame, normal_force);
  Vector12 b = Vector12::Zero();
  b.segment<3>(0) = -frame.u;
  b.segment<3>(6) = frame.u;
  const Matrix12 outer = b * b.transpose();  // b_i b_j = b_j b_i: exactly symmetric
  return kappa * outer;
}

}  // namespace geardyn
