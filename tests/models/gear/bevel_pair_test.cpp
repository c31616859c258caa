// The straight bevel pair's geometry (issue 19) against published numbers and independent
// computations:
// * ISO 23509:2016's worked example (Gleason spiral bevel, z 14/39, m_et 4.536 mm, b 25.4 mm,
//   Σ 90°, its input d_e2 = 176.893 mm), as printed in D-Soft Con's BevGear report
//   (http://www.dsoftcon.be/BevGear/en/GeometryOutputHtml.htm, "Gleas FM ISO 23509 page 79"):
//   δ₁ = 19.7468°, δ₂ = 70.2532°, d_e2 = 176.893 mm, R_m = 81.273 mm, d_m1 = 54.919 mm,
//   d_m2 = 152.987 mm, m_mt = 3.9227 mm (with its x_hm1 = 0.505; unshifted, the 14-tooth pinion
//   would interfere). The pitch-cone data do not depend on the spiral angle,
//   so the straight pair with the same teeth, module and face has them too.
// * KHK Gear Technical Reference, Table 4.13 ("Gleason straight bevel gear", z 20/40, m 3 mm,
//   Σ 90°): δ₁ = 26.56505°, δ₂ = 63.43495°, d = 60 / 120 mm, R_e = 67.08204 mm.
// * The virtual spur pair: a pair whose virtual tooth counts are integers (z 36/48, Σ 90°:
//   cos δ₁ = 4/5, cos δ₂ = 3/5, z_v = 45/80) against the spur-gear geometry of those teeth at the
//   mean module (CalcGearPairGeometry: contact ratio, path of contact).
// * Bad inputs, each refused at its field.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/bevel_geometry.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "support/bevel_specs.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

BevelPairSpec Spec(int z1, int z2, double m_et, double b, double sigma_deg = 90.0) {
  return test::BevelSpec(z1, z2, m_et, b, sigma_deg);
}

TEST(BevelPairTest, ConeDataOfTheIso23509Example) {
  // The report prints 4 decimals of a degree and 3 of a millimetre: half a unit of the last one.
  // The example's input is d_e2 = 176.893 mm (m_et = d_e2 / z2 = 4.53572 mm, printed 4.5360).
  BevelPairSpec spec = Spec(14, 39, 176.893e-3 / 39, 25.4e-3);
  spec.pinion_profile_shift = 0.505;  // x_hm1 of the example (the cone data do not depend on it)
  const BevelPairGeometry g = CalcBevelPairGeometry(spec);
  EXPECT_NEAR(RadToDeg(g.pinion_cone_angle), 19.7468, 5e-5);
  EXPECT_NEAR(RadToDeg(g.gear_cone_angle), 70.2532, 5e-5);
  EXPECT_NEAR(g.gear_outer_pitch_diameter * 1e3, 176.893, 5e-4);
  EXPECT_NEAR(g.mean_cone_distance * 1e3, 81.273, 5e-4);
  // d_m1: the report prints 54.919; 2 R_m sin(delta_1) of its own printed R_m and delta_1
  // is 54.9183.
  EXPECT_NEAR(2.0 * g.pinion_mean_pitch_radius * 1e3, 54.919, 1e-3);
  EXPECT_NEAR(2.0 * g.gear_mean_pitch_radius * 1e3, 152.987, 5e-4);
  EXPECT_NEAR(g.mean_module * 1e3, 3.9227, 5e-5);
}

TEST(BevelPairTest, ConeDataOfTheKhkStraightBevelExample) {
  const BevelPairGeometry g = CalcBevelPairGeometry(Spec(20, 40, 3e-3, 22e-3));
  EXPECT_NEAR(RadToDeg(g.pinion_cone_angle), 26.56505, 5e-6);
  EXPECT_NEAR(RadToDeg(g.gear_cone_angle), 63.43495, 5e-6);
  EXPECT_NEAR(g.pinion_outer_pitch_diameter * 1e3, 60.0, 1e-12);
  EXPECT_NEAR(g.gear_outer_pitch_diameter * 1e3, 120.0, 1e-12);
  EXPECT_NEAR(g.outer_cone_distance * 1e3, 67.08204, 5e-6);
  // Both pitch cones end on the same heel: R_e = d_e2 / (2 sin δ2) too.
  EXPECT_NEAR(g.outer_cone_distance,
              g.gear_outer_pitch_diameter / (2.0 * std::sin(g.gear_cone_angle)), 1e-15);
}

