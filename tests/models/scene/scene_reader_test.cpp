// Scene reader: valid input (values, defaults, unit conversions), SceneError's format and
// LoadScene (files and built-ins). The bad-input tables are in scene_reader_{gear,mesh,
// bearing_load,override}_test.cpp.
#include "geardyn/models/scene/scene_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geardyn/common/units.hpp"
#include "scene_reader_cases.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::Helical;
using test::kBase;
using test::kSource;
using test::Replace;

// --- SceneError ---------------------------------------------------------------------------------

TEST(SceneErrorTest, FormatsSourceLineKeyReason) {
  const SceneError e("rig.toml", 12, "gear.wheel.teeth", "must be a positive integer, got -5");
  EXPECT_STREQ(e.what(), "rig.toml:12: gear.wheel.teeth: must be a positive integer, got -5");
  EXPECT_EQ(e.source(), "rig.toml");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.key(), "gear.wheel.teeth");
  EXPECT_EQ(e.reason(), "must be a positive integer, got -5");
  EXPECT_TRUE(e.override_spec().empty());
  const InvalidInput& base = e;  // catchable as the library's bad-input type
  EXPECT_STREQ(base.what(), e.what());
}

TEST(SceneErrorTest, FormatsOverrideAndMissingParts) {
  EXPECT_STREQ(SceneError("rig.toml", 0, "gear.pinion.teeth", "bad", "gear.pinion.teeth=0").what(),
               "rig.toml: --set gear.pinion.teeth=0: gear.pinion.teeth: bad");
  EXPECT_STREQ(SceneError("rig.toml", 0, "", "cannot open").what(), "rig.toml: cannot open");
  EXPECT_STREQ(SceneError("rig.toml", 3, "", "TOML syntax error: x").what(),
               "rig.toml:3: TOML syntax error: x");
}

TEST(SceneErrorTest, OverrideErrorCarriesTheOverride) {
  try {
    (void)ParseScene(kBase, kSource, {"gear.pinion.teeth=0"});
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.override_spec(), "gear.pinion.teeth=0");
    EXPECT_EQ(e.key(), "gear.pinion.teeth");
    EXPECT_EQ(e.reason(), "must be a positive integer, got 0");
  }
}

// --- LoadScene: files and built-ins ---------------------------------------------------------

TEST(LoadSceneTest, UnreadableFileNamesTheFile) {
  EXPECT_THROWS_MESSAGE(LoadScene("/nonexistent/dir/rig.toml"), SceneError,
                        R"(^/nonexistent/dir/rig\.toml: cannot open the scene file)");
  const std::string dir = std::filesystem::temp_directory_path().string();
  EXPECT_THROWS_MESSAGE(LoadScene(dir), SceneError, "is a directory");
}

TEST(LoadSceneTest, UnknownBuiltinListsTheNames) {
  EXPECT_THROWS_MESSAGE(
      LoadScene("builtin:helical-pear"), SceneError,
      R"(^builtin:helical-pear: no built-in scene named 'helical-pear' \(did you )"
      R"(mean 'helical-pair'\?\); built-in scenes: blankenship-kahraman-oscillator, geared-shafts, helical-pair, )");
}

TEST(LoadSceneTest, ReadsAFileAndNamesItInErrors) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "geardyn_scene_reader_test_rig.toml";
  {
    std::ofstream out(path);
    out << kBase;
  }
  const Scene scene = LoadScene(path.string());
  EXPECT_EQ(scene.source, path.string());
  EXPECT_EQ(scene.title, "test pair");
  EXPECT_THROWS_MESSAGE(
      LoadScene(path.string(), {"gear.wheel.teeth=-5"}), SceneError,
      "^" + std::regex_replace(path.string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
          R"(: --set gear\.wheel\.teeth=-5: gear\.wheel\.teeth: must be a )"
          R"(positive integer, got -5$)");
  std::filesystem::remove(path);
}

TEST(LoadSceneTest, BuiltinErrorsNameTheBuiltin) {
  EXPECT_THROWS_MESSAGE(
      LoadScene("builtin:helical-pair", {"gear.pinion.teeth=0"}), SceneError,
      R"(^builtin:helical-pair: --set gear\.pinion\.teeth=0: gear\.pinion\.teeth: )"
      R"(must be a positive integer, got 0$)");
}

// --- Valid input: values, defaults, unit conversions ----------------------------------------

// Relative tolerance for values that go through one unit conversion.
constexpr double kConvTol = 1e-14;

