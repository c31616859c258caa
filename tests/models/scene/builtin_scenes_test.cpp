#include "geardyn/models/scene/builtin_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn {
namespace {

const double kPi = std::acos(-1.0);
double Deg(double d) { return d * kPi / 180.0; }

std::filesystem::path ScenesDir() {
  return std::filesystem::path(GEARDYN_SOURCE_DIR) / "examples" / "scenes";
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot read " << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(BuiltinScenesTest, NamesAreSortedAndKnown) {
  const std::vector<std::string> names = BuiltinSceneNames();
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_NE(std::find(names.begin(), names.end(), "kahraman-blankenship-rig"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "helical-pair"), names.end());
  EXPECT_FALSE(BuiltinSceneText("no-such-scene").has_value());
  EXPECT_FALSE(BuiltinSceneText("").has_value());
}

TEST(BuiltinScenesTest, EmbeddedTextEqualsTheExampleFile) {
  for (const std::string& name : BuiltinSceneNames()) {
    const std::optional<std::string_view> text = BuiltinSceneText(name);
    ASSERT_TRUE(text.has_value()) << name;
    EXPECT_EQ(std::string(*text), ReadFile(ScenesDir() / (name + ".toml")))
        << "models/src/scene/builtin_scenes.cpp is out of date for " << name;
  }
}

TEST(BuiltinScenesTest, EveryExampleSceneFileIsBuiltinAndLoads) {
  const std::vector<std::string> names = BuiltinSceneNames();
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(ScenesDir())) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    const std::string stem = entry.path().stem().string();
    EXPECT_NE(std::find(names.begin(), names.end(), stem), names.end())
        << entry.path() << " is not a built-in scene";
    const Scene from_file = LoadScene(entry.path().string());
    EXPECT_EQ(from_file.source, entry.path().string());
  }
  EXPECT_EQ(files, static_cast<int>(names.size()));
}

// Σ T_i Ω_i over the operating-point torque and the loads: zero in a steady, balanced scene.
double NetPower(const Scene& s) {
  double p = s.operating_point.torque * s.GearSpeed(s.operating_point.body);
  for (const TorqueLoadDef& load : s.loads) p += load.torque * s.GearSpeed(load.body);
  return p;
}

// Tolerances: values typed with 4-5 significant digits in the TOML files.
constexpr double kTypedTol = 1e-4;     // relative
constexpr double kGeometryTol = 1e-9;  // m, closed-form geometry of exact inputs

TEST(BuiltinScenesTest, KahramanBlankenshipRigMatchesSpec03) {
  const Scene s = LoadScene("builtin:kahraman-blankenship-rig");
  EXPECT_EQ(s.source, "builtin:kahraman-blankenship-rig");
  ASSERT_EQ(s.gears.size(), 2u);
  ASSERT_EQ(s.meshes.size(), 1u);
  const GearPairGeometry& g = s.meshes[0].geometry;
  // Spec 03: module 3 mm, 50 teeth, 20°, pitch radius 75 mm, tip radius 78 mm, base radius
  // 70.477 mm, root radius 71.25 mm, face width 20 mm, centre distance 150 mm.
  EXPECT_EQ(g.pinion.teeth, 50);
  EXPECT_EQ(g.gear.teeth, 50);
  EXPECT_NEAR(g.transverse_module, 0.003, kGeometryTol);
  EXPECT_NEAR(g.transverse_pressure_angle, Deg(20.0), 1e-12);
  EXPECT_NEAR(g.pinion.reference_radius, 0.075, kGeometryTol);
  EXPECT_NEAR(g.pinion.base_radius, 0.070477, 0.5e-6);  // spec value, 3 decimals in mm
  EXPECT_NEAR(g.gear.base_radius, 0.070477, 0.5e-6);
  EXPECT_NEAR(g.pinion.tip_radius, 0.078, kGeometryTol);
  EXPECT_NEAR(g.pinion.root_radius, 0.07125, kGeometryTol);
  EXPECT_NEAR(g.face_width, 0.020, kGeometryTol);
  EXPECT_NEAR(g.center_distance, 0.150, kGeometryTol);
  // ε_α = (2 √(r_a² − r_b²) − a sin α) / (π m cos α), written out independently.
  const double rb = 0.075 * std::cos(Deg(20.0));
  const double eps_alpha =
      (2.0 * std::sqrt(0.078 * 0.078 - rb * rb) - 0.150 * std::sin(Deg(20.0))) /
      (kPi * 0.003 * std::cos(Deg(20.0)));
  EXPECT_NEAR(g.transverse_contact_ratio, eps_alpha, 1e-9);
  EXPECT_NEAR(g.transverse_contact_ratio, 1.755, 1e-3);
  EXPECT_EQ(g.overlap_contact_ratio, 0.0);

  // Assumed mass properties: solid steel discs of the pitch radius (stated in the file).
  const double r = 0.075;
  const double b = 0.020;
  const double mass = 7850.0 * kPi * r * r * b;
  for (const GearDef& gear : s.gears) {
    ASSERT_TRUE(gear.mass && gear.inertia) << gear.name;
    EXPECT_NEAR(*gear.mass, mass, kTypedTol * mass) << gear.name;
    EXPECT_NEAR(*gear.inertia, mass * r * r / 2.0, kTypedTol * *gear.inertia) << gear.name;
    ASSERT_TRUE(gear.transverse_inertia.has_value());
    EXPECT_NEAR(*gear.transverse_inertia, mass * (3.0 * r * r + b * b) / 12.0,
                kTypedTol * *gear.transverse_inertia);
  }

  // Operating point: 100 N m, 2400 rpm → 2400/60 · 50 = 2000 Hz, inside the 700-3500 Hz sweep.
  EXPECT_EQ(s.operating_point.body, "pinion");
  EXPECT_EQ(s.operating_point.torque, 100.0);
  EXPECT_NEAR(s.MeshFrequencyHz(s.meshes[0]), 2000.0, 1e-9);
  EXPECT_NEAR(NetPower(s), 0.0, 1e-9 * 100.0 * s.operating_point.speed);

  // Bearings: stiff radially, free about the gear axis.
  ASSERT_EQ(s.bearings.size(), 2u);
  for (const BearingDef& bearing : s.bearings) {
    EXPECT_TRUE(bearing.other.empty());
    EXPECT_GE(bearing.stiffness(0, 0), 1e9);
    EXPECT_GE(bearing.stiffness(1, 1), 1e9);
    EXPECT_EQ(bearing.stiffness(5, 5), 0.0);
  }
}