TEST(BevelPairTest, VirtualSpurPairIsTheSpurGeometryOfTheVirtualTeeth) {
  for (double x : {0.0, 0.25}) {
    BevelPairSpec spec = Spec(36, 48, 2.5e-3, 20e-3);
    spec.pinion_profile_shift = x;
    const BevelPairGeometry g = CalcBevelPairGeometry(spec);
    EXPECT_NEAR(g.pinion_virtual_teeth, 45.0, 1e-12);
    EXPECT_NEAR(g.gear_virtual_teeth, 80.0, 1e-12);
    GearPairSpec spur;
    spur.normal_module = g.mean_module;
    spur.normal_pressure_angle = spec.pressure_angle;
    spur.pinion.teeth = 45;
    spur.gear.teeth = 80;
    spur.pinion.face_width = spur.gear.face_width = spec.face_width;
    spur.pinion.profile_shift = x;
    spur.gear.profile_shift = -x;
    const GearPairGeometry s = CalcGearPairGeometry(spur);
    EXPECT_NEAR(g.virtual_center_distance, s.center_distance, 1e-12 * s.center_distance) << x;
    EXPECT_NEAR(g.path_of_contact_length, s.line_of_action_length, 1e-12 * s.center_distance);
    EXPECT_NEAR(g.contact_ratio, s.transverse_contact_ratio, 1e-10) << x;
    EXPECT_NEAR(g.path_start_from_pinion_tangent, s.path_start_from_pinion_tangent,
                1e-12 * s.center_distance);
  }
}

TEST(BevelPairTest, AnyShaftAngleKeepsTheConesOnOneElement) {
  // Σ = 45°, 90°, 120°: r_m1 / r_m2 = z1 / z2 (rolling without slip) and δ1 + δ2 = Σ; the pitch
  // cones touch along one element, so R_m sin δ = r_m for both.
  for (double sigma : {45.0, 90.0, 120.0}) {
    const BevelPairGeometry g = CalcBevelPairGeometry(Spec(17, 29, 3e-3, 15e-3, sigma));
    EXPECT_NEAR(g.pinion_cone_angle + g.gear_cone_angle, DegToRad(sigma), 1e-15);
    EXPECT_NEAR(g.pinion_mean_pitch_radius / g.gear_mean_pitch_radius, 17.0 / 29.0, 1e-15);
    EXPECT_NEAR(g.mean_cone_distance * std::sin(g.pinion_cone_angle), g.pinion_mean_pitch_radius,
                1e-15);
    EXPECT_NEAR(g.mean_cone_distance * std::sin(g.gear_cone_angle), g.gear_mean_pitch_radius,
                1e-15);
    EXPECT_GT(g.contact_ratio, 1.0);
  }
}

TEST(BevelPairTest, BadInputsAreRefusedAtTheirField) {
  EXPECT_THROWS_MESSAGE(CalcBevelPairGeometry(Spec(20, 40, -3e-3, 22e-3)), InvalidInput,
                        "^outer_module");
  EXPECT_THROWS_MESSAGE(CalcBevelPairGeometry(Spec(20, 40, 3e-3, 22e-3, 180.0)), InvalidInput,
                        "^shaft_angle");
  EXPECT_THROWS_MESSAGE(CalcBevelPairGeometry(Spec(2, 40, 3e-3, 22e-3)), InvalidInput,
                        "^pinion.teeth");
  EXPECT_THROWS_MESSAGE(CalcBevelPairGeometry(Spec(20, 40, 3e-3, 70e-3)), InvalidInput,
                        "^face_width: .* not below the outer cone distance");
  // δ2 = 90° (a crown gear) and above (internal bevel).
  EXPECT_THROWS_MESSAGE(CalcBevelPairGeometry(Spec(20, 40, 3e-3, 10e-3, 150.0)), InvalidInput,
                        "^gear_cone_angle: .*crown gear");
  // Cone angles inconsistent with the teeth and Σ.
  BevelPairSpec wrong = Spec(20, 40, 3e-3, 22e-3);
  wrong.pinion_cone_angle = DegToRad(30.0);
  EXPECT_THROWS_MESSAGE(CalcBevelPairGeometry(wrong), InvalidInput,
                        "^pinion_cone_angle: 30 deg is inconsistent.*26.56");
  wrong = Spec(20, 40, 3e-3, 22e-3);
  wrong.gear_cone_angle = DegToRad(63.43495);  // rounded beyond 1e-6 rad? 5e-6° ≈ 9e-8 rad: ok
  EXPECT_NO_THROW(CalcBevelPairGeometry(wrong));
  wrong.gear_cone_angle = DegToRad(63.5);
  EXPECT_THROWS_MESSAGE(CalcBevelPairGeometry(wrong), InvalidInput, "^gear_cone_angle");
  // A profile shift that makes the pinion's tip reach past the gear's virtual base circle.
  BevelPairSpec shifted = Spec(20, 40, 3e-3, 22e-3);
  shifted.pinion_profile_shift = 2.5;
  EXPECT_THROW(CalcBevelPairGeometry(shifted), InvalidInput);
  // A face wider than R_e/3 is accepted with a note.
  EXPECT_FALSE(CalcBevelPairGeometry(Spec(20, 40, 3e-3, 30e-3)).warnings.empty());
  EXPECT_TRUE(CalcBevelPairGeometry(Spec(20, 40, 3e-3, 20e-3)).warnings.empty());
}

}  // namespace
}  // namespace geardyn
