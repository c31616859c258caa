// The Blankenship–Singh mesh frame (spec 01 §2, B–S Eqs. 6–12 and 21a).
//
// Derivation of the conventions stated in mesh_frame.hpp, in short:
//
// 1. Plane of action. Let the transverse line of action be the set {x : u·(x − c_i) = a_i}
//    (tangent to the pinion's base circle at c_i + a_i u). For an external gear it is tangent to
//    the gear's base circle on the other side, u·(x − c_j) = −a_j; subtracting, u·(c_j − c_i) =
//    a_i + a_j, i.e. u·ê = cos φ with ê = (c_j − c_i)/C. For an internal gear (ring) it is
//    tangent on the same side, u·(x − c_j) = +a_j, so u·(c_i − c_j) = a_j − a_i: with
//    ê = (c_i − c_j)/C again u·ê = cos φ, now with cos φ = (a_j − a_i)/C. In both cases ê points
//    from the pinion centre to the pitch point p0 = c_i + (a_i / cos φ) ê.
// 2. Drive direction. The force on the driven gear is F v (F > 0) and on the pinion −F v. Its
//    moment about c_i is ((a_i u + λ v) × (−F v))·Z = −F a_i (u × v)·Z, which must oppose the
//    pinion's torque (sign s): (u × v)·Z = s. With u = cos φ ê − s sin φ ê⊥ and
//    v = sin φ ê + s cos φ ê⊥ (ê⊥ = Z × ê) one gets (u × v)·Z = s cos²φ + s sin²φ = s, and
//    v·ê = sin φ > 0: the radial part pushes the gear away from the pinion (external) and the
//    ring outwards (internal). The gear's moment is ((∓a_j u + λ v) × F v)·Z = ∓s F a_j.
// 3. Helix hand. The contact lines are generators of the pinion's involute helicoid, i.e.
//    tangents of its base helix where the plane of action touches the base cylinder (at c_i +
//    a_i u). There the counter-clockwise circumferential direction is Z × u = s v, so a
//    right-hand base helix (angle increasing with z) has tangent s sin ψ_b v + cos ψ_b Z. The
//    tooth normal lies in the plane of action, is perpendicular to that tangent and has η·v > 0
//    (it carries the transverse force), hence η = cos ψ_b v − s sin ψ_b Z; a left-hand pinion
//    flips the sin term: η = cos ψ v + sin ψ Z with ψ = −s h ψ_b. The gear's base helix gives the
//    same line (external: opposite hand, tangent point c_j − a_j u, circumferential −s v;
//    internal: same hand, same side), which mesh_frame_test checks from the helix
//    parametrisations.
#include "geardyn/models/mesh/mesh_frame.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn {
namespace {

// +1 right hand, −1 left hand, 0 spur.
int HandSign(HelixHand hand) {
  switch (hand) {
    case HelixHand::kRight:
      return 1;
    case HelixHand::kLeft:
      return -1;
    case HelixHand::kNone:
      return 0;
  }
  return 0;
}

void ValidatePlacement(const MeshPlacement& p) {
  GEARDYN_THROW_UNLESS(
      std::isfinite(p.pinion_base_radius) && p.pinion_base_radius > 0.0,
      "pinion_base_radius: must be positive and finite, got " << p.pinion_base_radius << " m");
  GEARDYN_THROW_UNLESS(
      p.rack || (std::isfinite(p.gear_base_radius) && p.gear_base_radius > 0.0),
      "gear_base_radius: must be positive and finite, got " << p.gear_base_radius << " m");
  GEARDYN_THROW_UNLESS(!(p.rack && p.internal),
                       "internal: a rack (rack = true) has no internal teeth");
  GEARDYN_THROW_UNLESS(!p.internal || p.gear_base_radius > p.pinion_base_radius,
                       "gear_base_radius: an internal gear (ring) must be larger than its pinion, "
                       "got "
                           << p.gear_base_radius << " m <= pinion_base_radius "
                           << p.pinion_base_radius << " m");
  GEARDYN_THROW_UNLESS(
      std::isfinite(p.operating_pressure_angle) && p.operating_pressure_angle > 0.0 &&
          p.operating_pressure_angle < 0.5 * kPi,
      "operating_pressure_angle: must lie in (0, pi/2) rad, got " << p.operating_pressure_angle);
  GEARDYN_THROW_UNLESS(std::isfinite(p.base_helix_angle) && p.base_helix_angle >= 0.0 &&
                           p.base_helix_angle < 0.5 * kPi,
                       "base_helix_angle: must lie in [0, pi/2) rad (the hand gives its sign), got "
                           << p.base_helix_angle);
  GEARDYN_THROW_UNLESS(p.base_helix_angle == 0.0 || p.pinion_hand != HelixHand::kNone,
                       "pinion_hand: kNone, but base_helix_angle = "
                           << p.base_helix_angle << " rad > 0 needs a right or left hand");
  GEARDYN_THROW_UNLESS(p.drive_sign == 1 || p.drive_sign == -1,
                       "drive_sign: must be +1 or -1, got " << p.drive_sign);
  GEARDYN_THROW_UNLESS(std::isfinite(p.face_offset),
                       "face_offset: must be finite, got " << p.face_offset);
  // Centres last: the convenience overload derives gear_center from the radii and angle, whose
  // own messages are the useful ones when they are bad.
  GEARDYN_THROW_UNLESS(p.pinion_center.allFinite(),
                       "pinion_center: must be finite, got " << p.pinion_center.transpose());
  GEARDYN_THROW_UNLESS(p.gear_center.allFinite(),
                       "gear_center: must be finite, got " << p.gear_center.transpose());
}

}  // namespace

