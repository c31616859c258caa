/// @file
/// @brief The unloaded separation e of a gear pair at a point of a contact line (spec 01 §3):
/// tooth flank modifications (profile tip/root relief, lead crowning, lead slope) and
/// tooth-to-tooth errors (single pitch deviations, runout), with the tooth indexing over the
/// hunting period (spec 01 §1, θ*).
///
/// **What e is.** The mesh energy (spec 01 §3) is U = ½∫k [δ_η − σδ_ζ − e]²₊ dℓ: e [m] is the gap
/// between the two unloaded flanks at a contact point, measured along the tooth normal η
/// (positive = material removed = gap; negative = interference). It is the sum of
///   e = e_profile(x) + e_lead(y) + e_pair(n) + e_runout(θ)
/// in the coordinates of contact_lines.hpp: roll x [m] along the path of contact from the pitch
/// point p0 (the zone of action spans x ∈ [x_s, x_e), x_s = −g_α/2 − pitch_point_offset,
/// x_e = x_s + g_α; contact moves from x_s, where the gear tip meets the pinion root, to x_e, the
/// pinion tip), face coordinate y ∈ [−b, b] [m] along +Z from mid face, n the mesh cycle of the
/// tooth pair (below) and θ the mesh phase [rad]. The flank modifications are the same on every
/// tooth and describe the LOADED flanks (the ones of the zone, for its drive sign); use the other
/// flanks' data for the reversed drive.
///
/// **Flank modifications** — amounts normal to the flank (along η) [m]; for amounts given in the
/// transverse plane multiply by cos β_b first:
/// * Profile relief, linear or parabolic in the roll distance into the relieved band,
///   e = C_a·u or C_a·u² with u = (distance from the band's inner end)/L_a ∈ [0, 1] (the
///   parabolic shape starts tangentially). Where each band lies on the path of contact:
///   - pinion tip relief: the end of the path, x ∈ [x_e − L_a, x_e] (the pinion tip is in contact
///     at x_e);
///   - gear tip relief: the start, x ∈ [x_s, x_s + L_a] (the gear tip is in contact at x_s);
///   - pinion root relief: the start, x ∈ [x_s, x_s + L_f] (the pinion root meets the gear tip);
///   - gear root relief: the end, x ∈ [x_e − L_f, x_e].
///   Root relief is measured from the start of the active profile (the path end), not from the
///   form diameter.
/// * Lead crowning, parabolic across the face and zero at mid face: e = C_b (y/b)² (C_b at both
///   face ends; the pair's total: pinion + gear crowning).
/// * Lead slope / helix misalignment, linear across the face: e = f_Hβ y/B, i.e. ±f_Hβ/2 at the
///   face ends y = ±b, with f_Hβ > 0 opening the gap toward +Z (the pair's combined slope: helix
///   slope deviations of both members plus misalignment in the plane of action).
///
/// **Tooth indexing (mesh cycles).** The tooth pair of mesh cycle n ∈ ℤ is the one whose contact
/// line passes the reference point p0 (x = 0 at mid face) at θ = 2πn; its mid-face roll position
/// is x = (θ/2π − n)·p_bt. In ContactLineModel's wrapped indexing (line j at
/// x_j = (θ_w/2π + j) p_bt with θ = 2πm + θ_w, θ_w ∈ [0, 2π)) that is n = m − j: n grows with time,
/// a line keeps its n while it crosses the zone, and the line entering the zone later has the
/// larger n. In cycle n the pinion tooth i_1 = n mod z_1 meshes with the gear tooth
/// i_2 = n mod z_2 (non-negative remainders); both members' teeth are numbered in the order in
/// which they come into mesh (tooth i+1 engages one mesh cycle after tooth i, i.e. it trails
/// tooth i in that member's rotation). The pattern repeats after lcm(z_1, z_2) mesh cycles, the
/// hunting period.
///
/// **Tooth-to-tooth errors** — transverse quantities (rigid displacements of a tooth or a gear),
/// converted to the normal by cos β_b:
/// * Single pitch deviations f_p[i] [m] of each member, measured on the loaded flanks along the
///   transverse path of contact (base-circle arc: f_pt·cos α_t for deviations measured on the
///   reference circle): the pitch from tooth i−1 to tooth i (cyclically, tooth −1 = tooth z−1)
///   minus the nominal base pitch, positive when tooth i trails further than nominal. The lag of
///   tooth i's flank is the cumulative sum F[i] = Σ_{k=1..i} f_p[k] taken relative to the mean over
///   the teeth (a common offset of all teeth is a rigid rotation and is dropped, so pitch errors
///   add nothing to the mean separation). A closed gear needs Σ_i f_p[i] = 0 (checked; subtract
///   the mean Σ/z from each entry of measured data first). A lagging pinion flank recedes from
///   the gear flank it drives (gap), a lagging gear flank moves toward the pinion flank that
///   drives it (interference):  e_pair(n) = cos β_b (F_1[n mod z_1] − F_2[n mod z_2]).
/// * Runout: eccentricity r_e [m] ≥ 0 and phase φ [rad] per member: the offset of the gear's
///   geometric centre from its axis of rotation, at angle φ + Θ from the transverse line of
///   action x̂ (= the mesh frame's v for the zone's drive sign), measured in that member's
///   direction of rotation, where Θ = θ/z is the member's rotation since θ = 0. A pinion centre
///   displaced along +x̂ moves its flanks into the gear's, a gear centre along +x̂ moves its flanks
///   away, so the separation, uniform over all lines at θ, is
///   e_runout(θ) = cos β_b [−r_e1 cos(θ/z_1 + φ_1) + r_e2 cos(θ/z_2 + φ_2)]
///   (first order in r_e; once per revolution of each member).
///
/// **Period.** Without tooth-to-tooth errors e is the same for every tooth pair and the channels
/// built from it are mesh-periodic (period_meshes() = 1); with any pitch deviation or runout
/// they are periodic over the hunting period, period_meshes() = lcm(z_1, z_2) (the θ* of spec
/// 01 §1).
#pragma once

