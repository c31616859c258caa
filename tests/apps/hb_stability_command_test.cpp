// `geardyn hb` (linear) with the Floquet verdict of every point (issue 12): on the built-in rig
// at f_m = 3290 Hz (the second parametric instability region of its 3428 Hz mesh mode) the point
// is marked unstable with modal damping 0.02 and stable with 0.1; the independent truth is the
// `geardyn floquet` path — the scene at the operating speed giving that mesh frequency (3948 rpm,
// 50 pinion teeth), its model, ComputeFloquet at the scene's own mesh frequency.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

constexpr const char* kRig = "builtin:kahraman-blankenship-rig";

// The `geardyn floquet` result of the rig at 3948 rpm with the given modal damping ratio.
FloquetResult FloquetAtOperatingSpeed(const std::string& ratio) {
  const Scene scene =
      LoadScene(kRig, {"operating_point.speed_rpm=3948", "damping.modal_ratio=" + ratio});
  FloquetOptions options;
  options.mesh_frequency_hz = scene.MeshFrequencyHz(scene.meshes.front());
  EXPECT_NEAR(options.mesh_frequency_hz, 3290.0, 1e-9);
  return ComputeFloquet(MakeSystemModel(scene), options);
}

nlohmann::json HbAt3290(const std::string& ratio) {
  return RunJson({"hb", kRig, "--mesh-frequency", "3290:3290:1", "--harmonics", "8", "--set",
                  "damping.modal_ratio=" + ratio});
}

TEST(HbStabilityCommandTest, RigAt3290HzIsUnstableWithTwoPercentDamping) {
  const FloquetResult truth = FloquetAtOperatingSpeed("0.02");
  ASSERT_EQ(truth.verdict, FloquetVerdict::kUnstable);
  ASSERT_GT(truth.max_abs_multiplier, 1.0);
  const nlohmann::json report = HbAt3290("0.02");
  EXPECT_EQ(report["status"], "success");  // an unstable point is a result, not a failure
  EXPECT_EQ(report["stability"], "floquet");
  const auto& s = report["points"][0]["stability"];
  EXPECT_EQ(s["verdict"], "unstable");
  EXPECT_NEAR(s["max_abs_multiplier"].get<double>(), truth.max_abs_multiplier,
              1e-9 * truth.max_abs_multiplier);
  ASSERT_EQ(report["unstable_ranges"].size(), 1u);
  EXPECT_EQ(report["unstable_ranges"][0]["lo_hz"].get<double>(), 3290.0);
  bool warned = false;
  for (const auto& w : report["warnings"]) {
    warned = warned || w.get<std::string>().find("parametrically unstable at f_m = 3290 Hz") !=
                           std::string::npos;
  }
  EXPECT_TRUE(warned) << report["warnings"].dump();
}

TEST(HbStabilityCommandTest, RigAt3290HzIsStableWithTenPercentDamping) {
  const FloquetResult truth = FloquetAtOperatingSpeed("0.1");
  ASSERT_EQ(truth.verdict, FloquetVerdict::kStable);
  ASSERT_LE(truth.max_abs_multiplier, 1.0 + 1e-12);
  const nlohmann::json report = HbAt3290("0.1");
  EXPECT_EQ(report["points"][0]["stability"]["verdict"], "stable");
  EXPECT_TRUE(report["unstable_ranges"].empty());
}

TEST(HbStabilityCommandTest, TextCsvAndPlotMarkTheUnstablePoint) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "hb_stability_command_test";
  std::filesystem::remove_all(dir);
  // 3100, 3290 (unstable, see above), 3480 Hz.
  const CliRun run = RunGeardyn({"hb", kRig, "--mesh-frequency", "3100:3480:3", "--harmonics", "8",
                                 "--set", "damping.modal_ratio=0.02", "--out", dir.string()});
  ASSERT_EQ(run.code, kExitOk) << run.err;
  EXPECT_NE(run.out.find("unstable (parametric, max|λ| = 1.0"), std::string::npos) << run.out;
  std::ifstream csv(dir / "hb.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].rfind("mesh_frequency_hz,harmonics,error_estimate,status,stability,"
                           "max_abs_multiplier",
                           0),
            0u);
  EXPECT_EQ(lines[2].rfind("3290,8,", 0), 0u);
  EXPECT_NE(lines[2].find(",success,unstable,"), std::string::npos) << lines[2];
  std::stringstream svg;
  svg << std::ifstream(dir / "hb_rms_dte.svg").rdbuf();
  EXPECT_NE(svg.str().find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.str().find("parametrically unstable"), std::string::npos);
}

// Issue 12 (tryout): the text table said "stable" where the JSON said `marginal: true`. Truth:
// the rig has no damping (C = 0), so det Φ = exp(−∫tr M⁻¹C dt) = 1 (Liouville) and a stable
// monodromy has every |λ| = 1: its verdict is marginal. The text says "stable, marginal" as
// `geardyn floquet` does; with 10 % modal damping (|λ| < 1) it says "stable" alone.
TEST(HbStabilityCommandTest, UndampedStablePointReadsMarginalInTheText) {
  const std::vector<std::string> args = {"hb",   kRig,          "--mesh-frequency",
                                         "2000", "--harmonics", "8"};
  const nlohmann::json report = RunJson(args);
  const auto& s = report["points"][0]["stability"];
  ASSERT_EQ(s["verdict"], "stable");
  EXPECT_TRUE(s["marginal"].get<bool>());
  const CliRun run = RunGeardyn(args);
  ASSERT_EQ(run.code, kExitOk) << run.err;
  EXPECT_NE(run.out.find("stable, marginal"), std::string::npos) << run.out;

  const CliRun damped = RunGeardyn({"hb", kRig, "--mesh-frequency", "3290", "--harmonics", "8",
                                    "--set", "damping.modal_ratio=0.1"});
  ASSERT_EQ(damped.code, kExitOk) << damped.err;
  EXPECT_NE(damped.out.find("  stable"), std::string::npos) << damped.out;
  EXPECT_EQ(damped.out.find("marginal"), std::string::npos) << damped.out;
}

TEST(HbStabilityCommandTest, StabilityNoneSkipsTheVerdicts) {
  const nlohmann::json report =
      RunJson({"hb", kRig, "--mesh-frequency", "3290", "--harmonics", "8", "--set",
               "damping.modal_ratio=0.02", "--stability", "none"});
  EXPECT_EQ(report["stability"], "none");
  EXPECT_TRUE(report["points"][0]["stability"].is_null());
  EXPECT_TRUE(report["unstable_ranges"].empty());
}

}  // namespace
}  // namespace geardyn::app
