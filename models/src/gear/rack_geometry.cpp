/// @file
/// @brief The gear–rack pair geometry (gear_geometry.hpp, "Rack"; issue 19).
///
/// Heights are distances from the pinion axis, perpendicular to the rack's pitch line. A point of
/// the transverse line of action at roll length ρ from T1 (the tangency point on the pinion's
/// base circle) lies at height h(ρ) = r_b1 cos α_t + ρ sin α_t: T1 = r_b1 u has height
/// r_b1 cos α_t, and the line rises at sin α_t (it makes α_t with the pitch line). At the pitch
/// point ρ = r_b1 tan α_t gives h = r_b1 / cos α_t = r_1: the pinion rolls on its reference circle.
/// The rack tip line (height a_w − h_aP* m_n) therefore starts contact at
/// T1A = (a_w − h_aP* m_n − r_b1 cos α_t) / sin α_t. A rack moved away by Δ from the zero-backlash
/// line a_w0 = r_1 + x_1 m_n opens a gap of 2Δ tan α_t on the pitch line (each flank moves by
/// Δ tan α_t), j_bn = 2Δ sin α_n. These are the limits z_2 → ∞ (x_2 = 0) of the gear-pair
/// formulas, which gear_geometry_test checks.
#include <cmath>
#include <limits>
#include <numeric>
#include <ostream>
#include <sstream>
#include <string>

#include "gear_geometry_internal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn::internal {
namespace {

constexpr double kLengthTolerance = 1e-9;         // of m_n, as gear_geometry.cpp
constexpr double kShiftRoundingTolerance = 1e-4;  // as gear_geometry.cpp

struct Mm {
  double metres;
};
std::ostream& operator<<(std::ostream& os, const Mm& mm) { return os << mm.metres * 1e3 << " mm"; }

}  // namespace

