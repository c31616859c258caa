/// @file
/// Published gear stages shared by the reference tests: their data as printed by the source.
#pragma once

#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"

namespace geardyn::test {

/// NREL 5 MW reference gearbox, parallel stage, as the KISSsoft 03/2017 report "stage_03" prints
/// it (repository gfsReboucas/Drivetrain, file @NREL_5MW/stage_03.rtf): m_n 14 mm, α_n 20°,
/// β 10°, z 24/95, b 360 mm, x 0.4800/0.6691 (printed to 4 decimals), a = 861 mm (whole
/// millimetres), solid blanks, standard tips (the report's tip alteration and webs are added by
/// the tests that need them).
inline GearPairSpec NrelParallelStage() {
  constexpr double kMm = 1e-3;
  GearPairSpec s;
  s.normal_module = 14.0 * kMm;
  s.normal_pressure_angle = DegToRad(20.0);
  s.helix_angle = DegToRad(10.0);
  s.pinion_hand = HelixHand::kRight;
  s.pinion.teeth = 24;
  s.gear.teeth = 95;
  s.pinion.profile_shift = 0.4800;
  s.gear.profile_shift = 0.6691;
  s.pinion.face_width = 360.0 * kMm;
  s.gear.face_width = 360.0 * kMm;
  s.center_distance = 861.0 * kMm;
  return s;
}

}  // namespace geardyn::test