#include <cstdint>
#include <vector>

#include "geardyn/models/mesh/contact_lines.hpp"

namespace geardyn {

/// Shape of a profile relief as a function of u ∈ [0, 1], the relative depth into its band.
enum class ReliefShape {
  kLinear,     ///< e = C u (a kink at the band's inner end)
  kParabolic,  ///< e = C u² (tangent at the band's inner end)
};

/// @brief One profile relief band: amount, extent along the path of contact and shape.
struct ProfileRelief {
  double amount = 0.0;  ///< C [m] ≥ 0, normal to the flank, at the path end; 0 = no relief
  double length = 0.0;  ///< L [m], extent along the transverse path of contact, 0 < L ≤ g_α
  ReliefShape shape = ReliefShape::kLinear;  ///< linear or parabolic in the roll distance

  /// True when the relief removes material (amount > 0).
  bool is_active() const { return amount > 0.0; }
};

/// @brief Flank modifications common to all teeth (see the @file for the bands and signs).
struct ToothModifications {
  ProfileRelief pinion_tip_relief;   ///< band [x_e − L, x_e] (end of the path)
  ProfileRelief gear_tip_relief;     ///< band [x_s, x_s + L] (start of the path)
  ProfileRelief pinion_root_relief;  ///< band [x_s, x_s + L] (start of the path)
  ProfileRelief gear_root_relief;    ///< band [x_e − L, x_e] (end of the path)
  double lead_crowning = 0.0;        ///< C_b [m] ≥ 0: e = C_b (y/b)², the pair's total
  double lead_slope = 0.0;           ///< f_Hβ [m], signed: e = f_Hβ y/B (±f_Hβ/2 at y = ±b)
};

/// @brief Tooth-to-tooth errors of the two members (see the @file for signs and indexing).
struct ToothErrors {
  int pinion_teeth = 0;  ///< z_1 ≥ 1 [-]; needed when any error below is non-zero
  int gear_teeth = 0;    ///< z_2 ≥ 1 [-]; needed when any error below is non-zero
  /// (z_1 or empty) single pitch deviations f_p[i] of the pinion's loaded flanks along the
  /// transverse path of contact [m]; Σ = 0.
  std::vector<double> pinion_pitch_deviations;
  /// (z_2 or empty) single pitch deviations of the gear's loaded flanks [m]; Σ = 0.
  std::vector<double> gear_pitch_deviations;
  double pinion_runout = 0.0;        ///< r_e1 [m] ≥ 0, eccentricity of the pinion
  double pinion_runout_phase = 0.0;  ///< φ_1 [rad], angle from x̂ at θ = 0, in its rotation sense
  double gear_runout = 0.0;          ///< r_e2 [m] ≥ 0, eccentricity of the gear
  double gear_runout_phase = 0.0;  ///< φ_2 [rad], angle from x̂ at θ = 0, in its rotation sense
};

/// @brief Validated description of the unloaded separation e(x, y, n, θ) on a zone of action.
///
/// Immutable; the pointwise functions never allocate.
class UnloadedSeparation {
 public:
  /// @param[in] zone the zone of action (validated again here: length, face_width,
  ///   transverse_base_pitch, base_helix_angle as ContactLineModel).
  /// @param[in] modifications flank modifications.
  /// @param[in] errors tooth-to-tooth errors.
  /// @throws InvalidInput naming the field ("modifications.pinion_tip_relief.amount",
  ///   "modifications.gear_root_relief.length", "modifications.lead_crowning",
  ///   "errors.pinion_pitch_deviations", "errors.gear_teeth", ...): non-finite values, negative
  ///   amounts, lengths or eccentricities, a relief length that is zero for a non-zero amount or
  ///   longer than the path of contact g_α, a pitch-deviation vector whose size is not the tooth
  ///   count or whose sum is not zero (relative 1e-9 of Σ|f_p|), tooth counts < 1 when errors are
  ///   given, or a hunting period lcm(z_1, z_2) above 2^31.
  UnloadedSeparation(const ZoneOfAction& zone, const ToothModifications& modifications,
                     const ToothErrors& errors = {});

