#include "geardyn/models/contact/tooth_flank.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geardyn/common/check.hpp"

namespace geardyn {

double ToothFlankGeometry::form_roll() const {
  return std::sqrt(std::max(0.0, form_radius * form_radius - base_radius * base_radius));
}

double ToothFlankGeometry::tip_roll() const {
  return std::sqrt(std::max(0.0, tip_radius * tip_radius - base_radius * base_radius));
}

double ToothFlankGeometry::corner_roll() const {
  const double rc = tip_radius - tip_corner_radius;
  return tip_corner_radius + std::sqrt(std::max(0.0, rc * rc - base_radius * base_radius));
}

double ToothFlankGeometry::angular_pitch() const { return 2.0 * std::numbers::pi / teeth; }

ToothFlankGeometry MakeToothFlankGeometry(const GearPairGeometry& pair, const GearGeometry& member,
                                          double form_radius, double tip_corner_radius) {
  GEARDYN_THROW_UNLESS(member.kind == GearKind::kExternal,
                       "member.kind: the contact geometry supports external gears only (an "
                       "internal gear was given)");
  GEARDYN_THROW_UNLESS(std::isfinite(form_radius),
                       "form_radius: must be finite, got " << form_radius);
  GEARDYN_THROW_UNLESS(
      std::isfinite(tip_corner_radius) && tip_corner_radius >= 0.0,
      "tip_corner_radius: must be finite and >= 0, got " << tip_corner_radius << " m");
  ToothFlankGeometry g;
  g.teeth = member.teeth;
  g.base_radius = member.base_radius;
  g.tip_radius = member.tip_radius;
  g.form_radius =
      form_radius > 0.0 ? form_radius : std::max(member.base_radius, member.root_radius);
  GEARDYN_THROW_UNLESS(g.form_radius >= g.base_radius && g.form_radius < g.tip_radius,
                       "form_radius: " << g.form_radius << " m must lie in [r_b, r_a) = ["
                                       << g.base_radius << ", " << g.tip_radius << ") m");
  GEARDYN_THROW_UNLESS(tip_corner_radius < 0.5 * member.tip_thickness_transverse,
                       "tip_corner_radius: " << tip_corner_radius
                                             << " m must be below half the tip thickness, "
                                             << 0.5 * member.tip_thickness_transverse << " m");
  g.tip_corner_radius = tip_corner_radius;
  // ψ_b = s_t/(2r) + inv α_t: half the tooth's angular width at the base circle.
  const double alpha_t = pair.transverse_pressure_angle;
  g.base_half_angle = member.tooth_thickness_transverse / (2.0 * member.reference_radius) +
                      std::tan(alpha_t) - alpha_t;
  const int hand =
      member.hand == HelixHand::kRight ? 1 : (member.hand == HelixHand::kLeft ? -1 : 0);
  g.helix_factor = hand * std::tan(pair.base_helix_angle) / member.base_radius;
  return g;
}

InvoluteFlankPose MakeFlankPose(const ToothFlankGeometry& geometry, const Vector2& center,
                                double centerline_angle, int unwind) {
  InvoluteFlankPose f;
  f.center = center;
  f.base_radius = geometry.base_radius;
  f.base_angle = centerline_angle - unwind * geometry.base_half_angle;  // β = γ − ε ψ_b
  f.unwind = unwind;
  f.roll_min = geometry.form_roll();
  f.roll_max = geometry.corner_roll();
  f.max_depth = 0.5 * geometry.base_radius * geometry.angular_pitch();
  return f;
}

Vector2 InvolutePoint(const InvoluteFlankPose& flank, double roll) {
  // P = c + r_b e(t) − ε ρ e′(t), t = β + ε ρ / r_b.
  const double t = flank.base_angle + flank.unwind * roll / flank.base_radius;
  const double ct = std::cos(t), st = std::sin(t);
  return flank.center + flank.base_radius * Vector2(ct, st) -
         flank.unwind * roll * Vector2(-st, ct);
}

Vector2 InvoluteNormal(const InvoluteFlankPose& flank, double roll) {
  const double t = flank.base_angle + flank.unwind * roll / flank.base_radius;
  return -flank.unwind * Vector2(-std::sin(t), std::cos(t));  // n = −ε e′(t)
}

}  // namespace geardyn
