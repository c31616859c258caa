/// @file
/// @brief Involute gear-pair geometry (ISO 21771:2007, ISO 53 basic rack) and its rejections.
///
/// Implementation notes
/// * Sign convention for internal gears: tooth counts and radii are positive; the formulas carry
///   σ = +1 (external pair) or −1 (internal pair). A positive profile shift thickens the teeth of
///   either kind (ISO 21771 with signed z, see gear_geometry.hpp). With this convention:
///     a      = r_2 + σ r_1                          reference centre distance
///     cos α_wt = (r_b2 + σ r_b1) / a_w              operating pressure angle
///     inv α_wt = inv α_t + σ 2 tan α_n (x_1 + x_2) / (z_2 + σ z_1)   zero backlash.
///   The internal form follows from the no-backlash condition on the operating pitch circle,
///   e_w2 = s_w1 (the pinion tooth fills the ring's space), with the ring's space width
///   e(r) = d_r (e/d + inv α_t − inv α_r) and s_1 − e_2 = 2 m_t tan α_n (x_1 + x_2); it equals
///   ISO 21771's external formula with z_2 → −z_2 and KHK's with x_2 → −x_2.
/// * Tooth thickness at radius r_y: external s_y = d_y (s/d + inv α_t − inv α_y), internal
///   s_y = d_y (s/d − inv α_t + inv α_y) (the ring's space is an external tooth).
/// * Positions on the line of action are the pinion's roll lengths ρ measured from T1, the
///   tangency point on the pinion's base circle; T1T2 = a_w sin α_wt. External: T2 lies beyond the
///   pitch point, internal: T2 lies behind T1 (both base circles on the same side).
/// * Not checked: contact of a mating tip with the root fillet above the root circle (needs the
///   generated root form circle), and trimming interference of internal pairs (only blocks
///   radial assembly; SDP/SI Table 5-4 pairs have it and are valid with axial assembly).
#include "geardyn/models/gear/gear_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <ostream>
#include <sstream>
#include <string>

#include "gear_geometry_internal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn {
namespace {

constexpr int kMinTeeth = 3;  // below this the formulas degenerate; physics checks do the rest
constexpr double kMaxPressureAngle = 45.0 * kPi / 180.0;
constexpr double kMaxHelixAngle = 60.0 * kPi / 180.0;
// Relative tolerance (of m_n) under which a negative backlash or clearance counts as round-off:
// a zero-backlash pair computed from its own a_w has |j_wt| ~ 1e-15 m_n.
constexpr double kLengthTolerance = 1e-9;
// Interference accepted as zero backlash, as the profile-shift sum excess that causes it: two
// shifts printed to 4 decimals are each off by at most 5e-5 (documented in docs/scene-format.md).
constexpr double kShiftRoundingTolerance = 1e-4;

using internal::Involute;

/// α in (0, π/2) with inv α = v > 0. Newton on the convex increasing f(α) = inv α − v converges
/// monotonically from any start with f ≥ 0; both (3v)^(1/3) (inv α ≥ α³/3) and atan(v + π/2)
/// (inv α = v + π/2 − α ≥ v there) are such starts.
double InverseInvolute(double v) {
  GEARDYN_DEMAND(v > 0.0 && std::isfinite(v));
  double alpha = std::min(std::cbrt(3.0 * v), std::atan(v + 0.5 * kPi));
  for (int i = 0; i < 100; ++i) {
    const double t = std::tan(alpha);
    const double step = (t - alpha - v) / (t * t);
    alpha -= step;
    if (std::abs(step) <= 1e-15 * alpha) break;
  }
  return alpha;
}

/// Stream helper: a length in millimetres with its unit.
struct Mm {
  double metres;
};
std::ostream& operator<<(std::ostream& os, const Mm& mm) { return os << mm.metres * 1e3 << " mm"; }

bool FiniteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }
bool FinitePositive(double v) { return std::isfinite(v) && v > 0.0; }