  /// The zone of action.
  const ZoneOfAction& zone() const { return zone_; }
  /// The flank modifications, as given.
  const ToothModifications& modifications() const { return modifications_; }
  /// The tooth-to-tooth errors, as given.
  const ToothErrors& errors() const { return errors_; }

  /// x_s = −g_α/2 − pitch_point_offset, start of the path of contact [m] (roll from p0).
  double path_start() const { return x_start_; }
  /// x_e = x_s + g_α, end of the path of contact [m].
  double path_end() const { return x_end_; }
  /// True when a pitch deviation or a runout is non-zero (e differs between tooth pairs).
  bool has_tooth_errors() const { return has_tooth_errors_; }
  /// True when a profile relief, crowning or slope is non-zero.
  bool has_flank_modifications() const;
  /// P [-]: 1 without tooth-to-tooth errors, else lcm(z_1, z_2) (the hunting period).
  std::int64_t period_meshes() const { return period_meshes_; }

  /// @brief Roll positions x [m] strictly inside (x_s, x_e), sorted, where e_profile has a kink
  /// (the inner ends of the active relief bands): e_profile is a polynomial of degree ≤ 2 in x
  /// between them.
  const std::vector<double>& profile_kinks() const { return profile_kinks_; }

  /// @brief e_profile(x) [m]: the sum of the four relief bands at roll x [m] (0 outside them).
  double ProfileSeparation(double roll) const;
  /// @brief e_lead(y) = C_b (y/b)² + f_Hβ y/B [m] at face coordinate y [m].
  double LeadSeparation(double face) const;
  /// @brief e_pair(n) = cos β_b (F_1[n mod z_1] − F_2[n mod z_2]) [m] of mesh cycle n (0
  /// without pitch deviations).
  double ToothPairSeparation(std::int64_t cycle) const;
  /// @brief e_runout(θ) [m] at mesh phase θ [rad] (θ unwrapped: the members' rotation is θ/z).
  double RunoutSeparation(double theta) const;
  /// @brief e = e_profile(x) + e_lead(y) + e_pair(n) + e_runout(θ) [m].
  double Separation(double roll, double face, std::int64_t cycle, double theta) const;

  /// @brief The pinion tooth i_1 = n mod z_1 ∈ [0, z_1) in mesh in cycle n (needs z_1 ≥ 1).
  int PinionTooth(std::int64_t cycle) const;
  /// @brief The gear tooth i_2 = n mod z_2 ∈ [0, z_2) in mesh in cycle n (needs z_2 ≥ 1).
  int GearTooth(std::int64_t cycle) const;
  /// @brief (z_1 or empty) lag F_1[i] of each pinion flank along the transverse path [m] (mean 0).
  const std::vector<double>& pinion_flank_lags() const { return pinion_lags_; }
  /// @brief (z_2 or empty) lag F_2[i] of each gear flank along the transverse path [m] (mean 0).
  const std::vector<double>& gear_flank_lags() const { return gear_lags_; }

 private:
  ZoneOfAction zone_;
  ToothModifications modifications_;
  ToothErrors errors_;
  std::vector<double> profile_kinks_;
  std::vector<double> pinion_lags_;
  std::vector<double> gear_lags_;
  double x_start_ = 0.0, x_end_ = 0.0, b_ = 0.0, cos_ = 1.0;
  bool has_tooth_errors_ = false;
  std::int64_t period_meshes_ = 1;
};

}  // namespace geardyn
