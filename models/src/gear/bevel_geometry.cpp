// Straight bevel pair geometry (bevel_geometry.hpp).
#include "geardyn/models/gear/bevel_geometry.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn {
namespace {

constexpr int kMinBevelTeeth = 3;
constexpr double kMaxPressureAngle = std::numbers::pi / 4.0;
// Given cone angles must match the implied ones to 1e-6 rad (0.2″): they are derived data, so a
// larger difference means the teeth or the shaft angle are not what the user thinks.
constexpr double kConeAngleTol = 1e-6;
// ISO 23509 / Gleason practice: b ≤ R_e / 3; wider faces are accepted with a note.
constexpr double kMaxRecommendedFaceRatio = 1.0 / 3.0;

bool FinitePositive(double x) { return std::isfinite(x) && x > 0.0; }

void CheckGivenConeAngle(const std::optional<double>& given, double implied, const char* field,
                         const BevelPairSpec& spec) {
  if (!given) return;
  GEARDYN_THROW_UNLESS(std::isfinite(*given) && std::abs(*given - implied) <= kConeAngleTol,
                       field << ": " << RadToDeg(*given) << " deg is inconsistent with the teeth "
                             << spec.pinion_teeth << "/" << spec.gear_teeth
                             << " and the shaft angle " << RadToDeg(spec.shaft_angle)
                             << " deg, which give " << RadToDeg(implied)
                             << " deg (δ1 = atan(sin Σ / (z2/z1 + cos Σ)), δ2 = Σ − δ1); "
                                "leave it out or correct it");
}

}  // namespace

