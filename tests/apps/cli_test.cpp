// The geardyn command run in-process: exit codes, JSON fields against independent closed forms,
// --set, --out, and bad input that must fail with a clear message (never a crash).
#include "geardyn/cli.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

// Closed form for a standard external spur pair (x = 0, h_a* = 1, α = 20°, a = m z): ε_α from the
// tip and base radii and the path of contact (ISO 21771 §5.4), written here independently.
double SpurContactRatio(double m, int z1, int z2) {
  const double alpha = 20.0 * M_PI / 180.0;
  const double r1 = m * z1 / 2, r2 = m * z2 / 2;
  const double rb1 = r1 * std::cos(alpha), rb2 = r2 * std::cos(alpha);
  const double ra1 = r1 + m, ra2 = r2 + m;
  const double g = std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2) -
                   (r1 + r2) * std::sin(alpha);
  return g / (M_PI * m * std::cos(alpha));
}

TEST(CliTest, InfoOnKimRigMatchesClosedForms) {
  const nlohmann::json r = RunJson({"info", "builtin:kahraman-blankenship-rig"});
  ASSERT_EQ(r["meshes"].size(), 1u);
  const nlohmann::json& m = r["meshes"][0];
  constexpr double kLengthTol = 1e-9;  // metres; closed forms in double precision
  // spec 03: base radius 70.477 mm (rounded to the µm in the paper).
  EXPECT_NEAR(m["base_radius_pinion"].get<double>(), 0.070477, 5e-7);
  EXPECT_NEAR(m["base_radius_gear"].get<double>(), 0.075 * std::cos(20.0 * M_PI / 180), kLengthTol);
  EXPECT_NEAR(m["tip_radius_pinion"].get<double>(), 0.078, kLengthTol);
  EXPECT_NEAR(m["tip_radius_gear"].get<double>(), 0.078, kLengthTol);
  EXPECT_NEAR(m["operating_pressure_angle_deg"].get<double>(), 20.0, 1e-9);
  EXPECT_NEAR(m["transverse_contact_ratio"].get<double>(), SpurContactRatio(0.003, 50, 50), 1e-9);
  EXPECT_NEAR(m["overlap_contact_ratio"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(m["base_helix_angle_deg"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(m["base_pitch"].get<double>(), M_PI * 0.003 * std::cos(20.0 * M_PI / 180), 1e-12);
  // Spur: one or two full-face lines in contact (20 mm face).
  EXPECT_NEAR(m["min_contact_line_length"].get<double>(), 0.020, kLengthTol);
  EXPECT_NEAR(m["max_contact_line_length"].get<double>(), 0.040, kLengthTol);
  EXPECT_NEAR(m["mean_contact_line_length"].get<double>(),
              0.020 * m["transverse_contact_ratio"].get<double>(), kLengthTol);
  // f_mesh = z n / 60 with n the pinion speed in rpm.
  EXPECT_NEAR(m["mesh_frequency_hz"].get<double>(),
              50.0 * r["operating_point"]["speed_rpm"].get<double>() / 60.0, 1e-9);
  // ISO 6336-1 method B: c_γα = c'(0.75 ε_α + 0.25), c_γβ = 0.85 c_γα; c' of steel gears is of
  // the order of 1e10 N/m² (ISO 6336-1 §9: about 14 N/(mm·µm) before load scaling).
  const double c1 = m["single_tooth_stiffness"].get<double>();
  EXPECT_GT(c1, 5e9);
  EXPECT_LT(c1, 2e10);
  EXPECT_NEAR(m["mesh_stiffness_alpha"].get<double>(),
              c1 * (0.75 * m["transverse_contact_ratio"].get<double>() + 0.25), 1e-6 * c1);
  EXPECT_NEAR(m["mesh_stiffness_beta"].get<double>(),
              0.85 * m["mesh_stiffness_alpha"].get<double>(), 1e-6 * c1);
  EXPECT_EQ(m["hunting_period_meshes"].get<long>(), 50);  // lcm(50, 50)
}

TEST(CliTest, InfoOnHelicalPairHasOverlapAndBaseHelix) {
  const nlohmann::json r = RunJson({"info", "builtin:helical-pair"});
  ASSERT_GE(r["meshes"].size(), 1u);
  const nlohmann::json& m = r["meshes"][0];
  const double beta = m["helix_angle_deg"].get<double>() * M_PI / 180;
  const double alpha_n = m["normal_pressure_angle_deg"].get<double>() * M_PI / 180;
  ASSERT_GT(beta, 0.0);
  // sin β_b = sin β cos α_n (ISO 21771).
  EXPECT_NEAR(std::sin(m["base_helix_angle_deg"].get<double>() * M_PI / 180),
              std::sin(beta) * std::cos(alpha_n), 1e-12);
  // ε_β = b sin β / (π m_n).
  EXPECT_NEAR(
      m["overlap_contact_ratio"].get<double>(),
      m["face_width"].get<double>() * std::sin(beta) / (M_PI * m["normal_module"].get<double>()),
      1e-12);
  EXPECT_NEAR(
      m["total_contact_ratio"].get<double>(),
      m["transverse_contact_ratio"].get<double>() + m["overlap_contact_ratio"].get<double>(),
      1e-12);
}

// A pinion on a rack (examples/rack/rack-and-pinion.toml): the rack's speed is the pinion's
// pitch-line speed Ω r_1, the mesh is flagged, and the rack's infinite radii are JSON nulls.
TEST(CliTest, InfoOnARackGivesItsPitchLineSpeed) {
  const std::string path = std::string(GEARDYN_SOURCE_DIR) + "/examples/rack/rack-and-pinion.toml";
  const nlohmann::json r = RunJson({"info", path});
  ASSERT_EQ(r["gears"].size(), 2u);
  const nlohmann::json& rack = r["gears"][1];
  EXPECT_TRUE(rack["rack"].get<bool>());
  const double r1 = r["gears"][0]["reference_radius"].get<double>();
  EXPECT_NEAR(rack["speed_m_per_s"].get<double>(), 300.0 * 2.0 * M_PI / 60.0 * r1, 1e-12);
  const nlohmann::json& m = r["meshes"][0];
  EXPECT_TRUE(m["rack"].get<bool>());
  EXPECT_TRUE(m["base_radius_gear"].is_null());
  EXPECT_NEAR(m["operating_pressure_angle_deg"].get<double>(), 20.0, 1e-12);
  const CliRun text = RunGeardyn({"info", path});
  EXPECT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("(rack, hand none)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("m/s"), std::string::npos) << text.out;
}

// A scene file for a published worked example, written where the test can read it back.
std::string WriteScene(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(CliTest, InfoMatchesKhkProfileShiftedSpurExample) {
  // KHK Gear Technical Reference, profile-shifted spur gears: m 3, α 20°, z 12/24, x 0.6/0.36,
  // a_w 56.500 mm, tips shortened to d_a 44.840/79.400 mm → α_w 26.0888°, d_b 33.8289/67.6579 mm,
  // ε_α 1.202 (printed precision).
  const std::string path = WriteScene("khk_spur.toml", R"toml(
[[gear]]
name = "p"
teeth = 12
normal_module = 0.003
profile_shift = 0.6
tip_diameter = 0.04484
face_width = 0.02
mass = 1.0
inertia = 1e-3
[[gear]]
name = "g"
teeth = 24
normal_module = 0.003
profile_shift = 0.36
tip_diameter = 0.0794
face_width = 0.02
mass = 2.0
inertia = 4e-3
[[mesh]]
pinion = "p"
gear = "g"
center_distance = 0.0565
[operating_point]
speed_rpm = 1000
torque = 10
)toml");
  const nlohmann::json m = RunJson({"info", path})["meshes"][0];
  EXPECT_NEAR(m["operating_pressure_angle_deg"].get<double>(), 26.0888, 5e-5);
  EXPECT_NEAR(2e3 * m["base_radius_pinion"].get<double>(), 33.8289, 5e-5);
  EXPECT_NEAR(2e3 * m["base_radius_gear"].get<double>(), 67.6579, 5e-5);
  EXPECT_NEAR(m["transverse_contact_ratio"].get<double>(), 1.202, 5e-4);
  EXPECT_EQ(m["hunting_period_meshes"].get<long>(), 24);  // lcm(12, 24)
}

TEST(CliTest, InfoMatchesIso21771HelicalExampleThroughOverrides) {
  // ISO 21771 profile-shift worked sheet: z 31/30, m_n 3.5 mm, α_n 20°, β 21°, Σx 0.651877131252
  // → a 114.3447280708 mm (reference), α_wt 23.8707609654°, zero-backlash a_w 116.5 mm. The
  // example scene's pair is turned into it with --set only.
  const nlohmann::json r =
      RunJson({"info", "builtin:helical-pair", "--set", "gear.pinion.teeth=31", "--set",
               "gear.wheel.teeth=30", "--set", "gear.pinion.normal_module=0.0035", "--set",
               "gear.wheel.normal_module=0.0035", "--set", "gear.pinion.helix_angle_deg=21",
               "--set", "gear.wheel.helix_angle_deg=21", "--set", "gear.pinion.profile_shift=0.291",
               "--set", "gear.wheel.profile_shift=0.360877131252"});
  const nlohmann::json& m = r["meshes"][0];
  EXPECT_NEAR(m["reference_center_distance"].get<double>(), 0.1143447280708, 1e-12);
  EXPECT_NEAR(m["operating_pressure_angle_deg"].get<double>(), 23.8707609654, 2e-9);
  EXPECT_NEAR(m["center_distance"].get<double>(), 0.1165, 1e-11);
}

TEST(CliTest, SetOverridesAValueWithoutEditingTheFile) {
  const nlohmann::json base = RunJson({"info", "builtin:kahraman-blankenship-rig"});
  const nlohmann::json r = RunJson(
      {"info", "builtin:kahraman-blankenship-rig", "--set", "operating_point.speed_rpm=1200"});
  EXPECT_NEAR(r["meshes"][0]["mesh_frequency_hz"].get<double>(), 1200.0 / 60.0 * 50.0, 1e-9);
  EXPECT_NEAR(r["meshes"][0]["base_radius_pinion"].get<double>(),
              base["meshes"][0]["base_radius_pinion"].get<double>(), 0.0);
}

// `info` on a tooth-contact mesh (time-domain only) shows the geometry and the tooth DOF instead
// of refusing. Truth: Kim et al. 2015's counts — two 50-tooth gears, 1 DOF per type-A tooth
// (100), 3 per type-B tooth (300) — and the geometry unchanged by the mesh level.
TEST(CliTest, InfoShowsAToothContactMesh) {
  const std::string rig = "builtin:kahraman-blankenship-rig";
  const nlohmann::json base = RunJson({"info", rig});
  for (const auto& [teeth, dofs] : {std::pair{"revolute", 100}, std::pair{"bushing", 300}}) {
    const std::vector<std::string> args = {
        "info",  rig,
        "--set", "mesh.pinion-wheel.model=contact",
        "--set", std::string("mesh.pinion-wheel.contact.teeth=") + teeth,
        "--set", "mesh.pinion-wheel.contact.bending_stiffness=11.5e3"};
    const nlohmann::json m = RunJson(args)["meshes"][0];
    EXPECT_EQ(m["contact"]["teeth"], teeth);
    EXPECT_EQ(m["contact"]["tooth_dofs"].get<int>(), dofs);
    EXPECT_EQ(m["contact"]["law"], "kim");
    EXPECT_EQ(m["transverse_contact_ratio"], base["meshes"][0]["transverse_contact_ratio"]);
    const CliRun text = RunGeardyn(args);
    ASSERT_EQ(text.code, kExitOk) << text.err;
    EXPECT_NE(text.out.find("model contact (time-domain only"), std::string::npos) << text.out;
  }
}

// `info` prints the mesh model's own notes as the analyses do. Truth: mesh_model_test proves that
// table_samples has no effect on a mesh without transmission error (the core is the same at every
// θ with and without the key), which is what the warning says.
TEST(CliTest, InfoShowsTheMeshModelWarningsTheAnalysesPrint) {
  const std::vector<std::string> args = {"info", "builtin:helical-pair", "--set",
                                         "mesh.pinion-wheel.table_samples=64"};
  const CliRun text = RunGeardyn(args);
  ASSERT_EQ(text.code, kExitOk) << text.err;
  EXPECT_NE(text.out.find("warning: mesh.pinion-wheel: table_samples has no effect"),
            std::string::npos)
      << text.out;
  const nlohmann::json r = RunJson(args);
  int count = 0;
  for (const nlohmann::json& w : r["meshes"][0]["warnings"]) {
    if (w.get<std::string>().find("table_samples has no effect") != std::string::npos) ++count;
  }
  EXPECT_EQ(count, 1);
  // A scene without such a key has no model warning.
  const nlohmann::json plain = RunJson({"info", "builtin:helical-pair"});
  for (const nlohmann::json& w : plain["meshes"][0]["warnings"]) {
    EXPECT_EQ(w.get<std::string>().find("no effect"), std::string::npos) << w;
  }
}

TEST(CliTest, OutWritesJsonAndText) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output" / "cli_info";
  std::filesystem::remove_all(dir);
  const CliRun run =
      RunGeardyn({"info", "builtin:kahraman-blankenship-rig", "--out", dir.string()});
  ASSERT_EQ(run.code, kExitOk) << run.err;
  std::ifstream json_file(dir / "info.json");
  ASSERT_TRUE(json_file.good());
  const nlohmann::json r = nlohmann::json::parse(json_file);
  EXPECT_NEAR(r["meshes"][0]["tip_radius_gear"].get<double>(), 0.078, 1e-9);
  EXPECT_TRUE(std::filesystem::exists(dir / "info.txt"));
  EXPECT_NE(run.out.find("transverse contact ratio"), std::string::npos);
}

TEST(CliTest, ScenesListsTheBuiltins) {
  const CliRun run = RunGeardyn({"scenes"});
  EXPECT_EQ(run.code, kExitOk);
  EXPECT_NE(run.out.find("builtin:kahraman-blankenship-rig"), std::string::npos);
  EXPECT_NE(run.out.find("builtin:helical-pair"), std::string::npos);
}

struct BadCommand {
  std::vector<std::string> args;
  std::string expected_in_err;
};

void PrintTo(const BadCommand& c, std::ostream* os) {
  *os << "geardyn";
  for (const std::string& a : c.args) *os << " " << a;
}

class CliBadInputTest : public ::testing::TestWithParam<BadCommand> {};

TEST_P(CliBadInputTest, FailsWithExitCodeTwoAndAClearMessage) {
  const CliRun run = RunGeardyn(GetParam().args);
  EXPECT_EQ(run.code, kExitBadInput) << run.out;
  EXPECT_NE(run.err.find(GetParam().expected_in_err), std::string::npos) << run.err;
}

INSTANTIATE_TEST_SUITE_P(
    Commands, CliBadInputTest,
    ::testing::Values(
        BadCommand{{}, "subcommand"}, BadCommand{{"frobnicate"}, "frobnicate"},
        BadCommand{{"info"}, "scene"},
        BadCommand{{"info", "/nonexistent/scene.toml"}, "/nonexistent/scene.toml"},
        BadCommand{{"info", "builtin:no-such-scene"}, "builtin:no-such-scene"},
        BadCommand{{"info", "builtin:kahraman-blankenship-rig", "--set", "gear.pinion.teeth=-5"},
                   "teeth"},
        BadCommand{{"info", "builtin:kahraman-blankenship-rig", "--set", "nonsense"}, "nonsense"},
        BadCommand{{"info", "builtin:kahraman-blankenship-rig", "--set", "gear.nobody.teeth=3"},
                   "nobody"},
        BadCommand{{"info", "builtin:kahraman-blankenship-rig", "--bogus"}, "--bogus"}));

}  // namespace
}  // namespace geardyn::app
