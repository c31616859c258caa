/// @file
/// @brief Involute gear-pair geometry (ISO 21771 / ISO 53 basic rack): inputs, derived
/// quantities and the checks that reject pairs that cannot mesh.
///
/// All lengths in metres, angles in radians (degrees appear only at the input boundary, in the
/// scene reader). "Pinion" and "gear" are the two members of a pair as the user named them (the
/// pinion drives); ISO 6336's "pinion = the gear with fewer teeth" is applied internally where
/// the standard needs it (see iso_stiffness.hpp).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace geardyn {

/// Hand of a helical gear. Spur gears have kNone.
enum class HelixHand { kNone, kRight, kLeft };

/// External (teeth outside), internal (ring) gear, or a rack (straight teeth, infinite radius;
/// only as the `gear` of a pair, see CalcGearPairGeometry "Rack").
enum class GearKind { kExternal, kInternal, kRack };

/// @brief Tooth and blank data of one gear of a pair (per-gear inputs).
///
/// Profile shift sign convention (ISO 21771): a positive x moves the basic rack profile away from
/// the gear's material for external gears (thicker root, thicker tooth at the reference circle).
/// For an internal gear a positive x likewise thickens its teeth: the whole profile moves by x m_n
/// toward the gear axis, so r_a = r − m_n (h_aP* + x), r_f = r + m_n (h_fP* − x) and the
/// transverse tooth thickness is s_t = m_t (π/2 + 2 x tan α_n) for both kinds (ISO 21771 with a
/// signed tooth count). KHK / SDP-SI tables use the opposite sign for internal gears:
/// x(ISO) = −x(KHK). See the implementation notes in gear_geometry.cpp.
struct GearBlank {
  int teeth = 0;  ///< z [-] (positive also for internal gears; a rack's count is not used)
  GearKind kind = GearKind::kExternal;    ///< external or internal (ring) gear
  double face_width = 0.0;                ///< b [m]
  double profile_shift = 0.0;             ///< x [-]
  double addendum_coefficient = 1.0;      ///< h_aP* of the basic rack [-] (tooth addendum / m_n)
  double dedendum_coefficient = 1.25;     ///< h_fP* of the basic rack [-] (tooth dedendum / m_n)
  double root_radius_coefficient = 0.38;  ///< ρ_fP* of the basic rack [-] (tool tip radius / m_n)
  std::optional<double> tip_diameter;     ///< d_a [m]; if set, replaces the addendum rule
  std::optional<double> web_thickness;    ///< b_s [m], web of a webbed blank (ISO 6336-1 C_R)
  std::optional<double> rim_thickness;    ///< s_R [m], rim under the teeth (ISO 6336-1 C_R)
};

/// Smallest normal module accepted [m]: 10 µm, below the finest micro-moulded and watch gears
/// (≈ 0.02–0.05 mm). Smaller values are unit mistakes (mm given as m is 10³ too large, not
/// small), and they make ε_β = b sin β/(π m_n), hence the contact-line count, explode.
inline constexpr double kMinNormalModule = 1e-5;
/// Largest overlap ratio ε_β accepted [-]: 100 contact lines across the face, i.e. b/m_n ≈ 360 at
/// β = 60° and ≈ 1200 at 15°, where manufactured pairs stay below b/m_n ≈ 100 (ISO 6336-1
/// treats b/m_n ≲ 50). Each unit of ε_γ is one more contact line at every angle.
inline constexpr double kMaxOverlapRatio = 100.0;

/// @brief Inputs of a parallel-axis involute gear pair.
struct GearPairSpec {
  double normal_module = 0.0;          ///< m_n [m]
  double normal_pressure_angle = 0.0;  ///< α_n [rad]
  double helix_angle = 0.0;            ///< β at the reference circle [rad], 0 ≤ β < 60°
  /// The pinion's hand; an external mate has the other hand, a ring gear the same one.
  HelixHand pinion_hand = HelixHand::kNone;
  GearBlank pinion;                       ///< the driving member as the user named it
  GearBlank gear;                         ///< the driven member (may be internal)
  std::optional<double> center_distance;  ///< a_w [m]; if absent: zero-backlash centre distance
  double min_tip_thickness_factor = 0.2;  ///< reject s_an < factor · m_n (tip too thin) [-]
};