GearPairGeometry CalcRackPairGeometry(const GearPairSpec& spec) {
  const GearBlank& rack = spec.gear;
  GEARDYN_THROW_UNLESS(rack.profile_shift == 0.0,
                       "gear.profile_shift: a rack has no profile shift (got "
                           << rack.profile_shift
                           << "); move the rack with center_distance, the distance from the "
                              "pinion axis to the rack's reference line");
  GEARDYN_THROW_UNLESS(!rack.tip_diameter.has_value(),
                       "gear.tip_diameter: a rack has no tip circle; its addendum is "
                       "addendum_coefficient * m_n");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  GearPairGeometry g;
  g.spec = spec;
  g.rack = true;
  FillTransverseBasics(&g);
  const double m_n = spec.normal_module;
  const double alpha_n = spec.normal_pressure_angle;
  const double beta = spec.helix_angle;
  const double m_t = g.transverse_module;
  const double alpha_t = g.transverse_pressure_angle;
  const double beta_b = g.base_helix_angle;
  const double inv_alpha_t = Involute(alpha_t);
  const double tol = kLengthTolerance * m_n;
  g.operating_pressure_angle = alpha_t;  // whatever the mounting

  const GearBlank& pinion = spec.pinion;
  const double z1 = static_cast<double>(pinion.teeth);
  const double x1 = pinion.profile_shift;
  const double r1 = 0.5 * z1 * m_t;
  const double rb1 = r1 * std::cos(alpha_t);
  const double ra1 = pinion.tip_diameter ? 0.5 * *pinion.tip_diameter
                                         : r1 + m_n * (pinion.addendum_coefficient + x1);
  const double rf1 = r1 - m_n * (pinion.dedendum_coefficient - x1);
  g.reference_center_distance = r1;
  g.zero_backlash_center_distance = r1 + x1 * m_n;
  const double a_w = spec.center_distance.value_or(g.zero_backlash_center_distance);
  g.center_distance = a_w;

  // Backlash: a rack Δ beyond the zero-backlash line opens j_wt = 2Δ tan α_t (file notes).
  const double delta = a_w - g.zero_backlash_center_distance;
  const double j_wt = 2.0 * delta * std::tan(alpha_t);
  if (j_wt < -tol) {
    const double shift_excess = -delta / m_n;  // the pinion shift that closes the same gap
    std::ostringstream message;
    message << "center_distance: " << Mm{a_w} << " puts the rack's reference line " << Mm{-delta}
            << " inside the zero-backlash line " << Mm{g.zero_backlash_center_distance}
            << " (r_1 + x_1 m_n): the flanks interfere, as if x1 were " << shift_excess
            << " too large";
    GEARDYN_THROW_UNLESS(shift_excess <= kShiftRoundingTolerance,
                         message.str() << " (more than the " << kShiftRoundingTolerance
                                       << " that rounding the shift to 4 decimals explains)");
    g.interference_normal = -j_wt * std::cos(alpha_t) * std::cos(beta_b);
    message << "; within the " << kShiftRoundingTolerance
            << " of a shift rounded to 4 decimals: taken as zero backlash";
    g.warnings.push_back(message.str());
  }
  g.backlash_circumferential = std::max(j_wt, 0.0);
  g.backlash_normal = g.backlash_circumferential * std::cos(alpha_t) * std::cos(beta_b);

  // Pinion radii.
  GEARDYN_THROW_UNLESS(rf1 > 0.0, "pinion.root_radius: " << Mm{rf1} << " is not positive (short by "
                                                         << Mm{-rf1} << ")");
  GEARDYN_THROW_UNLESS(
      ra1 > rb1, "pinion.tip_radius: " << Mm{ra1} << " is not above the base radius " << Mm{rb1}
                                       << " (short by " << Mm{rb1 - ra1} << ")");
  GEARDYN_THROW_UNLESS(
      ra1 > rf1, "pinion.tip_radius: " << Mm{ra1} << " is not above the root radius " << Mm{rf1});
  const double s_t1 = m_t * (0.5 * kPi + 2.0 * x1 * std::tan(alpha_n));
  const double inv_aa1 = Involute(std::acos(rb1 / ra1));
  const double s_at1 = 2.0 * ra1 * (s_t1 / (2.0 * r1) + inv_alpha_t - inv_aa1);
  if (pinion.tip_diameter) {
    GEARDYN_THROW_UNLESS(s_at1 > 0.0, "pinion.tip_diameter: "
                                          << Mm{2.0 * ra1}
                                          << " is beyond the diameter where the tooth comes to a "
                                             "point; lengths are in metres: 44 mm is 0.044");
  }

  // Path of contact (roll lengths from T1).
  const double rack_tip_height = a_w - rack.addendum_coefficient * m_n;
  const double rack_root_height = a_w + rack.dedendum_coefficient * m_n;
  const double rho_start = (rack_tip_height - rb1 * std::cos(alpha_t)) / std::sin(alpha_t);
  const double rho_end = std::sqrt(ra1 * ra1 - rb1 * rb1);
  if (spec.center_distance) {
    GEARDYN_THROW_UNLESS(rho_end - rho_start > 0.0,
                         "center_distance: " << Mm{a_w}
                                             << " puts the rack's tip line beyond the pinion tip "
                                                "along the line of action (no path of contact: "
                                                "g_α = "
                                             << Mm{rho_end - rho_start} << ")");
  }
  GEARDYN_THROW_UNLESS(rho_start >= -tol,
                       "gear.tip_interference: the rack tip meets the pinion flank "
                           << Mm{-rho_start}
                           << " beyond the interference point T1, i.e. below the pinion's base "
                              "circle (reduce the rack's addendum or add pinion profile shift)");
  g.path_start_from_pinion_tangent = std::max(rho_start, 0.0);
  g.path_end_from_pinion_tangent = rho_end;
  g.pitch_point_from_pinion_tangent = rb1 * std::tan(alpha_t);
  g.line_of_action_length = rho_end - g.path_start_from_pinion_tangent;

  // Undercut of the pinion (the gear-pair rule of gear_geometry.cpp).
  const double h_ap0 =
      pinion.dedendum_coefficient - pinion.root_radius_coefficient * (1.0 - std::sin(alpha_n));
  const double x_min = h_ap0 - z1 * std::pow(std::sin(alpha_t), 2) / (2.0 * std::cos(beta));
  GEARDYN_THROW_UNLESS(
      x1 >= x_min - 1e-12,
      "pinion.undercut: x = " << x1 << " is below the undercut limit x_min = " << x_min
                              << " for z = " << pinion.teeth << " (short by " << x_min - x1 << ")");

  // Tip lands: the pinion's at its tip circle, the rack's top land of the basic-rack trapezoid.
  const double s_min = spec.min_tip_thickness_factor * m_n;
  const double beta_a1 = std::atan(std::tan(beta) * ra1 / r1);
  const double s_an1 = s_at1 * std::cos(beta_a1);
  GEARDYN_THROW_UNLESS(
      s_an1 >= s_min, "pinion.tip_thickness_normal: "
                          << Mm{s_an1} << " is below min_tip_thickness_factor * m_n = " << Mm{s_min}
                          << " (short by " << Mm{s_min - s_an1} << ")");
  const double s_an2 = m_n * (0.5 * kPi - 2.0 * rack.addendum_coefficient * std::tan(alpha_n));
  GEARDYN_THROW_UNLESS(
      s_an2 >= s_min, "gear.tip_thickness_normal: the rack's top land "
                          << Mm{s_an2} << " is below min_tip_thickness_factor * m_n = " << Mm{s_min}
                          << " (addendum_coefficient " << rack.addendum_coefficient
                          << " too large)");

  // Radial clearances: the pinion tip against the rack's root line, the rack tip against the
  // pinion's root circle.
  GEARDYN_THROW_UNLESS(rack_root_height - ra1 >= -tol,
                       "pinion.tip_clearance: the pinion tip reaches "
                           << Mm{ra1 - rack_root_height} << " past the rack's root line");
  GEARDYN_THROW_UNLESS(rack_tip_height - rf1 >= -tol, "gear.tip_clearance: the rack tip reaches "
                                                          << Mm{rf1 - rack_tip_height}
                                                          << " past the pinion's root "
                                                             "circle");

  // The members.
  GearGeometry& p = g.pinion;
  p.teeth = pinion.teeth;
  p.kind = GearKind::kExternal;
  p.hand = spec.pinion_hand;
  p.reference_radius = r1;
  p.base_radius = rb1;
  p.tip_radius = ra1;
  p.root_radius = rf1;
  p.operating_pitch_radius = r1;
  p.virtual_teeth = z1 / (std::pow(std::cos(beta_b), 2) * std::cos(beta));
  p.tip_thickness_normal = s_an1;
  p.tip_thickness_transverse = s_at1;
  p.tooth_thickness_transverse = s_t1;
  p.profile_shift = x1;
  p.start_of_active_profile_radius = std::hypot(rb1, g.path_start_from_pinion_tangent);
  GearGeometry& r = g.gear;
  r.teeth = rack.teeth;
  r.kind = GearKind::kRack;
  r.hand = OppositeHand(spec.pinion_hand);
  r.reference_radius = r.base_radius = r.tip_radius = r.root_radius = kInf;
  r.operating_pitch_radius = r.virtual_teeth = r.start_of_active_profile_radius = kInf;
  r.tip_thickness_normal = s_an2;
  r.tip_thickness_transverse = s_an2 / std::cos(beta);
  r.tooth_thickness_transverse = 0.5 * kPi * m_t;
  r.profile_shift = 0.0;

  FillContactRatios(&g);
  g.gear_ratio = kInf;
  // The pinion's errors repeat every z_1 mesh cycles; the rack's never do.
  g.teeth_gcd = pinion.teeth;
  g.hunting_period_meshes = pinion.teeth;
  g.pinion_turns_per_hunting_period = 1;
  g.gear_turns_per_hunting_period = 0;
  return g;
}

}  // namespace geardyn::internal