MeshFrame CalcMeshFrame(const MeshPlacement& p) {
  ValidatePlacement(p);
  const double a_i = p.pinion_base_radius;
  const double a_j = p.rack ? 0.0 : p.gear_base_radius;

  // Transverse centre distance: both axes are parallel to Z, an axial offset of the centres
  // does not change the plane of action.
  Vector3 d = p.gear_center - p.pinion_center;
  d.z() = 0.0;
  const double C = d.norm();
  const double radius_scale = a_i + a_j;
  GEARDYN_THROW_UNLESS(C > 1e-12 * radius_scale,
                       "gear_center: coincides with pinion_center in the transverse plane (centre "
                       "distance "
                           << C << " m)");
  // cos φ = (a_i + a_j)/C external, (a_j − a_i)/C internal (derivation step 1); a rack's
  // reference point is the pitch point itself, so cos φ = a_i / C (a_j = 0).
  const double radius_sum = p.internal ? a_j - a_i : a_i + a_j;
  GEARDYN_THROW_UNLESS(C > radius_sum,
                       "gear_center: centre distance "
                           << C << " m is not larger than "
                           << (p.internal ? "gear_base_radius - pinion_base_radius = "
                               : p.rack   ? "pinion_base_radius = "
                                          : "pinion_base_radius + gear_base_radius = ")
                           << radius_sum << " m (the base circles "
                           << (p.internal ? "cannot share a same-side tangent)" : "overlap)"));
  const double cos_phi = radius_sum / C;
  const double phi = std::acos(cos_phi);
  GEARDYN_THROW_UNLESS(std::abs(phi - p.operating_pressure_angle) <= kCentreDistanceAngleTol,
                       "operating_pressure_angle: "
                           << p.operating_pressure_angle << " rad does not match the centres and "
                           << "base radii, which give " << phi << " rad (centre distance " << C
                           << " m; expected " << radius_sum / std::cos(p.operating_pressure_angle)
                           << " m)");
  const double sin_phi = std::sin(phi);
  const double s = static_cast<double>(p.drive_sign);

  // ê: from the pinion centre towards the pitch point (derivation step 1).
  const Vector3 e_hat = (p.internal ? -d : d) / C;
  const Vector3 e_perp = Vector3::UnitZ().cross(e_hat);

  MeshFrame f;
  // Spec 01 §2 / B–S Eqs. (9)–(10): plane-of-action normal and transverse line of action.
  f.u = cos_phi * e_hat - s * sin_phi * e_perp;
  f.v = sin_phi * e_hat + s * cos_phi * e_perp;
  f.w = Vector3::UnitZ();

  // Helical frame (B–S Fig. 3, derivation step 3): rotate (u, v, w) about u by ψ = −s h ψ_b.
  const double psi = -s * HandSign(p.pinion_hand) * p.base_helix_angle;
  f.zeta = f.u;
  f.eta = std::cos(psi) * f.v + std::sin(psi) * f.w;
  f.sigma = f.zeta.cross(f.eta);

  // Reference point: operating pitch point (pitch radius a_i / cos φ along ê) at mid face.
  f.reference_point = p.pinion_center + (a_i / cos_phi) * e_hat;
  f.reference_point.z() = 0.5 * (p.pinion_center.z() + p.gear_center.z()) + p.face_offset;

  f.pinion_center = p.pinion_center;
  f.gear_center = p.gear_center;
  f.pinion_lever_arm = f.reference_point - p.pinion_center;
  f.gear_lever_arm = f.reference_point - p.gear_center;
  f.pinion_base_radius = a_i;
  f.gear_base_radius = a_j;
  f.center_distance = C;
  f.operating_pressure_angle = phi;
  f.base_helix_angle = p.base_helix_angle;
  f.signed_helix_angle = psi;
  f.drive_sign = p.drive_sign;
  f.internal = p.internal;
  f.rack = p.rack;
  return f;
}

MeshFrame CalcMeshFrame(const GearPairGeometry& geometry, const Vector3& pinion_center,
                        double line_of_centres_angle, int drive_sign) {
  GEARDYN_THROW_UNLESS(std::isfinite(line_of_centres_angle),
                       "line_of_centres_angle: must be finite, got " << line_of_centres_angle);
  MeshPlacement p;
  p.pinion_center = pinion_center;
  p.pinion_base_radius = geometry.pinion.base_radius;
  p.gear_base_radius = geometry.gear.base_radius;
  p.operating_pressure_angle = geometry.operating_pressure_angle;
  p.base_helix_angle = geometry.base_helix_angle;
  p.pinion_hand =
      geometry.pinion.hand != HelixHand::kNone ? geometry.pinion.hand : geometry.spec.pinion_hand;
  p.internal = geometry.internal;
  p.rack = geometry.rack;
  if (p.rack) p.gear_base_radius = 0.0;
  p.drive_sign = drive_sign;
  // C = (r_b2 ± r_b1)/cos α_wt = a_w (a rack: r_b1/cos α_t, to its pitch point); invalid radii or
  // angles are reported by the call below.
  const double radius_sum = p.internal ? p.gear_base_radius - p.pinion_base_radius
                                       : p.pinion_base_radius + p.gear_base_radius;
  const double C = radius_sum / std::cos(p.operating_pressure_angle);
  p.gear_center = pinion_center + C * Vector3(std::cos(line_of_centres_angle),
                                              std::sin(line_of_centres_angle), 0.0);
  return CalcMeshFrame(p);
}

Matrix3 CalcDirectionalMatrix(const MeshFrame& frame) {
  Matrix3 W;
  W.col(0) = frame.u;
  W.col(1) = frame.v;
  W.col(2) = frame.w;
  return W;
}

}  // namespace geardyn
