/// @file
/// @brief The Blankenship–Singh mesh frame of one parallel-axis gear mesh: the directional matrix
/// W = [u v w] (B–S Eq. 21a), the helical tooth frame (ζ, η, σ), the reference point p0 and the
/// lever arms r_i, r_j that the mesh Jacobian needs (spec 01 §2).
///
/// **Conventions** (pinion i drives gear j; both axes parallel to the inertial Z; derived in
/// mesh_frame.cpp and proved by mesh_frame_test.cpp):
///
/// * ê is the unit vector in the transverse (XY) plane from the pinion centre towards the pitch
///   point: ê = (c_j − c_i)_xy / C for an external pair, ê = (c_i − c_j)_xy / C for an internal
///   pair (the pitch point lies beyond the pinion, on the side away from the ring's centre).
///   ê⊥ = Z × ê, s = drive_sign (+1 when the pinion's driving torque points along +Z).
/// * u = cos φ ê − s sin φ ê⊥ (plane-of-action normal), v = sin φ ê + s cos φ ê⊥ (transverse line
///   of action, direction of the transverse force on the driven gear, its radial part pushes the
///   wheels apart), w = Z (spec 01 §2). (u × v)·Z = s, so det W = s: W is a reflection when the
///   drive is reversed.
/// * The plane of action touches the pinion's base circle at c_i + a_i u, the gear's base circle
///   at c_j − a_j u (external, opposite side) or at c_j + a_j u (internal: the SAME side, because
///   the ring's centre lies on the pinion's side of the plane of action). Hence
///   cos φ = (a_i + a_j)/C (external) and cos φ = (a_j − a_i)/C (internal).
/// * Torque of the mesh force F η (on the driven gear; −F η on the pinion) about each centre:
///   pinion −s F a_i cos ψ_b (it opposes the drive), gear −s F a_j cos ψ_b (external: the gear
///   turns against the pinion) or +s F a_j cos ψ_b (internal: the ring turns with the pinion).
/// * **Helix hand** (intrinsic, independent of which way the axis points): a right-hand tooth
///   trace is a right-hand screw thread, i.e. it advances counter-clockwise about +Z as z
///   increases. An external mate has the opposite hand, an internal mate the same hand.
///   With h = +1 (right-hand pinion) or −1 (left-hand pinion), the signed helix angle is
///   ψ = −s h ψ_b and η = cos ψ v + sin ψ w (the rotation of (u, v, w) about u by ψ, B–S Fig. 3).
///   Example: right-hand pinion, positive drive ⇒ the axial mesh force on the driven gear is
///   −F sin ψ_b (towards −Z), on the pinion +F sin ψ_b (towards +Z), as for a right-hand screw
///   turned positively in a nut. Reversing the torque or the hand flips both.
/// * ζ = u, σ = ζ × η ((ζ, η, σ) is right-handed for both drive directions; σ runs along the
///   contact lines in the plane of action and points roughly along s·Z). The σ coordinate of a
///   contact point x used in spec 01 §3 (h, μ and the unloaded separation integrals) is
///   σ(x) = (x − p0)·σ̂, measured from the reference point p0 below.
/// * p0 is the operating pitch point c_i + r_wi ê (r_wi = a_i / cos φ) at mid face:
///   its z is the mean of the two centres' z plus MeshPlacement::face_offset.
#pragma once

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn {

/// @brief Plain inputs that place one parallel-axis mesh in the inertial frame (axes along Z).
///
/// Base radii, pressure angle and centres must agree: the transverse centre distance C must equal
/// (a_i + a_j)/cos φ (external) or (a_j − a_i)/cos φ (internal) to within
/// kCentreDistanceAngleTol of the pressure angle (a consistency check, not a tolerance of the
/// model: the frame is built from the centres and radii, so that the plane of action is tangent
/// to both base circles to rounding).
struct MeshPlacement {
  Vector3 pinion_center = Vector3::Zero();   ///< c_i, centre of the pinion (driver) [m]
  Vector3 gear_center = Vector3::Zero();     ///< c_j, centre of the driven gear or ring [m]
  double pinion_base_radius = 0.0;           ///< a_i = r_b1 > 0 [m]
  double gear_base_radius = 0.0;             ///< a_j = r_b2 > 0 (> a_i when internal) [m]
  double operating_pressure_angle = 0.0;     ///< φ = α_wt ∈ (0, π/2), transverse [rad]
  double base_helix_angle = 0.0;             ///< ψ_b = β_b ∈ [0, π/2), unsigned [rad]
  HelixHand pinion_hand = HelixHand::kNone;  ///< pinion's hand; kNone only when ψ_b = 0
  bool internal = false;                     ///< true when the gear is a ring (internal teeth)
  /// True when the gear is a rack: gear_center is then the rack's reference point and must lie
  /// at the pitch point, a_i / cos φ from the pinion axis (the rack's pitch line touches the
  /// pinion's reference circle there); gear_base_radius is not used. ê points from the pinion
  /// centre to it, the plane of action is tangent to the pinion's base circle only, and the
  /// rack's lever arm is zero in the transverse plane (its rotations act through δ_ζ only).
  bool rack = false;
  int drive_sign = 1;  ///< s: +1 when the pinion's driving torque points along +Z, −1 reversed
  double face_offset = 0.0;  ///< axial position of this mesh's mid face relative to the mean of
                             ///< the two centres' z [m] (e.g. ± for the halves of a double-helical
                             ///< pair, or a gear mounted off its body's reference point)
};

/// @brief The mesh frame of spec 01 §2 in inertial coordinates (all vectors unit unless stated).
struct MeshFrame {
  Vector3 u = Vector3::UnitX();     ///< plane-of-action normal (B–S u^{ij}, W's first column) [-]
  Vector3 v = Vector3::UnitY();     ///< transverse line of action (B–S v^{ij}) [-]
  Vector3 w = Vector3::UnitZ();     ///< gear axis Z (B–S w^{ij}) [-]
  Vector3 zeta = Vector3::UnitX();  ///< ζ = u, axis of the relative twist δ_ζ [-]
  Vector3 eta = Vector3::UnitY();   ///< η, tooth normal = mesh-force direction on the gear [-]
  Vector3 sigma = Vector3::UnitZ();            ///< σ = ζ × η, along the contact lines [-]
  Vector3 reference_point = Vector3::Zero();   ///< p0, operating pitch point at mid face [m]
  Vector3 pinion_center = Vector3::Zero();     ///< c_i [m]
  Vector3 gear_center = Vector3::Zero();       ///< c_j [m]
  Vector3 pinion_lever_arm = Vector3::Zero();  ///< r_i = p0 − c_i [m]
  Vector3 gear_lever_arm = Vector3::Zero();    ///< r_j = p0 − c_j [m]
  double pinion_base_radius = 0.0;             ///< a_i [m]
  double gear_base_radius = 0.0;               ///< a_j [m] (0 for a rack)
  double center_distance = 0.0;                ///< C, transverse centre distance [m]
  double operating_pressure_angle = 0.0;       ///< φ, from the centres and radii [rad]
  double base_helix_angle = 0.0;               ///< ψ_b ≥ 0 [rad]
  double signed_helix_angle = 0.0;             ///< ψ = −s h ψ_b: η = cos ψ v + sin ψ w [rad]
  int drive_sign = 1;                          ///< s = det W [-]
  bool internal = false;                       ///< ring gear (same-side plane of action)
  bool rack = false;                           ///< the gear is a rack (MeshPlacement::rack)
};

/// Largest accepted difference between MeshPlacement::operating_pressure_angle and the angle
/// implied by the centres and base radii [rad]: 1e-6 rad ≈ 0.2″, far below any manufacturing
/// tolerance, yet loose enough for centres computed from an iterated α_wt.
inline constexpr double kCentreDistanceAngleTol = 1e-6;

/// @brief Builds the mesh frame of spec 01 §2 (B–S Eqs. 6–12, 21a) from plain inputs.
/// @param[in] placement centres [m], base radii [m], angles [rad], hand, internal flag, drive sign.
/// @return u, v, w, ζ, η, σ, p0 [m], r_i, r_j [m] and the data they were built from.
/// @throws InvalidInput naming the field: a non-finite value, a base radius ≤ 0 (or a ring not
///   larger than its pinion), an angle out of range, a helical pair without a hand, drive_sign not
///   ±1, centres that coincide or lie too close for the base circles, or centres inconsistent with
///   the pressure angle (see kCentreDistanceAngleTol).
MeshFrame CalcMeshFrame(const MeshPlacement& placement);

/// @brief Convenience: places a pair from its derived geometry and builds its mesh frame.
///
/// The gear centre is c_i + C (cos γ, sin γ, 0) with C = (r_b2 ± r_b1)/cos α_wt (+ external,
/// − internal), which equals the operating centre distance a_w; for a rack it is the rack's
/// reference point at the pitch point, C = r_b1 / cos α_t = r_1 (γ is then the direction from the
/// pinion axis perpendicular to the rack, which runs along Z × (cos γ, sin γ, 0)); the pinion's
/// hand is geometry.pinion.hand (or geometry.spec.pinion_hand when that is kNone).
/// @param[in] geometry derived pair geometry (base radii, α_wt, β_b, hands, internal flag).
/// @param[in] pinion_center c_i [m].
/// @param[in] line_of_centres_angle γ, direction from the pinion centre to the gear (or ring)
///   centre in the XY plane, from +X towards +Y [rad].
/// @param[in] drive_sign +1 when the pinion's driving torque points along +Z, −1 reversed.
/// @throws InvalidInput as CalcMeshFrame(const MeshPlacement&), or for a non-finite γ.
MeshFrame CalcMeshFrame(const GearPairGeometry& geometry, const Vector3& pinion_center,
                        double line_of_centres_angle, int drive_sign);

/// @brief The directional matrix W = [u v w] of B–S Eq. (21a) (3×3, columns unit) [-].
Matrix3 CalcDirectionalMatrix(const MeshFrame& frame);

}  // namespace geardyn
