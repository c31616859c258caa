// `geardyn info` on a published stage written as a designer's report prints it: the NREL 5 MW
// parallel stage (KISSsoft Release 03/2017 report "stage_03", repository gfsReboucas/Drivetrain,
// @NREL_5MW/stage_03.rtf), shifts printed to 4 decimals and a = 861 mm, both blanks webbed
// (b_s/b = 0.25, s_R/m_n = 5), with no mass properties.
//
// Independent truth: the report's printed values (ε_α 1.463, C_R 0.898, c' 13.832,
// c_γα 18.632, c_γβ 15.837 N/(mm·µm)); the interference its rounding causes is below the
// documented tolerance 2e-4 m_n sin α_n, so the pair runs with zero backlash and a warning.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "support/cli_run.hpp"

namespace geardyn {
namespace {

constexpr char kStage[] = R"toml(title = "NREL 5 MW parallel stage"
[[gear]]
name = "pinion"
teeth = 24
normal_module = 0.014
helix_angle_deg = 10
hand = "right"
face_width = 0.36
profile_shift = 0.4800
tip_diameter = 0.380747
web_thickness = 0.09
rim_thickness = 0.07
[[gear]]
name = "wheel"
teeth = 95
normal_module = 0.014
helix_angle_deg = 10
hand = "left"
face_width = 0.36
profile_shift = 0.6691
tip_diameter = 1.395376
web_thickness = 0.09
rim_thickness = 0.07
[[mesh]]
pinion = "pinion"
gear = "wheel"
center_distance = 0.861
[operating_point]
speed_rpm = 1165.9
torque = 0
)toml";

std::string WriteStage() {
  const std::filesystem::path dir = std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "nrel_parallel_stage.toml";
  std::ofstream(path) << kStage;
  return path.string();
}

double Printed(int decimals) { return 0.5 * std::pow(10.0, -decimals) * (1.0 + 1e-9); }

TEST(InfoPublishedStageTest, NrelParallelStageMatchesTheKisssoftReport) {
  const std::string path = WriteStage();
  const nlohmann::json m = test::RunJson({"info", path})["meshes"][0];
  EXPECT_NEAR(m["transverse_contact_ratio"].get<double>(), 1.463, Printed(3));
  EXPECT_NEAR(m["iso_factors"]["C_R"].get<double>(), 0.898, Printed(3));
  EXPECT_NEAR(1e-9 * m["single_tooth_stiffness"].get<double>(), 13.832, Printed(3));
  // c_γα, c_γβ carry the report's rounding of ε_α as well: 0.75 c' · 0.0005.
  const double eps_slack = 0.75 * 13.832 * Printed(3);
  EXPECT_NEAR(1e-9 * m["mesh_stiffness_alpha"].get<double>(), 18.632, Printed(3) + eps_slack);
  EXPECT_NEAR(1e-9 * m["mesh_stiffness_beta"].get<double>(), 15.837, Printed(3) + eps_slack);
  // Rounding-level interference: zero backlash, the amount, and a warning saying it.
  EXPECT_EQ(m["backlash_normal"].get<double>(), 0.0);
  EXPECT_GT(m["interference_normal"].get<double>(), 0.0);
  EXPECT_LT(m["interference_normal"].get<double>(),
            2e-4 * 0.014 * std::sin(20.0 * std::numbers::pi / 180.0));
  bool warned = false;
  for (const nlohmann::json& w : m["warnings"]) {
    warned = warned || w.get<std::string>().find("taken as zero backlash") != std::string::npos;
  }
  EXPECT_TRUE(warned) << m["warnings"].dump();
  // The text report prints the warning too.
  const test::CliRun text = test::RunGeardyn({"info", path});
  EXPECT_EQ(text.code, app::kExitOk) << text.err;
  EXPECT_NE(text.out.find("warning: mesh.pinion-wheel: center_distance: 861 mm gives negative "
                          "backlash"),
            std::string::npos)
      << text.out;
}

}  // namespace
}  // namespace geardyn