TEST(ParseSceneTest, ReadsTheBasePairWithDefaultsAndSiUnits) {
  const Scene s = ParseScene(kBase, kSource);
  EXPECT_EQ(s.source, kSource);
  EXPECT_EQ(s.title, "test pair");
  ASSERT_EQ(s.gears.size(), 2u);
  const GearDef& p = s.gear("pinion");
  EXPECT_EQ(p.blank.teeth, 20);
  EXPECT_EQ(p.blank.kind, GearKind::kExternal);
  EXPECT_DOUBLE_EQ(p.normal_module, 0.002);
  EXPECT_NEAR(p.normal_pressure_angle, 20.0 * std::acos(-1.0) / 180.0, kConvTol);  // default 20°
  EXPECT_EQ(p.helix_angle, 0.0);
  EXPECT_EQ(p.hand, HelixHand::kNone);
  EXPECT_DOUBLE_EQ(p.blank.face_width, 0.02);
  EXPECT_EQ(p.blank.profile_shift, 0.0);
  EXPECT_EQ(p.blank.addendum_coefficient, 1.0);
  EXPECT_EQ(p.blank.dedendum_coefficient, 1.25);
  EXPECT_EQ(p.blank.root_radius_coefficient, 0.38);
  EXPECT_FALSE(p.blank.tip_diameter.has_value());
  EXPECT_FALSE(p.blank.web_thickness.has_value());
  EXPECT_FALSE(p.blank.rim_thickness.has_value());
  EXPECT_EQ(p.mass, 0.5);
  EXPECT_EQ(p.inertia, 1e-4);
  EXPECT_EQ(p.key, "gear.pinion");
  EXPECT_FALSE(p.transverse_inertia.has_value());
  EXPECT_EQ(s.gear("wheel").mass, 2.0);  // 2.0 written as a float, also fine as int below

  ASSERT_EQ(s.meshes.size(), 1u);
  const MeshDef& m = s.meshes[0];
  EXPECT_EQ(m.name, "pinion-wheel");  // default name
  EXPECT_EQ(m.pinion, "pinion");
  EXPECT_EQ(m.gear, "wheel");
  EXPECT_EQ(m.geometry.pinion.teeth, 20);
  EXPECT_EQ(m.geometry.gear.teeth, 40);
  EXPECT_NEAR(m.geometry.center_distance, 0.002 * (20 + 40) / 2.0, 1e-12);  // zero backlash
  EXPECT_FALSE(m.geometry.spec.center_distance.has_value());

  ASSERT_EQ(s.bearings.size(), 1u);
  const BearingDef& b = s.bearings[0];
  EXPECT_EQ(b.name, "b1");
  EXPECT_EQ(b.body, "pinion");
  EXPECT_TRUE(b.other.empty());
  Matrix6 k = Matrix6::Zero();
  k.diagonal() << 1e9, 1e9, 1e9, 1e7, 1e7, 0.0;
  EXPECT_EQ(b.stiffness, k);
  EXPECT_EQ(b.damping, Matrix6::Zero());

  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].name, "brake");
  EXPECT_EQ(s.loads[0].body, "wheel");
  EXPECT_EQ(s.loads[0].torque, 100.0);

  EXPECT_EQ(s.operating_point.body, "pinion");  // default: the first mesh's pinion
  EXPECT_NEAR(s.operating_point.speed, 3000.0 * 2.0 * std::acos(-1.0) / 60.0, 1e-12);
  EXPECT_EQ(s.operating_point.torque, 50.0);
}

TEST(ParseSceneTest, ConvertsDegreesAndRpm) {
  const std::string text =
      Replace(Replace(Helical(), "helix_angle_deg = 15.0\nhand = \"right\"",
                      "helix_angle_deg = 15.0\nhand = \"right\"\nnormal_pressure_angle_deg = 25"),
              "helix_angle_deg = 15.0\nhand = \"left\"",
              "helix_angle_deg = 15.0\nhand = \"left\"\nnormal_pressure_angle_deg = 25.0");
  const Scene s = ParseScene(text, kSource, {"operating_point.speed_rpm=60"});
  const double pi = std::acos(-1.0);
  EXPECT_NEAR(s.gear("pinion").normal_pressure_angle, 25.0 * pi / 180.0, kConvTol);
  EXPECT_NEAR(s.gear("pinion").helix_angle, 15.0 * pi / 180.0, kConvTol);
  EXPECT_EQ(s.gear("pinion").hand, HelixHand::kRight);
  EXPECT_EQ(s.gear("wheel").hand, HelixHand::kLeft);
  EXPECT_NEAR(s.operating_point.speed, 2.0 * pi, kConvTol);  // 60 rpm = 1 rev/s
  EXPECT_EQ(s.meshes[0].geometry.spec.pinion_hand, HelixHand::kRight);
}

