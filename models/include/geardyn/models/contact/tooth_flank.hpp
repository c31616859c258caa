/// @file
/// @brief The involute tooth flanks of one gear for the contact simulator (spec 03): the flank
/// geometry of a gear (base, form and tip radii, base half angle, tip-corner radius) and the
/// planar pose of one flank (its base circle, the angle where it leaves that circle and its
/// unwinding sense).
///
/// **Planar conventions** (transverse plane, world axes X, Y; angles counter-clockwise about +Z;
/// e(t) = (cos t, sin t), J = rotation by +90°, so J e(t) = e′(t) = (−sin t, cos t)):
/// an involute flank of the base circle (c, r_b) that leaves the circle at the angle β and
/// unwinds with the sense ε = ±1 is, as a function of its roll distance ρ ≥ 0 [m],
/// \f[ t = β + ε ρ / r_b, \qquad P(ρ) = c + r_b e(t) − ε ρ\, e′(t) = T(t) + ρ\, n(t),
///     \qquad n = −ε\, e′(t), \f]
/// T the tangent point on the base circle and n the flank's OUTWARD normal (pointing out of the
/// tooth's material). The flank's normal lies on the tangent of the base circle at T (the
/// generating line) and the radius of curvature at P equals ρ. The polar angle of P about c is
/// β + ε inv α with tan α = ρ/r_b: ε = −1 flanks lean back towards smaller angles, ε = +1
/// flanks towards larger ones. A tooth whose centre line is at the angle γ spans the base-circle
/// angles [γ − ψ_b, γ + ψ_b]: its flank at γ + ψ_b has ε = −1, its flank at γ − ψ_b has ε = +1,
/// i.e. β = γ − ε ψ_b.
///
/// **Which flank drives** (external pair, pinion drive sign s, mesh_frame.hpp): the pinion turns
/// towards s, so its leading flank drives: the drive flanks of both members have ε = −s, the coast
/// (back) flanks ε = +s (involute_contact.hpp derives why both members' flanks in one contact have
/// the same ε).
///
/// **Tooth half angle at the base circle**: ψ_b = s_t/(2r) + inv α_t with s_t the transverse tooth
/// thickness at the reference radius r and α_t the transverse pressure angle there.
#pragma once

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn {

/// Which of a tooth's two flanks: the one that carries the drive torque or the back flank.
enum class FlankSide { kDrive, kCoast };

/// @brief Flank geometry of one external gear, common to all its teeth (SI units).
struct ToothFlankGeometry {
  int teeth = 0;                   ///< z [-]
  double base_radius = 0.0;        ///< r_b [m]
  double tip_radius = 0.0;         ///< r_a [m]
  double form_radius = 0.0;        ///< r_F, start of the usable involute [m], r_b ≤ r_F < r_a
  double base_half_angle = 0.0;    ///< ψ_b = s_t/(2r) + inv α_t [rad]
  double tip_corner_radius = 0.0;  ///< ρ_a ≥ 0, radius of the rounded tip corner [m]
  double helix_factor = 0.0;       ///< h tan β_b / r_b [rad/m]: section twist per metre along +Z
                                   ///< (h = +1 right hand, −1 left hand, 0 spur)
  /// ρ_F = √(r_F² − r_b²), roll distance of the form circle [m].
  double form_roll() const;
  /// ρ_a = √(r_a² − r_b²), roll distance of the tip circle [m].
  double tip_roll() const;
  /// ρ_t = ρ_a + √((r_a − ρ_a)² − r_b²), roll distance where the tip-corner circle (radius
  /// ρ_a, tangent to the flank and to the tip circle) meets the flank [m]; the involute ends
  /// there (= tip_roll() when ρ_a = 0). From |Q − c|² = r_b² + (ρ_t − ρ_a)² for the corner centre
  /// Q = P(ρ_t) − ρ_a n(ρ_t) on the circle of radius r_a − ρ_a.
  double corner_roll() const;
  /// Angular pitch 2π/z [rad].
  double angular_pitch() const;
};

/// @brief The flank geometry of one member of a pair.
/// @param[in] pair derived pair geometry (α_t, β_b, reference radii, thicknesses).
/// @param[in] member the pinion or the gear of `pair` (must be external).
/// @param[in] form_radius r_F [m]; ≤ 0 selects max(r_b, r_f), the lowest point an involute can
///   have without a fillet model (the real form circle lies slightly above r_f).
/// @param[in] tip_corner_radius ρ_a ≥ 0 [m].
/// @throws InvalidInput naming "member.kind" (internal gears are not supported by the contact
///   geometry), "form_radius" (not below the tip radius) or "tip_corner_radius" (negative, not
///   finite, or not below the tip thickness).
ToothFlankGeometry MakeToothFlankGeometry(const GearPairGeometry& pair, const GearGeometry& member,
                                          double form_radius = 0.0, double tip_corner_radius = 0.0);

/// @brief The planar pose of one involute flank (see the @file for the parametrisation).
struct InvoluteFlankPose {
  Vector2 center = Vector2::Zero();  ///< c, centre of the (effective) base circle [m]
  double base_radius = 0.0;          ///< r_b [m]
  double base_angle = 0.0;           ///< β, where the involute leaves the base circle [rad]
  int unwind = 1;                    ///< ε = ±1, unwinding sense (the @file)
  double roll_min = 0.0;             ///< ρ_F, roll distance of the form circle [m]
  double roll_max = 0.0;  ///< ρ_t, end of the involute: the tip circle or the corner [m]
  /// Largest |δ| of a contact of this flank [m]: half the base pitch π r_b / z. The common
  /// tangent also meets the flanks of the wrong mating tooth, k base pitches away (δ ± k p_b);
  /// true contacts stay far below half a pitch, so this bound tells them apart.
  double max_depth = 0.0;
};

/// @brief The pose of one flank of a tooth of a rigid (or rigidly displaced) tooth.
/// @param[in] geometry flank geometry of the gear.
/// @param[in] center c, centre of the (effective) base circle [m].
/// @param[in] centerline_angle γ, world angle of the tooth's centre line [rad].
/// @param[in] unwind ε = ±1 of the flank (the drive flank has ε = −s, the coast flank ε = +s).
/// @return β = γ − ε ψ_b with the roll limits [ρ_F, ρ_t] of `geometry` (corner_roll()) and
///   max_depth = π r_b / z.
InvoluteFlankPose MakeFlankPose(const ToothFlankGeometry& geometry, const Vector2& center,
                                double centerline_angle, int unwind);

/// @brief P(ρ) [m], the flank point at roll distance ρ [m].
Vector2 InvolutePoint(const InvoluteFlankPose& flank, double roll);
/// @brief n(ρ), the flank's outward unit normal at roll distance ρ [m].
Vector2 InvoluteNormal(const InvoluteFlankPose& flank, double roll);

}  // namespace geardyn
