/// @file
/// @brief The mesh frame of a straight bevel pair (issue 19): the B–S interface derived at the
/// mean point of the face, for two gears on intersecting axes at any shaft angle. The result is a
/// MeshFrame, so the mesh Jacobian G (CalcMeshJacobian: δ_η = η·(t_i − t_j) + θ_i·(r_i × η) −
/// θ_j·(r_j × η), δ_ζ = ζ·(θ_i − θ_j)) and everything built on it read it unchanged.
///
/// **Placement.** The apex O (where the axes meet), the unit axes a_i, a_j of pinion and gear,
/// each pointing from the apex towards its gear's heel, at the angle Σ of the pair. The cone
/// element of contact is p̂ = (sin(Σ − δ₁) a_i + sin δ₁ a_j) / sin Σ (at δ₁ from a_i, δ₂ from
/// a_j), the mean point P = O + R_m p̂, and each body's reference point (its "centre") is the foot
/// of P on its axis, c = O + R_m cos δ a, so that the lever arm r = P − c is the mean pitch
/// radius r_m, perpendicular to the axis.
///
/// **Tooth normal** (Tredgold: the mean back cone developed into the virtual spur pair). The
/// tooth surface of a straight bevel gear contains the cone element, so the normal at P lies in
/// the plane normal to p̂; in that plane the virtual pinion's centre lies at P − r_v1 ê and the
/// virtual gear's at P + r_v2 ê, ê the unit normal to p̂ in the axial plane pointing from the
/// pinion's axis towards the gear's. The virtual axis is ẑ_v = ±p̂, the sign chosen so that a
/// positive rotation of the pinion about a_i moves P as a positive rotation about ẑ_v does. The
/// spur formulas of mesh_frame.hpp then apply with ê, ê⊥ = ẑ_v × ê, α_wt = α and s = the drive
/// sign (+1 when the pinion's driving torque points along +a_i): u = cos α ê − s sin α ê⊥,
/// v = η = sin α ê + s cos α ê⊥, w = ẑ_v, ζ = u, σ = ζ × η (along the face, ±p̂).
///
/// Consequences (tested): η ⊥ p̂ and η makes the angle α with the pitch-line tangent, so the force
/// F η on the gear has the textbook components on the pinion: tangential F cos α, radial
/// F cos α tan α cos δ₁ (separating), axial F cos α tan α sin δ₁ (towards the heel), and turns the
/// pinion by −s F r_m1 cos α about a_i. At Σ → 0 (both axes → the same direction, R_e → ∞) the
/// frame tends to the spur pair's with radii r_m, α_wt = α, to first order in Σ.
///
/// MeshFrame fields for a bevel mesh: pinion_base_radius / gear_base_radius = the virtual base
/// radii r_vb, center_distance = a_v, operating_pressure_angle = α, helix angles 0, internal and
/// rack false, pinion_center / gear_center = the reference points c above.
#pragma once

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/gear/bevel_geometry.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"

namespace geardyn {

/// Largest accepted |‖a‖ − 1| of a given axis [-] (axes are data, not directions to normalise:
/// a non-unit axis is a unit mistake or a typo).
inline constexpr double kUnitAxisTol = 1e-9;
/// Largest accepted difference between the axes' angle and the pair's shaft angle [rad].
inline constexpr double kShaftAngleTol = 1e-6;

/// @brief Where a bevel pair sits: apex, the two axes (apex → heel) and the drive sign.
struct BevelPlacement {
  Vector3 apex = Vector3::Zero();          ///< O [m]
  Vector3 pinion_axis = Vector3::UnitZ();  ///< a_i, unit [-]
  Vector3 gear_axis = Vector3::UnitX();    ///< a_j, unit, at Σ from a_i [-]
  int drive_sign = 1;                      ///< s: +1 when the pinion's torque points along +a_i
};

/// @brief The bevel mesh frame and the cone data it was built from.
struct BevelMeshFrame {
  MeshFrame frame;                          ///< the B–S frame at the mean point (see the @file)
  Vector3 apex = Vector3::Zero();           ///< O [m]
  Vector3 pinion_axis = Vector3::UnitZ();   ///< a_i [-]
  Vector3 gear_axis = Vector3::UnitX();     ///< a_j [-]
  Vector3 cone_element = Vector3::UnitX();  ///< p̂, apex → mean point [-]
  /// t̂ = a_i × (P − c_i) / r_m1, the pitch-line direction of a positive pinion rotation [-].
  Vector3 pitch_tangent = Vector3::UnitY();
};

/// @brief Builds the bevel mesh frame (see the @file).
/// @throws InvalidInput naming the field: "apex" (not finite), "pinion_axis"/"gear_axis" (not
///   finite or not unit within kUnitAxisTol, the norm named), "gear_axis" (the angle between the
///   axes differs from the pair's shaft angle by more than kShaftAngleTol, both named),
///   "drive_sign" (not ±1).
BevelMeshFrame CalcBevelMeshFrame(const BevelPairGeometry& geometry,
                                  const BevelPlacement& placement);

}  // namespace geardyn