/// @brief Derived geometry of one gear in its pair.
struct GearGeometry {
  int teeth = 0;  ///< z [-]
  GearKind kind = GearKind::kExternal;
  HelixHand hand = HelixHand::kNone;    ///< its own hand
  double reference_radius = 0.0;        ///< r = z m_t / 2 [m]
  double base_radius = 0.0;             ///< r_b = r cos α_t [m]
  double tip_radius = 0.0;              ///< r_a [m] (for internal gears: the inner, tip circle)
  double root_radius = 0.0;             ///< r_f [m]
  double operating_pitch_radius = 0.0;  ///< r_w = r_b / cos α_wt [m]
  double virtual_teeth = 0.0;           ///< z_n = z / (cos² β_b cos β) [-]
  double tip_thickness_normal = 0.0;    ///< s_an, normal tooth thickness at the tip circle [m]
  /// Radius where the mating tip meets this flank [m]: the innermost contact radius of an
  /// external gear (start of active profile), the outermost one of an internal gear.
  double start_of_active_profile_radius = 0.0;
  double face_width = 0.0;     ///< b [m]
  double profile_shift = 0.0;  ///< x [-]
  // Added by the geometry implementation (not in the first contract):
  double tooth_thickness_transverse = 0.0;  ///< s_t = m_t (π/2 + 2 x tan α_n) at r [m]
  double tip_thickness_transverse = 0.0;    ///< s_at, transverse tooth thickness at r_a [m]
};

/// @brief Everything derived from a GearPairSpec. Angles in rad, lengths in m.
struct GearPairGeometry {
  GearPairSpec spec;  ///< the inputs, as given
  GearGeometry pinion;
  GearGeometry gear;
  bool internal = false;                   ///< true when the gear is internal (a ring)
  bool rack = false;                       ///< true when the gear is a rack (see "Rack")
  double transverse_module = 0.0;          ///< m_t = m_n / cos β [m]
  double transverse_pressure_angle = 0.0;  ///< α_t [rad]
  double base_helix_angle = 0.0;           ///< β_b [rad]
  /// α_wt, transverse, at the operating centre distance [rad]
  double operating_pressure_angle = 0.0;
  double reference_center_distance = 0.0;      ///< a = (r_2 ± r_1) [m]
  double center_distance = 0.0;                ///< a_w, the operating centre distance [m]
  double zero_backlash_center_distance = 0.0;  ///< a_w at which the flanks close on both sides [m]
  double backlash_circumferential = 0.0;       ///< j_wt on the operating pitch circle [m] (≥ 0)
  double backlash_normal = 0.0;                ///< j_bn = j_wt cos α_wt cos β_b [m]
  /// Interference accepted as zero backlash [m]: −j_bn of a given a_w slightly below the
  /// zero-backlash distance (above for internal pairs), at most what rounding x1 + x2 by 1e-4
  /// causes, 2e-4 m_n sin α_n (see CalcGearPairGeometry); 0 otherwise.
  double interference_normal = 0.0;
  double transverse_base_pitch = 0.0;     ///< p_bt = π m_t cos α_t [m]
  double normal_base_pitch = 0.0;         ///< p_bn = π m_n cos α_n [m]
  double line_of_action_length = 0.0;     ///< g_α, length of path of contact (transverse) [m]
  double face_width = 0.0;                ///< common face width b = min(b_1, b_2) [m]
  double transverse_contact_ratio = 0.0;  ///< ε_α = g_α / p_bt [-]
  double overlap_contact_ratio = 0.0;     ///< ε_β = b sin β / (π m_n) [-]
  double total_contact_ratio = 0.0;       ///< ε_γ = ε_α + ε_β [-]
  double gear_ratio = 0.0;                ///< u = z_gear / z_pinion [-]
  // Tooth-count facts that θ* needs (spec 01 §1).
  int teeth_gcd = 0;                        ///< gcd(z_1, z_2)
  std::int64_t hunting_period_meshes = 0;   ///< mesh cycles per hunting period = lcm(z_1, z_2)
  int pinion_turns_per_hunting_period = 0;  ///< n_2 = z_2 / gcd
  int gear_turns_per_hunting_period = 0;    ///< n_1 = z_1 / gcd
  // Total contact-line length in the zone of action (spec 01 §4.1): closed forms in ε_α, ε_β.
  double mean_contact_line_length = 0.0;  ///< b ε_α / cos β_b [m]
  double min_contact_line_length = 0.0;   ///< [m]
  double max_contact_line_length = 0.0;   ///< [m]
  // Added by the geometry implementation: where the path of contact lies on the line of action,
  // as distances from T1, the point where the line of action touches the pinion's base circle
  // (the pinion's roll lengths ρ). Contact runs from A to E; C is the pitch point.
  double path_start_from_pinion_tangent = 0.0;   ///< T1A: mating tip meets the pinion flank [m]
  double path_end_from_pinion_tangent = 0.0;     ///< T1E = sqrt(r_a1² − r_b1²): pinion tip [m]
  double pitch_point_from_pinion_tangent = 0.0;  ///< T1C = r_b1 tan α_wt [m]
  /// Notes on inputs accepted with an adjustment (interference within the rounding tolerance).
  std::vector<std::string> warnings;
};