BevelPairGeometry CalcBevelPairGeometry(const BevelPairSpec& spec) {
  GEARDYN_THROW_UNLESS(FinitePositive(spec.outer_module) && spec.outer_module >= kMinNormalModule,
                       "outer_module: must be finite and at least "
                           << kMinNormalModule << " m, got " << spec.outer_module << " m");
  GEARDYN_THROW_UNLESS(
      std::isfinite(spec.pressure_angle) && spec.pressure_angle > 0.0 &&
          spec.pressure_angle < kMaxPressureAngle,
      "pressure_angle: must lie in (0, 45) deg, got " << RadToDeg(spec.pressure_angle) << " deg");
  GEARDYN_THROW_UNLESS(std::isfinite(spec.shaft_angle) && spec.shaft_angle > 0.0 &&
                           spec.shaft_angle < std::numbers::pi,
                       "shaft_angle: must lie in (0, 180) deg (intersecting axes), got "
                           << RadToDeg(spec.shaft_angle) << " deg");
  GEARDYN_THROW_UNLESS(spec.pinion_teeth >= kMinBevelTeeth, "pinion.teeth: must be at least "
                                                                << kMinBevelTeeth << ", got "
                                                                << spec.pinion_teeth);
  GEARDYN_THROW_UNLESS(spec.gear_teeth >= kMinBevelTeeth, "gear.teeth: must be at least "
                                                              << kMinBevelTeeth << ", got "
                                                              << spec.gear_teeth);
  GEARDYN_THROW_UNLESS(FinitePositive(spec.face_width),
                       "face_width: must be finite and positive, got " << spec.face_width << " m");
  GEARDYN_THROW_UNLESS(
      FinitePositive(spec.addendum_coefficient),
      "addendum_coefficient: must be finite and positive, got " << spec.addendum_coefficient);
  GEARDYN_THROW_UNLESS(std::isfinite(spec.pinion_profile_shift),
                       "pinion_profile_shift: must be finite, got " << spec.pinion_profile_shift);

  BevelPairGeometry g;
  g.spec = spec;
  const double z1 = spec.pinion_teeth, z2 = spec.gear_teeth;
  const double sigma = spec.shaft_angle, alpha = spec.pressure_angle;
  g.gear_ratio = z2 / z1;
  // ISO 23509: tan δ1 = sin Σ / (u + cos Σ); atan2 keeps δ1 ∈ (0, π) for every Σ.
  g.pinion_cone_angle = std::atan2(std::sin(sigma), g.gear_ratio + std::cos(sigma));
  g.gear_cone_angle = sigma - g.pinion_cone_angle;
  GEARDYN_THROW_UNLESS(g.gear_cone_angle < std::numbers::pi / 2.0 - kConeAngleTol,
                       "gear_cone_angle: δ2 = " << RadToDeg(g.gear_cone_angle) << " deg (teeth "
                                                << spec.pinion_teeth << "/" << spec.gear_teeth
                                                << ", shaft angle " << RadToDeg(sigma)
                                                << " deg) makes a crown gear (90 deg) or an "
                                                   "internal bevel gear (above): not supported");
  CheckGivenConeAngle(spec.pinion_cone_angle, g.pinion_cone_angle, "pinion_cone_angle", spec);
  CheckGivenConeAngle(spec.gear_cone_angle, g.gear_cone_angle, "gear_cone_angle", spec);

  const double m_et = spec.outer_module, b = spec.face_width;
  g.pinion_outer_pitch_diameter = z1 * m_et;
  g.gear_outer_pitch_diameter = z2 * m_et;
  g.outer_cone_distance = g.pinion_outer_pitch_diameter / (2.0 * std::sin(g.pinion_cone_angle));
  GEARDYN_THROW_UNLESS(
      b < g.outer_cone_distance,
      "face_width: " << b * 1e3 << " mm is not below the outer cone distance R_e = "
                     << g.outer_cone_distance * 1e3 << " mm: the teeth would reach the apex");
  if (b > kMaxRecommendedFaceRatio * g.outer_cone_distance) {
    std::ostringstream note;
    note << "face_width: " << b * 1e3
         << " mm is above R_e/3 = " << g.outer_cone_distance * 1e3 / 3.0
         << " mm (ISO 23509 practice); the mean section still represents the face";
    g.warnings.push_back(note.str());
  }
  g.mean_cone_distance = g.outer_cone_distance - 0.5 * b;
  g.mean_module = m_et * g.mean_cone_distance / g.outer_cone_distance;
  g.pinion_mean_pitch_radius = 0.5 * z1 * g.mean_module;
  g.gear_mean_pitch_radius = 0.5 * z2 * g.mean_module;

  // Tredgold's virtual spur pair at the mean back cone.
  const double c1 = std::cos(g.pinion_cone_angle), c2 = std::cos(g.gear_cone_angle);
  g.pinion_virtual_teeth = z1 / c1;
  g.gear_virtual_teeth = z2 / c2;
  g.pinion_virtual_radius = g.pinion_mean_pitch_radius / c1;
  g.gear_virtual_radius = g.gear_mean_pitch_radius / c2;
  g.pinion_virtual_base_radius = g.pinion_virtual_radius * std::cos(alpha);
  g.gear_virtual_base_radius = g.gear_virtual_radius * std::cos(alpha);
  const double m_m = g.mean_module, x = spec.pinion_profile_shift, ha = spec.addendum_coefficient;
  g.pinion_virtual_tip_radius = g.pinion_virtual_radius + m_m * (ha + x);
  g.gear_virtual_tip_radius = g.gear_virtual_radius + m_m * (ha - x);
  g.virtual_center_distance = g.pinion_virtual_radius + g.gear_virtual_radius;
  g.mean_base_pitch = std::numbers::pi * m_m * std::cos(alpha);
  GEARDYN_THROW_UNLESS(g.pinion_virtual_tip_radius > g.pinion_virtual_base_radius,
                       "pinion.tip_radius: the virtual tip circle lies inside the base circle "
                       "(addendum m_m (h_aP* + x_hm1) = "
                           << m_m * (ha + x) * 1e3
                           << " mm); lower pinion_profile_shift's magnitude");
  GEARDYN_THROW_UNLESS(g.gear_virtual_tip_radius > g.gear_virtual_base_radius,
                       "gear.tip_radius: the virtual tip circle lies inside the base circle "
                       "(addendum m_m (h_aP* − x_hm1) = "
                           << m_m * (ha - x) * 1e3 << " mm); lower pinion_profile_shift");
  const double T1E = std::sqrt(g.pinion_virtual_tip_radius * g.pinion_virtual_tip_radius -
                               g.pinion_virtual_base_radius * g.pinion_virtual_base_radius);
  const double T2A = std::sqrt(g.gear_virtual_tip_radius * g.gear_virtual_tip_radius -
                               g.gear_virtual_base_radius * g.gear_virtual_base_radius);
  const double T1T2 = g.virtual_center_distance * std::sin(alpha);
  g.path_start_from_pinion_tangent = T1T2 - T2A;
  g.path_end_from_pinion_tangent = T1E;
  g.pitch_point_from_pinion_tangent = g.pinion_virtual_base_radius * std::tan(alpha);
  GEARDYN_THROW_UNLESS(g.path_start_from_pinion_tangent >= 0.0,
                       "pinion.tip_interference: the gear's tip meets the pinion's flank "
                           << -g.path_start_from_pinion_tangent * 1e3
                           << " mm inside its virtual base circle (T1A < 0); raise "
                              "pinion_profile_shift or the pinion's teeth");
  GEARDYN_THROW_UNLESS(T1E <= T1T2,
                       "gear.tip_interference: the pinion's tip meets the gear's "
                       "flank "
                           << (T1E - T1T2) * 1e3
                           << " mm inside its virtual base circle; lower "
                              "pinion_profile_shift");
  g.path_of_contact_length = T1E + T2A - T1T2;
  g.contact_ratio = g.path_of_contact_length / g.mean_base_pitch;
  GEARDYN_THROW_UNLESS(g.contact_ratio >= 1.0,
                       "contact_ratio: " << g.contact_ratio << " is below 1 (short by "
                                         << 1.0 - g.contact_ratio
                                         << "): the virtual spur pair loses contact");
  return g;
}

}  // namespace geardyn
