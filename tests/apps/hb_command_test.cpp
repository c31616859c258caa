// `geardyn hb`: the JSON equals SweepHarmonicBalance on MakeSystemModel of the same scene (the
// library path), --out writes one CSV row per mesh frequency plus the JSON and the SVG plot, and
// bad options exit with 2 and a message naming the option.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

const std::vector<std::string> kDamped = {"--set", "mesh.pinion-wheel.damping_ratio=0.05"};

std::vector<std::string> Args(std::vector<std::string> head) {
  head.insert(head.end(), kDamped.begin(), kDamped.end());
  return head;
}

TEST(HbCommandTest, JsonEqualsTheLibrarySweep) {
  const nlohmann::json report = RunJson(
      Args({"hb", "builtin:helical-pair", "--mesh-frequency", "300:3000:4", "--harmonics", "6"}));
  ASSERT_EQ(report["points"].size(), 4u);
  EXPECT_EQ(report["mode"], "linear");
  EXPECT_EQ(report["harmonics"], 6);
  EXPECT_EQ(report["meshes"][0], "pinion-wheel");
  const SystemModel model =
      MakeSystemModel(LoadScene("builtin:helical-pair", {"mesh.pinion-wheel.damping_ratio=0.05"}));
  HbOptions options;
  options.harmonics = 6;
  const HbSweepResult sweep = SweepHarmonicBalance(model, {300.0, 1200.0, 2100.0, 3000.0}, options);
  for (int i = 0; i < 4; ++i) {
    const auto& p = report["points"][i];
    EXPECT_DOUBLE_EQ(p["mesh_frequency_hz"].get<double>(), sweep.points[i].mesh_frequency_hz);
    EXPECT_EQ(p["status"], "success");
    EXPECT_EQ(p["harmonics"], 6);
    const auto& m = p["meshes"][0];
    const HbMeshOutput& lib = sweep.points[i].meshes[0];
    EXPECT_NEAR(m["rms_dte_m"].get<double>(), lib.rms_dte, 1e-12 * lib.rms_dte);
    EXPECT_NEAR(m["peak_to_peak_dte_m"].get<double>(), lib.peak_to_peak_dte,
                1e-12 * lib.peak_to_peak_dte);
    EXPECT_EQ(m["dte_amplitudes_m"].size(), 7u);
    EXPECT_GT(m["mean_force_n"].get<double>(), 0.0);  // the teeth are compressed
    EXPECT_EQ(p["elements"].size(), 4u);              // the four bearings
  }
}

TEST(HbCommandTest, OutWritesOneCsvRowPerMeshFrequency) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "hb_command_test";
  std::filesystem::remove_all(dir);
  const CliRun run = RunGeardyn(Args({"hb", "builtin:helical-pair", "--mesh-frequency",
                                      "200:2000:7", "--harmonics", "4", "--out", dir.string()}));
  ASSERT_EQ(run.code, kExitOk) << run.err;
  std::ifstream csv(dir / "hb.csv");
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(csv, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 8u);  // header + 7 mesh frequencies
  EXPECT_EQ(lines[0].rfind("mesh_frequency_hz,harmonics,error_estimate,status", 0), 0u);
  EXPECT_NE(lines[0].find("pinion-wheel:rms_dte_m"), std::string::npos);
  EXPECT_EQ(lines[1].rfind("200,4,", 0), 0u);
  EXPECT_TRUE(std::filesystem::exists(dir / "hb.json"));
  std::ifstream svg(dir / "hb_rms_dte.svg");
  std::stringstream svg_text;
  svg_text << svg.rdbuf();
  EXPECT_NE(svg_text.str().find("<svg"), std::string::npos);
}