/// @brief Derives the pair geometry and rejects pairs that cannot mesh.
///
/// Without `center_distance` the pair runs at its zero-backlash centre distance. Rejections, in
/// the order checked (the message starts with the name): bad scalars ("normal_module" not finite
/// or below kMinNormalModule,
/// "normal_pressure_angle" outside (0, 45°), "helix_angle" outside [0, 60°), "pinion_hand"
/// inconsistent with β, "<member>.teeth" < 3, "<member>.face_width", ...), "pinion.kind"
/// (internal pinion), "gear.teeth" (ring not larger than its pinion), "profile_shift_sum" (no
/// zero-backlash distance), "center_distance" (not above r_b2 ± r_b1, or negative backlash
/// beyond the rounding tolerance: a given a_w may interfere by at most what a profile-shift sum
/// too large by 1e-4 causes, j_bn ≥ −2e-4 m_n sin α_n, the rounding of two shifts printed to 4
/// decimals; such a pair runs with zero backlash, interference_normal and a warning),
/// "<member>.root_radius", "<member>.tip_radius" (tip not above its base circle),
/// "center_distance" (a given a_w at which the tips no longer overlap along the line of action,
/// g_α ≤ 0: external pairs above sqrt((T1E + T2A)² + (r_b1 + r_b2)²), internal pairs below
/// sqrt((T2A − T1E)² + (r_b2 − r_b1)²), with T1E = sqrt(r_a1² − r_b1²), T2A = sqrt(r_a2² − r_b2²)),
/// "<member>.tip_interference" (a tip meets the mate below its base circle),
/// "gear.trochoid_interference" (internal pairs), "<member>.undercut",
/// "<member>.tip_thickness_normal", "<member>.tip_clearance" (a tip reaches the mating root
/// circle), "transverse_contact_ratio" (< 1), "overlap_contact_ratio" (> kMaxOverlapRatio).
/// @throws InvalidInput whose message starts with the quantity's name (e.g.
///   "transverse_contact_ratio: 0.93 is below 1 (short by 0.07)") and says by how much the bound
///   is missed.
///
/// **Rack** (spec.gear.kind == kRack, Cardona's gear–rack pair): the pinion meshes with a basic-
/// rack-shaped rack of addendum h_aP* m_n and dedendum h_fP* m_n (the gear blank's coefficients)
/// and reference tooth thickness π m_n / 2. `center_distance` is then the distance from the
/// pinion axis to the rack's reference line, by default r_1 + x_1 m_n (zero backlash); the
/// pinion rolls on its reference circle whatever the mounting, so α_wt = α_t and r_w1 = r_1.
/// With d_a = the rack tip line's distance from the pinion axis (center_distance − h_aP* m_n), the
/// path of contact starts at the roll length T1A = (d_a − r_b1 cos α_t) / sin α_t (where the rack
/// tip line crosses the line of action) and ends at the pinion tip T1E; backlash
/// j_wt = 2 (a_w − a_w0) tan α_t on the pitch line. The limit of a gear with z_2 → ∞ and x_2 = 0
/// (tested). The rack's radii, virtual teeth and gear_ratio are +∞; its hunting period is the
/// pinion's z_1 mesh cycles (the rack's own errors never repeat). Rack rejections:
/// "gear.profile_shift" (≠ 0: move the rack with center_distance), "gear.tip_diameter" (a rack has
/// none), "gear.tip_interference" (T1A < 0: the rack tip meets the pinion below its base circle),
/// "gear.tip_thickness_normal" (the rack's top land π/2 − 2 h_aP* tan α_n, in m_n, below
/// min_tip_thickness_factor), the tip clearances, and the pinion checks as for any pair.
GearPairGeometry CalcGearPairGeometry(const GearPairSpec& spec);

}  // namespace geardyn