TEST(BuiltinScenesTest, HelicalPairGeometryAndBearings) {
  const Scene s = LoadScene("builtin:helical-pair");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "pinion-wheel");
  const GearPairGeometry& g = s.meshes[0].geometry;
  const double beta = Deg(15.0);
  const double mt = 0.003 / std::cos(beta);
  const double alpha_t = std::atan(std::tan(Deg(20.0)) / std::cos(beta));
  EXPECT_EQ(g.pinion.teeth, 25);
  EXPECT_EQ(g.gear.teeth, 61);
  EXPECT_EQ(g.pinion.hand, HelixHand::kRight);
  EXPECT_EQ(g.gear.hand, HelixHand::kLeft);
  EXPECT_NEAR(g.pinion.reference_radius, 25 * mt / 2.0, kGeometryTol);
  EXPECT_NEAR(g.gear.base_radius, 61 * mt / 2.0 * std::cos(alpha_t), kGeometryTol);
  EXPECT_NEAR(g.center_distance, 86 * mt / 2.0, kGeometryTol);  // x1 = x2 = 0: zero backlash
  EXPECT_NEAR(g.overlap_contact_ratio, 0.025 * std::sin(beta) / (kPi * 0.003), 1e-12);
  EXPECT_GT(g.transverse_contact_ratio, 1.2);

  // 1500 rpm · 25 / 60 = 625 Hz; torques balanced through the ratio 61/25.
  EXPECT_NEAR(s.MeshFrequencyHz(s.meshes[0]), 625.0, 1e-9);
  EXPECT_NEAR(NetPower(s), 0.0, 1e-9 * 150.0 * s.operating_point.speed);

  // Four bearings, two per shaft at ±e: their tilt couplings cancel on each gear, the radial
  // stiffnesses add and the tilt stiffness is 2 k_r e².
  ASSERT_EQ(s.bearings.size(), 4u);
  Matrix6 pinion = Matrix6::Zero();
  Matrix6 wheel = Matrix6::Zero();
  for (const BearingDef& bearing : s.bearings) {
    EXPECT_TRUE(bearing.other.empty());
    (bearing.body == "pinion" ? pinion : wheel) += bearing.stiffness;
  }
  EXPECT_EQ(pinion(0, 4), 0.0);
  EXPECT_EQ(pinion(1, 3), 0.0);
  EXPECT_EQ(wheel(0, 4), 0.0);
  EXPECT_NEAR(pinion(3, 3), 2.0 * 5e8 * 0.06 * 0.06, 1e-6 * pinion(3, 3));
  EXPECT_NEAR(wheel(4, 4), 2.0 * 8e8 * 0.07 * 0.07, 1e-6 * wheel(4, 4));
  EXPECT_EQ(pinion(5, 5), 0.0);
}

}  // namespace
}  // namespace geardyn
