/// @file
/// @brief Profile and lead modifications of the contact simulator's flanks, evaluated at each
/// flank's own roll distance (per tooth, per flank, per face slice), with their slopes.
///
/// The data are tooth_modifications.hpp's (ToothModifications; amounts normal to the flank, along
/// η, bands along the path of contact). There the bands are placed on the path coordinate x of a
/// rigid pair; here each member's bands are put on that member's own roll distance ρ, so that a
/// deflected or displaced tooth carries its relief with it:
/// * pinion bands at x = ρ1 − T1C (T1C = r_b1 tan α_wt, x from the pitch point);
/// * gear bands at x = (T1T2 − ρ2) − T1C with the nominal T1T2 = (r_b1 + r_b2) tan α_wt.
/// For a rigid pair at the nominal centre distance ρ1 + ρ2 = T1T2 and the two agree with
/// UnloadedSeparation::ProfileSeparation (tested). The modifications given describe the drive
/// flanks; the coast flanks get their own set (none by default). The normal separation a contact
/// adds is e = e_1(ρ1) + e_2(ρ2) + e_lead(y); the transverse one e / cos β_b.
#pragma once

#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/mesh/tooth_modifications.hpp"

namespace geardyn {

/// @brief Value and slope of a separation term.
struct ReliefValue {
  double value = 0.0;  ///< e [m]
  double slope = 0.0;  ///< de/dρ [-]
};

/// @brief Per-flank profile and lead modifications of a pair.
class FlankModifications {
 public:
  /// @param[in] pair derived pair geometry (external).
  /// @param[in] drive modifications of the drive flanks (validated as UnloadedSeparation does).
  /// @param[in] coast modifications of the coast flanks.
  /// @throws InvalidInput as UnloadedSeparation for invalid amounts or lengths.
  FlankModifications(const GearPairGeometry& pair, const ToothModifications& drive,
                     const ToothModifications& coast = {});

  /// e_1(ρ1) [m] of a pinion flank and its slope, ρ1 the pinion's roll distance [m].
  ReliefValue Pinion(bool coast, double roll) const;
  /// e_2(ρ2) [m] of a gear flank and its slope, ρ2 the gear's roll distance [m].
  ReliefValue Gear(bool coast, double roll) const;
  /// e_lead(y) [m] at face coordinate y from mid face [m] (crowning and slope).
  double Lead(bool coast, double face) const;
  /// True when any modification is non-zero.
  bool empty() const { return empty_; }

 private:
  ToothModifications drive_, coast_;
  double pitch_roll_ = 0.0;      // T1C [m]
  double tangent_length_ = 0.0;  // nominal T1T2 [m]
  double path_start_ = 0.0, path_end_ = 0.0, half_face_ = 0.0;
  bool empty_ = true;
};

}  // namespace geardyn
