// The mesh frame of a straight bevel pair (bevel_mesh_frame.hpp).
#include "geardyn/models/mesh/bevel_mesh_frame.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn {
namespace {

void CheckUnitAxis(const Vector3& a, const char* field) {
  GEARDYN_THROW_UNLESS(a.allFinite(), field << ": must be finite");
  GEARDYN_THROW_UNLESS(std::abs(a.norm() - 1.0) <= kUnitAxisTol,
                       field << ": must be a unit vector, its norm is " << a.norm());
}

}  // namespace

BevelMeshFrame CalcBevelMeshFrame(const BevelPairGeometry& g, const BevelPlacement& placement) {
  GEARDYN_THROW_UNLESS(placement.apex.allFinite(), "apex: must be finite");
  CheckUnitAxis(placement.pinion_axis, "pinion_axis");
  CheckUnitAxis(placement.gear_axis, "gear_axis");
  GEARDYN_THROW_UNLESS(placement.drive_sign == 1 || placement.drive_sign == -1,
                       "drive_sign: must be +1 or -1, got " << placement.drive_sign);
  const Vector3& a_i = placement.pinion_axis;
  const Vector3& a_j = placement.gear_axis;
  // The angle between the axes, robust at small angles (atan2 of |a × b| and a·b).
  const double sigma = std::atan2(a_i.cross(a_j).norm(), a_i.dot(a_j));
  GEARDYN_THROW_UNLESS(std::abs(sigma - g.spec.shaft_angle) <= kShaftAngleTol,
                       "gear_axis: the axes make " << RadToDeg(sigma)
                                                   << " deg, the pair's shaft angle is "
                                                   << RadToDeg(g.spec.shaft_angle) << " deg");
  const double d1 = g.pinion_cone_angle, d2 = g.gear_cone_angle, R_m = g.mean_cone_distance;
  // p̂ at δ1 from a_i towards a_j in their plane (spherical interpolation, exact unit length).
  const Vector3 p_hat =
      ((std::sin(sigma - d1) * a_i + std::sin(d1) * a_j) / std::sin(sigma)).normalized();
  const Vector3 P = placement.apex + R_m * p_hat;
  const Vector3 c_i = placement.apex + R_m * std::cos(d1) * a_i;
  const Vector3 c_j = placement.apex + R_m * std::cos(d2) * a_j;
  const Vector3 r_i = P - c_i;
  // ê: normal to p̂ in the axial plane, from the pinion's axis towards the gear's.
  const Vector3 e_hat = (r_i - r_i.dot(p_hat) * p_hat).normalized();
  const Vector3 tangent = a_i.cross(r_i).normalized();
  // ẑ_v = ±p̂ with (ẑ_v × ê) along the velocity a_i × r_i of a positive pinion rotation.
  const Vector3 z_v = p_hat.cross(e_hat).dot(tangent) > 0.0 ? p_hat : Vector3(-p_hat);
  const Vector3 e_perp = z_v.cross(e_hat);
  const double s = static_cast<double>(placement.drive_sign);
  const double alpha = g.spec.pressure_angle;

  BevelMeshFrame out;
  MeshFrame& f = out.frame;
  f.u = std::cos(alpha) * e_hat - s * std::sin(alpha) * e_perp;
  f.v = std::sin(alpha) * e_hat + s * std::cos(alpha) * e_perp;
  f.w = z_v;
  f.zeta = f.u;
  f.eta = f.v;
  f.sigma = f.zeta.cross(f.eta);
  f.reference_point = P;
  f.pinion_center = c_i;
  f.gear_center = c_j;
  f.pinion_lever_arm = r_i;
  f.gear_lever_arm = P - c_j;
  f.pinion_base_radius = g.pinion_virtual_base_radius;
  f.gear_base_radius = g.gear_virtual_base_radius;
  f.center_distance = g.virtual_center_distance;
  f.operating_pressure_angle = alpha;
  f.base_helix_angle = 0.0;
  f.signed_helix_angle = 0.0;
  f.drive_sign = placement.drive_sign;
  f.internal = false;
  f.rack = false;
  out.apex = placement.apex;
  out.pinion_axis = a_i;
  out.gear_axis = a_j;
  out.cone_element = p_hat;
  out.pitch_tangent = tangent;
  return out;
}

}  // namespace geardyn