void ValidateBlank(const GearBlank& blank, const std::string& name) {
  GEARDYN_THROW_UNLESS(blank.kind == GearKind::kRack || blank.teeth >= kMinTeeth,
                       name << ".teeth: must be at least " << kMinTeeth << ", got " << blank.teeth);
  GEARDYN_THROW_UNLESS(
      FinitePositive(blank.face_width),
      name << ".face_width: must be finite and positive, got " << blank.face_width << " m");
  GEARDYN_THROW_UNLESS(std::isfinite(blank.profile_shift),
                       name << ".profile_shift: must be finite, got " << blank.profile_shift);
  GEARDYN_THROW_UNLESS(
      FiniteNonNegative(blank.addendum_coefficient),
      name << ".addendum_coefficient: must be finite and >= 0, got " << blank.addendum_coefficient);
  GEARDYN_THROW_UNLESS(FinitePositive(blank.dedendum_coefficient),
                       name << ".dedendum_coefficient: must be finite and positive, got "
                            << blank.dedendum_coefficient);
  GEARDYN_THROW_UNLESS(FiniteNonNegative(blank.root_radius_coefficient),
                       name << ".root_radius_coefficient: must be finite and >= 0, got "
                            << blank.root_radius_coefficient);
  if (blank.tip_diameter) {
    GEARDYN_THROW_UNLESS(
        FinitePositive(*blank.tip_diameter),
        name << ".tip_diameter: must be finite and positive, got " << *blank.tip_diameter << " m");
  }
  if (blank.web_thickness) {
    GEARDYN_THROW_UNLESS(FinitePositive(*blank.web_thickness),
                         name << ".web_thickness: must be finite and positive, got "
                              << *blank.web_thickness << " m");
  }
  if (blank.rim_thickness) {
    GEARDYN_THROW_UNLESS(FinitePositive(*blank.rim_thickness),
                         name << ".rim_thickness: must be finite and positive, got "
                              << *blank.rim_thickness << " m");
  }
}

}  // namespace

namespace internal {

double Involute(double alpha) { return std::tan(alpha) - alpha; }

void ValidateGearPairSpec(const GearPairSpec& spec) {
  GEARDYN_THROW_UNLESS(
      FinitePositive(spec.normal_module),
      "normal_module: must be finite and positive, got " << spec.normal_module << " m");
  GEARDYN_THROW_UNLESS(spec.normal_module >= kMinNormalModule,
                       "normal_module: must be at least "
                           << kMinNormalModule << " m (" << kMinNormalModule * 1e3
                           << " mm, below the finest micro gears), got " << spec.normal_module
                           << " m");
  GEARDYN_THROW_UNLESS(std::isfinite(spec.normal_pressure_angle) &&
                           spec.normal_pressure_angle > 0.0 &&
                           spec.normal_pressure_angle < kMaxPressureAngle,
                       "normal_pressure_angle: must lie in (0, 45) deg, got "
                           << RadToDeg(spec.normal_pressure_angle) << " deg");
  GEARDYN_THROW_UNLESS(
      std::isfinite(spec.helix_angle) && spec.helix_angle >= 0.0 &&
          spec.helix_angle < kMaxHelixAngle,
      "helix_angle: must lie in [0, 60) deg, got " << RadToDeg(spec.helix_angle) << " deg");
  if (spec.helix_angle == 0.0) {
    GEARDYN_THROW_UNLESS(spec.pinion_hand == HelixHand::kNone,
                         "pinion_hand: a spur pair (helix_angle = 0) must have hand kNone");
  } else {
    GEARDYN_THROW_UNLESS(spec.pinion_hand != HelixHand::kNone,
                         "pinion_hand: kNone given for helix_angle = "
                             << RadToDeg(spec.helix_angle) << " deg; choose kRight or kLeft");
  }
  GEARDYN_THROW_UNLESS(
      FiniteNonNegative(spec.min_tip_thickness_factor),
      "min_tip_thickness_factor: must be finite and >= 0, got " << spec.min_tip_thickness_factor);
  ValidateBlank(spec.pinion, "pinion");
  ValidateBlank(spec.gear, "gear");
  GEARDYN_THROW_UNLESS(spec.pinion.kind != GearKind::kRack,
                       "pinion.kind: a rack cannot be the pinion of a pair; name the rack 'gear' "
                       "(it may still be the driving member physically: the drive sign says "
                       "which way the load flows)");
  GEARDYN_THROW_UNLESS(spec.pinion.kind == GearKind::kExternal,
                       "pinion.kind: an internal gear cannot be the pinion; name the ring gear "
                       "'gear' (it may still be the driving member physically)");
  if (spec.gear.kind == GearKind::kInternal) {
    GEARDYN_THROW_UNLESS(spec.gear.teeth > spec.pinion.teeth,
                         "gear.teeth: an internal gear needs more teeth than its pinion, got z2 = "
                             << spec.gear.teeth << " vs z1 = " << spec.pinion.teeth
                             << " (difference " << spec.gear.teeth - spec.pinion.teeth << ")");
  }
  if (spec.center_distance) {
    GEARDYN_THROW_UNLESS(
        FinitePositive(*spec.center_distance),
        "center_distance: must be finite and positive, got " << *spec.center_distance << " m");
  }
}

HelixHand OppositeHand(HelixHand hand) {
  switch (hand) {
    case HelixHand::kRight:
      return HelixHand::kLeft;
    case HelixHand::kLeft:
      return HelixHand::kRight;
    case HelixHand::kNone:
      return HelixHand::kNone;
  }
  return HelixHand::kNone;
}

}  // namespace internal

