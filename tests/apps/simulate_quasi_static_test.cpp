// `geardyn simulate --quasi-static`: the loaded K(θ) and STE written as a [mesh.parameters]
// table. Truths: an LTV source without tooth modifications has ε = 0, so the exported
// ε_η = STE − F/K (from the static solve) must vanish and K must be the source's channel; a
// slice source's K equals the LTV core of the same pair within the slicing error; and the table
// read back through the scene reader (--set) gives an LTV scene that `modes` and `hb` run, with
// the HB RMS DTE of the source within the table's linear-interpolation error.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "geardyn/cli.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

constexpr int kSamples = 64;
// Static solve and 17-digit round trip [-], relative to the STE.
constexpr double kStaticTol = 1e-8;
// Slices vs contact lines [-]: the slicing error of K is O(N⁻²) (mesh_cores.hpp).
constexpr double kSliceTol = 2e-2;
// HB of the table vs the source [-]: the table is the linear interpolation of K(θ) between 64
// samples (the contact-line K jumps where a line enters or leaves: one sample of smearing).
constexpr double kTableHbTol = 5e-2;

const std::string kRig = "builtin:kahraman-blankenship-rig";

std::string ReadFirstLine(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

nlohmann::json QuasiStatic(const std::vector<std::string>& sets, const std::string& dir) {
  std::vector<std::string> args = {
      "simulate", kRig, "--quasi-static", "--samples-per-period", std::to_string(kSamples),
      "--out",    dir};
  for (const std::string& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  return RunJson(args);
}

TEST(SimulateQuasiStaticTest, LtvSourceGivesItsOwnStiffnessAndZeroTransmissionError) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "simulate_qs_ltv";
  const nlohmann::json report = QuasiStatic({}, dir.string());
  ASSERT_EQ(report["status"], "success");
  const auto& mesh = report["runs"][0]["meshes"][0];
  const SystemModel model = MakeSystemModel(LoadScene(kRig));
  const auto& core = std::get<LinearMeshCore>(model.meshes()[0].core);
  double ste_max = 0.0;
  for (int s = 0; s < kSamples; ++s) {
    ste_max = std::max(ste_max, std::abs(mesh["loaded_ste_m"][s].get<double>()));
  }
  ASSERT_GT(ste_max, 0.0);  // loaded: the teeth deflect
  for (int s = 0; s < kSamples; ++s) {
    const double theta = 2.0 * std::numbers::pi * s / kSamples;
    const double k = EvalStiffnessCore(core, theta)(0, 0);
    EXPECT_NEAR(mesh["stiffness_n_per_m"][s].get<double>(), k, 1e-12 * k) << s;
    EXPECT_NEAR(mesh["transmission_error_m"][s].get<double>(), 0.0, kStaticTol * ste_max) << s;
    // F = K·STE along η (ε = 0): the static mesh force from the torque.
    EXPECT_NEAR(mesh["force_n"][s].get<double>(), k * mesh["loaded_ste_m"][s].get<double>(),
                kStaticTol * k * ste_max)
        << s;
  }
}

TEST(SimulateQuasiStaticTest, SliceTableReadBackGivesAnLtvSceneThatModesAndHbRun) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "simulate_qs_slices";
  const nlohmann::json report = QuasiStatic(
      {"mesh.pinion-wheel.model=slices", "mesh.pinion-wheel.damping_ratio=0.05"}, dir.string());
  ASSERT_EQ(report["status"], "success");
  const auto& mesh = report["runs"][0]["meshes"][0];
  // K of the slices vs the contact-line LTV core of the same pair.
  const SystemModel ltv = MakeSystemModel(LoadScene(kRig));
  const auto& core = std::get<LinearMeshCore>(ltv.meshes()[0].core);
  for (int s = 0; s < kSamples; ++s) {
    const double k = EvalStiffnessCore(core, 2.0 * std::numbers::pi * s / kSamples)(0, 0);
    EXPECT_NEAR(mesh["stiffness_n_per_m"][s].get<double>(), k, kSliceTol * k) << s;
  }
  // The table read back through the scene reader.
  const std::string set = ReadFirstLine(dir / "mesh_parameters_set.txt");
  ASSERT_EQ(set.rfind("mesh.pinion-wheel.parameters={form=\"table\"", 0), 0u) << set;
  std::ifstream toml(dir / "mesh_parameters.toml");
  std::stringstream toml_text;
  toml_text << toml.rdbuf();
  EXPECT_NE(toml_text.str().find("[mesh.parameters]\nform = \"table\"\nstiffness = ["),
            std::string::npos);
  const std::vector<std::string> damped = {"--set", "mesh.pinion-wheel.damping_ratio=0.05"};
  const CliRun modes = RunGeardyn({"modes", kRig, "--set", set});
  EXPECT_EQ(modes.code, kExitOk) << modes.err;
  const nlohmann::json hb_table =
      RunJson({"hb", kRig, "--set", set, "--set", "mesh.pinion-wheel.damping_ratio=0.05",
               "--mesh-frequency", "1000", "--stability", "none"});
  const nlohmann::json hb_slices_linear =
      RunJson({"hb", kRig, "--set", "mesh.pinion-wheel.model=slices", "--set",
               "mesh.pinion-wheel.damping_ratio=0.05", "--linear", "--mesh-frequency", "1000",
               "--stability", "none"});
  const double a = hb_table["points"][0]["meshes"][0]["rms_dte_m"].get<double>();
  const double b = hb_slices_linear["points"][0]["meshes"][0]["rms_dte_m"].get<double>();
  ASSERT_GT(b, 0.0);
  EXPECT_NEAR(a, b, kTableHbTol * b);
}

}  // namespace
}  // namespace geardyn::app