TEST(HbCommandTest, BadOptionsExitWithTwoAndNameTheOption) {
  const struct {
    std::vector<std::string> args;
    std::string needle;
  } cases[] = {
      {{"--mesh-frequency", "2000:100:5"}, "--mesh-frequency"},
      {{"--mesh-frequency", "abc"}, "--mesh-frequency"},
      {{"--mesh-frequency", "0:100:5"}, "--mesh-frequency"},
      {{"--mesh-frequency", "100:200:2.5"}, "--mesh-frequency"},
      {{"--harmonics", "-3"}, "--harmonics"},
      {{"--tolerance", "0"}, "--tolerance"},
      // A fixed H with a tolerance: the tolerance would be ignored (issue 12).
      {{"--harmonics", "6", "--tolerance", "1e-9"}, "--tolerance"},
      // Bounded with the memory it would take, not bad_alloc (issue 12).
      {{"--harmonics", "100000"}, "GB"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"hb", "builtin:helical-pair"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliRun run = RunGeardyn(args);
    EXPECT_EQ(run.code, kExitBadInput) << c.args[1];
    EXPECT_NE(run.err.find(c.needle), std::string::npos) << run.err;
  }
}

TEST(HbCommandTest, RunoutKeepsTheMeshHarmonicsOfTheRig) {
  // Issue 12: a gear runout makes the hunting period P = 50 meshes; H = 8 counted harmonics of
  // ω_m/P and dropped the mesh frequency (RMS DTE 0.0064 µm instead of 1.67 µm). K is
  // mesh-periodic, so the mesh orders do not couple with the runout's sidebands: their DTE lines
  // must equal those of the same rig without runout (solved with P = 1), and the RMS can only
  // grow by the runout's own lines.
  const std::vector<std::string> base = {
      "hb", "builtin:kahraman-blankenship-rig", "--mesh-frequency", "2000", "--harmonics", "8"};
  std::vector<std::string> runout = Args(base);
  runout.insert(runout.end(), {"--set", "mesh.pinion-wheel.errors.gear_runout=1e-5"});
  const nlohmann::json with = RunJson(runout);
  const nlohmann::json without = RunJson(Args(base));
  const auto& a = with["points"][0];
  const auto& b = without["points"][0];
  ASSERT_EQ(a["period_meshes"], 50);
  ASSERT_EQ(b["period_meshes"], 1);
  const auto amp_a = a["meshes"][0]["dte_amplitudes_m"].get<std::vector<double>>();
  const auto amp_b = b["meshes"][0]["dte_amplitudes_m"].get<std::vector<double>>();
  ASSERT_EQ(amp_a.size(), 8u * 50u + 2u);  // up to the sideband 8·50 + 1
  ASSERT_EQ(amp_b.size(), 9u);
  for (int j = 1; j <= 8; ++j) {
    EXPECT_NEAR(amp_a[50 * j], amp_b[j], 1e-9 * amp_b[1]) << "mesh order " << j;
  }
  const double rms_a = a["meshes"][0]["rms_dte_m"].get<double>();
  const double rms_b = b["meshes"][0]["rms_dte_m"].get<double>();
  EXPECT_GE(rms_a, rms_b * (1.0 - 1e-9));
  EXPECT_GT(rms_b, 1e-6);  // about 1.7 µm: the mesh harmonic is there
}

TEST(HbCommandTest, WarnsWhenAnUndampedModeDominates) {
  // Issue 12: the rig's bearings have no damping, so its bearing modes have a modal damping
  // ratio of exactly 0; at 3290 Hz the response is theirs (RMS DTE about 2 mm). The verdict
  // must say so instead of a plain success.
  const nlohmann::json report = RunJson(
      {"hb", "builtin:kahraman-blankenship-rig", "--mesh-frequency", "3290", "--harmonics", "8"});
  bool warned = false;
  for (const auto& w : report["warnings"]) {
    warned = warned || w.get<std::string>().find("undamped mode") != std::string::npos;
  }
  EXPECT_TRUE(warned) << report["warnings"].dump();
}

TEST(HbCommandTest, TextModeListsTheMesh) {
  const CliRun run = RunGeardyn(Args(
      {"hb", "builtin:kahraman-blankenship-rig", "--mesh-frequency", "1500", "--harmonics", "8"}));
  ASSERT_EQ(run.code, kExitOk) << run.err;
  EXPECT_NE(run.out.find("pinion-wheel"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("RMS DTE"), std::string::npos);
}

}  // namespace
}  // namespace geardyn::app