namespace {

using internal::OppositeHand;

/// Transverse tooth thickness at radius r_y of a gear with reference radius r, reference
/// thickness s_t and kind; inv_alpha_y = inv(acos(r_b / r_y)).
double ThicknessAt(GearKind kind, double r, double s_t, double inv_alpha_t, double r_y,
                   double inv_alpha_y) {
  const double sign = kind == GearKind::kExternal ? 1.0 : -1.0;
  return 2.0 * r_y * (s_t / (2.0 * r) + sign * (inv_alpha_t - inv_alpha_y));
}

/// Total contact-line length extremes in the zone of action (spec 01 §4.1), in units of
/// b / cos β_b: with ε_α = n + f and ε_β = m + g (integer + fractional parts),
///   min = ε_α − (f g − max(0, f + g − 1)) / ε_β,   max = ε_α + (min(f, g) − f g) / ε_β,
/// and for spur gears (ε_β = 0) min = n, max = n + 1 (both ε_α when f = 0).
}  // namespace

namespace internal {

void ContactLineExtremes(double eps_alpha, double eps_beta, double* lo, double* hi) {
  const double n = std::floor(eps_alpha);
  const double f = eps_alpha - n;
  if (eps_beta == 0.0) {
    *lo = f == 0.0 ? eps_alpha : n;
    *hi = f == 0.0 ? eps_alpha : n + 1.0;
    return;
  }
  const double g = eps_beta - std::floor(eps_beta);
  *lo = eps_alpha - (f * g - std::max(0.0, f + g - 1.0)) / eps_beta;
  *hi = eps_alpha + (std::min(f, g) - f * g) / eps_beta;
}

void FillTransverseBasics(GearPairGeometry* pair) {
  GearPairGeometry& g = *pair;
  const double m_n = g.spec.normal_module;
  const double beta = g.spec.helix_angle;
  // ISO 21771 basic relations (transverse section).
  g.transverse_module = m_n / std::cos(beta);
  g.transverse_pressure_angle = std::atan(std::tan(g.spec.normal_pressure_angle) / std::cos(beta));
  g.base_helix_angle = std::atan(std::tan(beta) * std::cos(g.transverse_pressure_angle));
  g.transverse_base_pitch = kPi * g.transverse_module * std::cos(g.transverse_pressure_angle);
  g.normal_base_pitch = kPi * m_n * std::cos(g.spec.normal_pressure_angle);
}

void FillContactRatios(GearPairGeometry* pair) {
  GearPairGeometry& g = *pair;
  const GearPairSpec& spec = g.spec;
  const double m_n = spec.normal_module;
  // Contact ratios (ISO 21771): ε_α = g_α / p_bt, ε_β = b sin β / (π m_n), b = min(b1, b2).
  g.face_width = std::min(spec.pinion.face_width, spec.gear.face_width);
  g.pinion.face_width = spec.pinion.face_width;
  g.gear.face_width = spec.gear.face_width;
  g.transverse_contact_ratio = g.line_of_action_length / g.transverse_base_pitch;
  GEARDYN_THROW_UNLESS(g.transverse_contact_ratio >= 1.0,
                       "transverse_contact_ratio: " << g.transverse_contact_ratio
                                                    << " is below 1 (short by "
                                                    << 1.0 - g.transverse_contact_ratio << ")");
  g.overlap_contact_ratio = g.face_width * std::sin(spec.helix_angle) / (kPi * m_n);
  // Every unit of ε_γ is one more contact line evaluated at every θ (and one more slice set):
  // bound it where no manufactured face width reaches.
  GEARDYN_THROW_UNLESS(g.overlap_contact_ratio <= kMaxOverlapRatio,
                       "overlap_contact_ratio: ε_β = b sin β / (π m_n) = "
                           << g.overlap_contact_ratio << " exceeds " << kMaxOverlapRatio
                           << " (face width " << g.face_width << " m = " << g.face_width / m_n
                           << " normal modules): that many contact lines "
                              "at every angle; check face_width and normal_module");
  g.total_contact_ratio = g.transverse_contact_ratio + g.overlap_contact_ratio;
  // Contact-line lengths in the zone of action (closed forms of spec 01 §4.1).
  const double unit = g.face_width / std::cos(g.base_helix_angle);
  double lo = 0.0;
  double hi = 0.0;
  ContactLineExtremes(g.transverse_contact_ratio, g.overlap_contact_ratio, &lo, &hi);
  g.mean_contact_line_length = unit * g.transverse_contact_ratio;
  g.min_contact_line_length = unit * lo;
  g.max_contact_line_length = unit * hi;
}

}  // namespace internal

