#include "geardyn/models/contact/flank_relief.hpp"

#include <cmath>

#include "geardyn/common/check.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"

namespace geardyn {

namespace {

// Value and slope d/d(depth) of one band at `depth` into it (0 outside; as ReliefValue of
// tooth_modifications.cpp, which FlankModificationsTest compares against).
ReliefValue Band(const ProfileRelief& relief, double depth) {
  if (!relief.is_active() || depth <= 0.0) return {};
  const double u = depth / relief.length;
  if (relief.shape == ReliefShape::kLinear)
    return {relief.amount * u, relief.amount / relief.length};
  return {relief.amount * u * u, 2.0 * relief.amount * u / relief.length};
}

bool IsEmpty(const ToothModifications& m) {
  return !m.pinion_tip_relief.is_active() && !m.gear_tip_relief.is_active() &&
         !m.pinion_root_relief.is_active() && !m.gear_root_relief.is_active() &&
         m.lead_crowning == 0.0 && m.lead_slope == 0.0;
}

}  // namespace

FlankModifications::FlankModifications(const GearPairGeometry& pair,
                                       const ToothModifications& drive,
                                       const ToothModifications& coast)
    : drive_(drive), coast_(coast) {
  GEARDYN_THROW_UNLESS(!pair.internal,
                       "pair.internal: flank modifications of the contact geometry need an "
                       "external pair");
  // Validation as the rigid-pair model does (amounts, lengths within the path of contact).
  const ZoneOfAction zone = MakeZoneOfAction(pair, 1);
  const UnloadedSeparation check_drive(zone, drive);
  const UnloadedSeparation check_coast(zone, coast);
  pitch_roll_ = pair.pitch_point_from_pinion_tangent;
  tangent_length_ =
      (pair.pinion.base_radius + pair.gear.base_radius) * std::tan(pair.operating_pressure_angle);
  path_start_ = pair.path_start_from_pinion_tangent - pitch_roll_;
  path_end_ = pair.path_end_from_pinion_tangent - pitch_roll_;
  half_face_ = 0.5 * pair.face_width;
  empty_ = IsEmpty(drive) && IsEmpty(coast);
}

ReliefValue FlankModifications::Pinion(bool coast, double roll) const {
  const ToothModifications& m = coast ? coast_ : drive_;
  const double x = roll - pitch_roll_;
  const ReliefValue tip = Band(m.pinion_tip_relief, x - (path_end_ - m.pinion_tip_relief.length));
  const ReliefValue root =
      Band(m.pinion_root_relief, (path_start_ + m.pinion_root_relief.length) - x);
  return {tip.value + root.value, tip.slope - root.slope};
}

ReliefValue FlankModifications::Gear(bool coast, double roll) const {
  const ToothModifications& m = coast ? coast_ : drive_;
  const double x = (tangent_length_ - roll) - pitch_roll_;  // dx/dρ2 = −1
  const ReliefValue tip = Band(m.gear_tip_relief, (path_start_ + m.gear_tip_relief.length) - x);
  const ReliefValue root = Band(m.gear_root_relief, x - (path_end_ - m.gear_root_relief.length));
  return {tip.value + root.value, tip.slope - root.slope};
}

double FlankModifications::Lead(bool coast, double face) const {
  const ToothModifications& m = coast ? coast_ : drive_;
  const double u = face / half_face_;
  return m.lead_crowning * u * u + 0.5 * m.lead_slope * u;
}

}  // namespace geardyn
