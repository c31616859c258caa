/// @file
/// Gear pairs and placements shared by the contact-geometry tests (tests/models/contact).
#pragma once

#include <numbers>

#include "geardyn/common/units.hpp"
#include "geardyn/models/contact/mesh_kinematics.hpp"
#include "geardyn/models/contact/tooth_flank.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"

namespace geardyn::test {

/// Kim et al. (2015) / Kahraman–Blankenship rig: m 3 mm, z 50/50, α 20°, r_a 78 mm, b 20 mm,
/// at a centre distance `center_mm` (150 mm = zero backlash).
inline GearPairSpec KimRigPair(double center_mm = 150.0) {
  GearPairSpec s;
  s.normal_module = 3e-3;
  s.normal_pressure_angle = DegToRad(20.0);
  s.pinion.teeth = 50;
  s.gear.teeth = 50;
  s.pinion.face_width = 0.02;
  s.gear.face_width = 0.02;
  s.pinion.tip_diameter = 0.156;
  s.gear.tip_diameter = 0.156;
  s.center_distance = center_mm * 1e-3;
  return s;
}

/// An unequal spur pair with profile shift and backlash: m 2.5 mm, z 23/41, x 0.2/−0.1.
inline GearPairSpec UnequalSpurPair() {
  GearPairSpec s;
  s.normal_module = 2.5e-3;
  s.normal_pressure_angle = DegToRad(20.0);
  s.pinion.teeth = 23;
  s.gear.teeth = 41;
  s.pinion.profile_shift = 0.2;
  s.gear.profile_shift = -0.1;
  s.pinion.face_width = 0.025;
  s.gear.face_width = 0.025;
  s.center_distance = 0.0805;
  return s;
}

/// A helical pair: m_n 2 mm, α_n 20°, β 20°, z 21/37, b 24 mm, hand given, with backlash.
inline GearPairSpec HelicalPair(HelixHand hand = HelixHand::kRight) {
  GearPairSpec s;
  s.normal_module = 2e-3;
  s.normal_pressure_angle = DegToRad(20.0);
  s.helix_angle = DegToRad(20.0);
  s.pinion_hand = hand;
  s.pinion.teeth = 21;
  s.gear.teeth = 37;
  s.pinion.face_width = 0.024;
  s.gear.face_width = 0.024;
  s.center_distance = 0.0619;
  return s;
}

/// Kinematics of a pair placed with the pinion at `pinion_center`, the line of centres at γ.
struct ContactPairSetup {
  GearPairGeometry pair;
  MeshFrame frame;
  ToothFlankGeometry pinion, gear;
};

inline ContactPairSetup MakeContactPair(const GearPairSpec& spec, int drive_sign = 1,
                                        double line_of_centres_angle = 0.3,
                                        const Vector3& pinion_center = Vector3(0.01, -0.02,
                                                                               0.005)) {
  ContactPairSetup s;
  s.pair = CalcGearPairGeometry(spec);
  s.frame = CalcMeshFrame(s.pair, pinion_center, line_of_centres_angle, drive_sign);
  s.pinion = MakeToothFlankGeometry(s.pair, s.pair.pinion);
  s.gear = MakeToothFlankGeometry(s.pair, s.pair.gear);
  return s;
}

}  // namespace geardyn::test