GearPairGeometry CalcGearPairGeometry(const GearPairSpec& spec) {
  internal::ValidateGearPairSpec(spec);
  if (spec.gear.kind == GearKind::kRack) return internal::CalcRackPairGeometry(spec);
  GearPairGeometry g;
  g.spec = spec;
  const bool internal = spec.gear.kind == GearKind::kInternal;
  const double sigma = internal ? -1.0 : 1.0;
  g.internal = internal;

  internal::FillTransverseBasics(&g);
  const double m_n = spec.normal_module;
  const double alpha_n = spec.normal_pressure_angle;
  const double beta = spec.helix_angle;
  const double m_t = g.transverse_module;
  const double alpha_t = g.transverse_pressure_angle;
  const double beta_b = g.base_helix_angle;
  const double inv_alpha_t = Involute(alpha_t);

  const double z1 = static_cast<double>(spec.pinion.teeth);
  const double z2 = static_cast<double>(spec.gear.teeth);
  const double x1 = spec.pinion.profile_shift;
  const double x2 = spec.gear.profile_shift;
  const double r1 = 0.5 * z1 * m_t;
  const double r2 = 0.5 * z2 * m_t;
  const double rb1 = r1 * std::cos(alpha_t);
  const double rb2 = r2 * std::cos(alpha_t);
  g.reference_center_distance = r2 + sigma * r1;
  const double tol = kLengthTolerance * m_n;

  // Zero-backlash operating pressure angle (ISO 21771 involute relation; internal form derived in
  // the file notes) and the matching centre distance a_w0 = a cos α_t / cos α_wt0.
  const double inv_alpha_w0 =
      inv_alpha_t + sigma * 2.0 * std::tan(alpha_n) * (x1 + x2) / (z2 + sigma * z1);
  GEARDYN_THROW_UNLESS(inv_alpha_w0 > 0.0,
                       "profile_shift_sum: x1 + x2 = "
                           << x1 + x2 << " leaves no zero-backlash centre distance (inv α_wt = "
                           << inv_alpha_w0 << " <= 0)");
  const double alpha_w0 = InverseInvolute(inv_alpha_w0);
  g.zero_backlash_center_distance =
      g.reference_center_distance * std::cos(alpha_t) / std::cos(alpha_w0);

  // Operating centre distance and pressure angle.
  const double rb_sum = rb2 + sigma * rb1;  // r_b2 ± r_b1
  double alpha_wt = alpha_w0;
  double a_w = g.zero_backlash_center_distance;
  if (spec.center_distance) {
    a_w = *spec.center_distance;
    GEARDYN_THROW_UNLESS(a_w > rb_sum,
                         "center_distance: " << Mm{a_w} << " is not above "
                                             << (internal ? "r_b2 - r_b1" : "r_b1 + r_b2") << " = "
                                             << Mm{rb_sum} << " (short by " << Mm{rb_sum - a_w}
                                             << "): no operating pressure angle exists");
    alpha_wt = std::acos(rb_sum / a_w);
  }
  g.center_distance = a_w;
  g.operating_pressure_angle = alpha_wt;
  const double inv_alpha_wt = Involute(alpha_wt);

  // Backlash on the operating pitch circle: j_wt = p_wt − s_w1 − s_w2 (ISO 21771).
  const double rw1 = rb1 / std::cos(alpha_wt);
  const double rw2 = rb2 / std::cos(alpha_wt);
  const double s_t1 = m_t * (0.5 * kPi + 2.0 * x1 * std::tan(alpha_n));
  const double s_t2 = m_t * (0.5 * kPi + 2.0 * x2 * std::tan(alpha_n));
  const double s_w1 = ThicknessAt(GearKind::kExternal, r1, s_t1, inv_alpha_t, rw1, inv_alpha_wt);
  const double s_w2 = ThicknessAt(spec.gear.kind, r2, s_t2, inv_alpha_t, rw2, inv_alpha_wt);
  const double p_wt = 2.0 * kPi * rw1 / z1;
  const double j_wt = p_wt - s_w1 - s_w2;
  if (j_wt < -tol) {
    // Interference as the profile-shift excess that causes it: at a fixed a_w a change Δx of
    // either shift changes the normal backlash by exactly −2 m_n sin α_n Δx (ISO 21771), and
    // j_bn = j_wt cos α_wt cos β_b. Designs printed with shifts rounded to 4 decimals carry
    // |Δx_1 + Δx_2| ≤ 1e-4, so up to that much is rounding: zero backlash plus a warning.
    const double j_bn = j_wt * std::cos(alpha_wt) * std::cos(beta_b);
    const double shift_excess = -j_bn / (2.0 * m_n * std::sin(alpha_n));
    std::ostringstream message;
    message << "center_distance: " << Mm{a_w} << " gives negative backlash j_wt = " << j_wt * 1e6
            << " um, j_bn = " << j_bn * 1e6 << " um (the flanks interfere, as if x1 + x2 were "
            << shift_excess << " too large); it is "
            << Mm{std::abs(a_w - g.zero_backlash_center_distance)}
            << (internal ? " above" : " below") << " the zero-backlash centre distance "
            << Mm{g.zero_backlash_center_distance};
    GEARDYN_THROW_UNLESS(shift_excess <= kShiftRoundingTolerance,
                         message.str() << " (more than the " << kShiftRoundingTolerance
                                       << " that rounding the shifts to 4 decimals explains)");
    g.interference_normal = -j_bn;
    message << "; within the " << kShiftRoundingTolerance
            << " of shifts rounded to 4 decimals: taken as zero backlash";
    g.warnings.push_back(message.str());
  }
  g.backlash_circumferential = std::max(j_wt, 0.0);
  g.backlash_normal = g.backlash_circumferential * std::cos(alpha_wt) * std::cos(beta_b);

  // Tip and root radii (ISO 21771; internal: profile moved toward the axis by x m_n).
  auto tip_radius = [&](const GearBlank& b, double r) {
    if (b.tip_diameter) return 0.5 * *b.tip_diameter;
    return b.kind == GearKind::kExternal ? r + m_n * (b.addendum_coefficient + b.profile_shift)
                                         : r - m_n * (b.addendum_coefficient + b.profile_shift);
  };
  auto root_radius = [&](const GearBlank& b, double r) {
    return b.kind == GearKind::kExternal ? r - m_n * (b.dedendum_coefficient - b.profile_shift)
                                         : r + m_n * (b.dedendum_coefficient - b.profile_shift);
  };
  const double ra1 = tip_radius(spec.pinion, r1);
  const double ra2 = tip_radius(spec.gear, r2);
  const double rf1 = root_radius(spec.pinion, r1);
  const double rf2 = root_radius(spec.gear, r2);
  // A given tip diameter beyond the one where the flanks meet (a pointed tooth) is no gear — most
  // often millimetres in the metre field. Checked here, before the path of contact, so that the
  // error names tip_diameter instead of the tip interference it causes further on (issue 16).
  auto check_given_tip = [&](const GearBlank& b, const std::string& name, double r, double rb,
                             double ra, double s_t) {
    if (!b.tip_diameter || ra <= rb) return;  // ra ≤ rb: the tip_radius check below names it
    const double s_at = ThicknessAt(b.kind, r, s_t, inv_alpha_t, ra, Involute(std::acos(rb / ra)));
    GEARDYN_THROW_UNLESS(s_at > 0.0, name << ".tip_diameter: " << Mm{2.0 * ra}
                                          << " is beyond the diameter where the tooth comes to a "
                                             "point (tip thickness "
                                          << Mm{s_at}
                                          << "); lengths are in metres: 44 mm is 0.044");
  };
  check_given_tip(spec.pinion, "pinion", r1, rb1, ra1, s_t1);
  check_given_tip(spec.gear, "gear", r2, rb2, ra2, s_t2);

  GEARDYN_THROW_UNLESS(rf1 > 0.0, "pinion.root_radius: " << Mm{rf1} << " is not positive (short by "
                                                         << Mm{-rf1} << ")");
  if (!internal) {
    GEARDYN_THROW_UNLESS(rf2 > 0.0, "gear.root_radius: " << Mm{rf2} << " is not positive (short by "
                                                         << Mm{-rf2} << ")");
  }
  GEARDYN_THROW_UNLESS(
      ra1 > rb1, "pinion.tip_radius: " << Mm{ra1} << " is not above the base radius " << Mm{rb1}
                                       << " (short by " << Mm{rb1 - ra1} << ")");
  GEARDYN_THROW_UNLESS(ra2 > rb2, "gear.tip_radius: " << Mm{ra2} << " is not above the base radius "
                                                      << Mm{rb2} << " (short by " << Mm{rb2 - ra2}
                                                      << "): no involute at the tip");
  GEARDYN_THROW_UNLESS(
      ra1 > rf1, "pinion.tip_radius: " << Mm{ra1} << " is not above the root radius " << Mm{rf1});
  GEARDYN_THROW_UNLESS(internal ? ra2 < rf2 : ra2 > rf2,
                       "gear.tip_radius: " << Mm{ra2} << " is not "
                                           << (internal ? "inside" : "above") << " the root radius "
                                           << Mm{rf2});

  // Path of contact on the line of action (roll lengths of the pinion, see file notes).
  const double t1t2 = a_w * std::sin(alpha_wt);
  const double ea1 = std::sqrt(ra1 * ra1 - rb1 * rb1);  // T1E, pinion tip
  const double ea2 = std::sqrt(ra2 * ra2 - rb2 * rb2);  // from T2 to where the gear tip meets
  const double rho_start = internal ? ea2 - t1t2 : t1t2 - ea2;  // T1A
  // A given centre distance must leave the tips overlapping along the line of action:
  // g_α = T1E − T1A > 0. With T1T2 = a_w sin α_wt = sqrt(a_w² − (r_b2 ± r_b1)²) this bounds a_w,
  // external pairs from above (g_α = T1E + T2A − T1T2), internal pairs from below
  // (g_α = T1E − T2A + T1T2, a bound only when T2A > T1E):
  //   external a_w < sqrt((T1E + T2A)² + (r_b1 + r_b2)²),
  //   internal a_w > sqrt((T2A − T1E)² + (r_b2 − r_b1)²).
  if (spec.center_distance) {
    const double path_length = ea1 - rho_start;  // g_α
    const double a_limit = std::hypot(internal ? ea2 - ea1 : ea1 + ea2, rb_sum);
    GEARDYN_THROW_UNLESS(
        path_length > 0.0,
        "center_distance: " << Mm{a_w}
                            << (internal ? " is below the smallest" : " exceeds the largest")
                            << " centre distance with a positive path of contact, " << Mm{a_limit}
                            << ", by " << Mm{std::abs(a_w - a_limit)}
                            << " (the tips no longer overlap along the line of action: g_α = "
                            << Mm{path_length} << ")");
  }
  GEARDYN_THROW_UNLESS(rho_start >= -tol,
                       "gear.tip_interference: the gear tip meets the pinion flank "
                           << Mm{-rho_start}
                           << " beyond the interference point T1, i.e. below the pinion's base "
                              "circle (reduce the gear's tip or add pinion profile shift)");
  if (!internal) {
    GEARDYN_THROW_UNLESS(ea1 <= t1t2 + tol,
                         "pinion.tip_interference: the pinion tip meets the gear flank "
                             << Mm{ea1 - t1t2}
                             << " beyond the interference point T2, i.e. below the gear's base "
                                "circle");
  }
  g.path_start_from_pinion_tangent = std::max(rho_start, 0.0);
  g.path_end_from_pinion_tangent = ea1;
  g.pitch_point_from_pinion_tangent = rb1 * std::tan(alpha_wt);
  g.line_of_action_length = ea1 - g.path_start_from_pinion_tangent;

  // Trochoid interference of internal pairs (recess: the pinion tip corner leaving the ring's
  // tooth space must not cut the ring's tip corner). SDP/SI "Elements of Metric Gear Technology"
  // Eq. (5-6)–(5-8) (= KHK Gear Technical Reference), evaluated in the transverse section:
  //   θ1 z1/z2 + inv α_wt − inv α_a2 ≥ θ2,
  //   θ1 = acos((r_a2² − r_a1² − a_w²)/(2 a_w r_a1)) + inv α_a1 − inv α_wt,
  //   θ2 = acos((a_w² + r_a2² − r_a1²)/(2 a_w r_a2)).
  // θ1 is the pinion rotation from the pitch-point position until its tip corner reaches P, the
  // intersection of the two tip circles; the ring turns θ1 z1/z2 meanwhile and its tip corner
  // started inv α_wt − inv α_a2 ahead of the pitch point; θ2 is the ring's angle of P.
  if (internal) {
    const double c1 = (ra2 * ra2 - ra1 * ra1 - a_w * a_w) / (2.0 * a_w * ra1);
    const double c2 = (a_w * a_w + ra2 * ra2 - ra1 * ra1) / (2.0 * a_w * ra2);
    if (std::abs(c1) <= 1.0 && std::abs(c2) <= 1.0) {
      const double inv_aa1 = Involute(std::acos(rb1 / ra1));
      const double inv_aa2 = Involute(std::acos(rb2 / ra2));
      const double theta1 = std::acos(c1) + inv_aa1 - inv_alpha_wt;
      const double theta2 = std::acos(c2);
      const double margin = theta1 * z1 / z2 + inv_alpha_wt - inv_aa2 - theta2;
      GEARDYN_THROW_UNLESS(margin >= 0.0,
                           "gear.trochoid_interference: the pinion tip cuts the ring's tip corner "
                           "when leaving mesh (angular margin "
                               << margin
                               << " rad < 0; z2 - z1 = " << spec.gear.teeth - spec.pinion.teeth
                               << "): increase the tooth-count difference or the ring's tip "
                                  "diameter");
    }
  }

  // Undercut of external gears generated by a rack (the undercut limit of DIN 3960:1987 and
  // Niemann/Winter, Maschinenelemente II; re-derived here): no undercut while the end of the
  // tool's straight flank, at height h_aP0 = h_fP − ρ_fP (1 − sin α_n) above the datum line (where
  // the tip radius ρ_fP is tangent to the flank), stays outside the interference point T, i.e.
  // (h_aP0* − x) m_n ≤ r sin² α_t with r = z m_n / (2 cos β) (heights are equal in the normal and
  // transverse sections):  x_min = h_aP0* − z sin² α_t / (2 cos β). Tools that take
  // h_aP0* = h_fP* (ρ ignored) are more conservative.
  auto check_undercut = [&](const GearBlank& b, const std::string& name) {
    if (b.kind != GearKind::kExternal) return;
    const double h_ap0 =
        b.dedendum_coefficient - b.root_radius_coefficient * (1.0 - std::sin(alpha_n));
    const double x_min = h_ap0 - static_cast<double>(b.teeth) * std::pow(std::sin(alpha_t), 2) /
                                     (2.0 * std::cos(beta));
    GEARDYN_THROW_UNLESS(b.profile_shift >= x_min - 1e-12,
                         name << ".undercut: x = " << b.profile_shift
                              << " is below the undercut limit x_min = " << x_min << " for z = "
                              << b.teeth << " (short by " << x_min - b.profile_shift << ")");
  };
  check_undercut(spec.pinion, "pinion");
  check_undercut(spec.gear, "gear");

  // Tooth thickness at the tip circle and its normal-section value s_an = s_at cos β_a with
  // tan β_a = tan β r_a / r (ISO 21771).
  auto fill_gear = [&](const GearBlank& b, const std::string& name, double r, double rb, double ra,
                       double rf, double rw, double s_t, GearGeometry* out) {
    const double inv_aa = Involute(std::acos(rb / ra));
    const double s_at = ThicknessAt(b.kind, r, s_t, inv_alpha_t, ra, inv_aa);
    const double beta_a = std::atan(std::tan(beta) * ra / r);
    const double s_an = s_at * std::cos(beta_a);
    const double s_min = spec.min_tip_thickness_factor * m_n;
    GEARDYN_THROW_UNLESS(s_an >= s_min,
                         name << ".tip_thickness_normal: " << Mm{s_an}
                              << " is below min_tip_thickness_factor * m_n = " << Mm{s_min}
                              << " (short by " << Mm{s_min - s_an} << ")");
    out->teeth = b.teeth;
    out->kind = b.kind;
    out->reference_radius = r;
    out->base_radius = rb;
    out->tip_radius = ra;
    out->root_radius = rf;
    out->operating_pitch_radius = rw;
    out->virtual_teeth =
        static_cast<double>(b.teeth) / (std::pow(std::cos(beta_b), 2) * std::cos(beta));
    out->tip_thickness_normal = s_an;
    out->tip_thickness_transverse = s_at;
    out->tooth_thickness_transverse = s_t;
    out->face_width = b.face_width;
    out->profile_shift = b.profile_shift;
  };
  fill_gear(spec.pinion, "pinion", r1, rb1, ra1, rf1, rw1, s_t1, &g.pinion);
  fill_gear(spec.gear, "gear", r2, rb2, ra2, rf2, rw2, s_t2, &g.gear);
  g.pinion.hand = spec.pinion_hand;
  g.gear.hand = internal ? spec.pinion_hand : OppositeHand(spec.pinion_hand);

  // Where each mating tip meets the flank (radius from the roll length on the line of action).
  g.pinion.start_of_active_profile_radius = std::hypot(rb1, g.path_start_from_pinion_tangent);
  g.gear.start_of_active_profile_radius = std::hypot(rb2, internal ? ea1 + t1t2 : t1t2 - ea1);

  // Radial tip clearance against the mating root circle (a tip must not reach the mating root).
  {
    const double c_pinion_tip = internal ? rf2 - (a_w + ra1) : a_w - ra1 - rf2;
    const double c_gear_tip = internal ? ra2 - (a_w + rf1) : a_w - ra2 - rf1;
    GEARDYN_THROW_UNLESS(c_pinion_tip >= -tol, "pinion.tip_clearance: the pinion tip reaches "
                                                   << Mm{-c_pinion_tip}
                                                   << " past the gear's root circle");
    GEARDYN_THROW_UNLESS(c_gear_tip >= -tol, "gear.tip_clearance: the gear tip reaches "
                                                 << Mm{-c_gear_tip}
                                                 << " past the pinion's root circle");
  }

  internal::FillContactRatios(&g);
  g.gear_ratio = z2 / z1;

  // Tooth-count facts for θ* (spec 01 §1).
  g.teeth_gcd = std::gcd(spec.pinion.teeth, spec.gear.teeth);
  g.hunting_period_meshes = static_cast<std::int64_t>(spec.pinion.teeth) / g.teeth_gcd *
                            static_cast<std::int64_t>(spec.gear.teeth);
  g.pinion_turns_per_hunting_period = spec.gear.teeth / g.teeth_gcd;
  g.gear_turns_per_hunting_period = spec.pinion.teeth / g.teeth_gcd;

  return g;
}

}  // namespace geardyn