TEST(ParseSceneTest, ReadsAllOptionalGearKeys) {
  const std::string text = Replace(kBase, "teeth = 40\n", R"(teeth = 40
profile_shift = -0.1
addendum_coefficient = 1.0
dedendum_coefficient = 1.3
root_radius_coefficient = 0.3
tip_diameter = 0.0836
web_thickness = 0.008
rim_thickness = 0.01
transverse_inertia = 9e-4
)");
  const Scene s = ParseScene(text, kSource);
  const GearDef& w = s.gear("wheel");
  EXPECT_EQ(w.blank.profile_shift, -0.1);
  EXPECT_EQ(w.blank.dedendum_coefficient, 1.3);
  EXPECT_EQ(w.blank.root_radius_coefficient, 0.3);
  EXPECT_EQ(w.blank.tip_diameter, 0.0836);
  EXPECT_EQ(w.blank.web_thickness, 0.008);
  EXPECT_EQ(w.blank.rim_thickness, 0.01);
  EXPECT_EQ(w.transverse_inertia, 9e-4);
  EXPECT_EQ(s.meshes[0].geometry.spec.gear.tip_diameter, 0.0836);
}

TEST(ParseSceneTest, IntegersAreAcceptedForFloats) {
  const Scene s = ParseScene(Replace(kBase, "mass = 2.0", "mass = 2"), kSource);
  EXPECT_EQ(s.gear("wheel").mass, 2.0);
}

TEST(ParseSceneTest, ReadsFullSymmetricMatricesAndDefaultNames) {
  const std::string text = Replace(Replace(kBase, "name = \"b1\"\n", ""),
                                   "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(other = "wheel"
stiffness = [
  [1e9, 0, 0, 0, 2e7, 0],
  [0, 1e9, 0, -2e7, 0, 0],
  [0, 0, 5e8, 0, 0, 0],
  [0, -2e7, 0, 1e6, 0, 0],
  [2e7, 0, 0, 0, 1e6, 0],
  [0, 0, 0, 0, 0, 0],
]
damping = [100, 100, 50, 1, 1, 0]
)");
  const Scene s = ParseScene(text, kSource);
  const BearingDef& b = s.bearings[0];
  EXPECT_EQ(b.name, "bearing0");
  EXPECT_EQ(b.other, "wheel");
  EXPECT_EQ(b.stiffness(0, 4), 2e7);
  EXPECT_EQ(b.stiffness(4, 0), 2e7);
  EXPECT_EQ(b.stiffness(1, 3), -2e7);
  EXPECT_EQ(b.stiffness(2, 2), 5e8);
  EXPECT_EQ(b.stiffness(5, 5), 0.0);
  EXPECT_EQ(b.damping(2, 2), 50.0);
  EXPECT_EQ(b.damping(0, 1), 0.0);
  // A default-named bearing is addressable by its default name.
  const Scene t = ParseScene(text, kSource, {"bearing.bearing0.damping=[1, 2, 3, 4, 5, 6]"});
  EXPECT_EQ(t.bearings[0].damping(5, 5), 6.0);
}

TEST(ParseSceneTest, ExplicitCenterDistanceReachesTheGeometry) {
  const Scene s = ParseScene(kBase, kSource, {"mesh.pinion-wheel.center_distance=0.0601"});
  ASSERT_TRUE(s.meshes[0].geometry.spec.center_distance.has_value());
  EXPECT_EQ(*s.meshes[0].geometry.spec.center_distance, 0.0601);
  EXPECT_NEAR(s.meshes[0].geometry.center_distance, 0.0601, 1e-15);
}

TEST(ParseSceneTest, InternalHelicalMeshKeepsTheDirection) {
  const std::string text = Replace(Replace(Helical(), "teeth = 40", "teeth = 60\ninternal = true"),
                                   "hand = \"left\"", "hand = \"right\"");
  const Scene s = ParseScene(text, kSource);
  EXPECT_EQ(s.gear("wheel").blank.kind, GearKind::kInternal);
  EXPECT_TRUE(s.meshes[0].geometry.internal);
  EXPECT_EQ(s.meshes[0].geometry.gear.hand, HelixHand::kRight);
  const double w = s.operating_point.speed;
  EXPECT_NEAR(s.GearSpeed("wheel"), w * 20.0 / 60.0, 1e-12 * w);  // same sign: internal mesh
}

TEST(ParseSceneTest, AcceptsInlineArraysOfTables) {
  const std::string text = R"(gear = [
  { name = "a", teeth = 30, normal_module = 0.001, face_width = 0.01, mass = 0.1, inertia = 1e-5 },
  { name = "b", teeth = 31, normal_module = 0.001, face_width = 0.01, mass = 0.1, inertia = 1e-5 },
]
mesh = [{ pinion = "a", gear = "b" }]
operating_point = { speed_rpm = 600, torque = 1 }
)";
  const Scene s = ParseScene(text, kSource);
  EXPECT_EQ(s.gears.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "a-b");
  EXPECT_NEAR(s.MeshFrequencyHz(s.meshes[0]), 600.0 / 60.0 * 30.0, 1e-9);
  // Inline tables carry lines too.
  EXPECT_THROWS_MESSAGE(ParseScene(Replace(text, "teeth = 31", "teeth = -31"), kSource), SceneError,
                        R"(^t\.toml:3: gear\.b\.teeth: must be a positive integer, got -31$)");
}

}  // namespace
}  // namespace geardyn
