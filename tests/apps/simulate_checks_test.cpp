// `geardyn simulate`'s pre-run checks and run bookkeeping (session 25): the warnings on a speed far
// above every mode and on a load beyond the teeth's elastic range (their numbers against closed
// forms), the `run.history` label, and `--quasi-static` of a contact mesh with backlash at zero
// torque (free play: K = 0 exactly, success, no NaN).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "geardyn/cli.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::CliRun;
using test::RunGeardyn;

const std::string kRig = "builtin:kahraman-blankenship-rig";

nlohmann::json Report(const std::vector<std::string>& args, int expected_code) {
  std::vector<std::string> a = args;
  a.push_back("--json");
  const CliRun run = RunGeardyn(a);
  EXPECT_EQ(run.code, expected_code) << run.err;
  return nlohmann::json::parse(run.out);
}

std::string Find(const nlohmann::json& warnings, const std::string& needle) {
  for (const auto& w : warnings) {
    if (w.get<std::string>().find(needle) != std::string::npos) return w.get<std::string>();
  }
  return "";
}

// The number right after `key` in `text`.
double NumberAfter(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  EXPECT_NE(at, std::string::npos) << text;
  return at == std::string::npos ? std::nan("") : std::stod(text.substr(at + key.size()));
}

// The rig's highest natural frequency is its mesh mode ≈ 5–6 kHz (torsional pair, stiff
// bearings: below 1e5 Hz); 1e8 Hz is flagged with the factor f_m / f_max > 100.
TEST(SimulateChecks, MeshFrequencyFarAboveEveryModeIsFlagged) {
  const nlohmann::json r = Report(
      {"simulate", kRig, "--mesh-frequency", "1e8", "--max-periods", "1"}, kExitNumericalIssue);
  const std::string w = Find(r["warnings"], "times the highest natural frequency");
  ASSERT_FALSE(w.empty()) << r["warnings"].dump();
  const double factor = NumberAfter(w, "Hz is ");
  const double f_max = NumberAfter(w, "of the system (");
  EXPECT_GT(factor, 100.0);
  EXPECT_NEAR(factor * f_max, 1e8, 1e-2 * 1e8);  // the factor is f_m / f_max (3 digits)
  EXPECT_LT(f_max, 1e5);
  // The operating point (2000 Hz) is not flagged.
  const nlohmann::json ok = Report({"simulate", kRig, "--max-periods", "1"}, kExitNumericalIssue);
  EXPECT_TRUE(Find(ok["warnings"], "highest natural frequency").empty());
  EXPECT_TRUE(Find(ok["warnings"], "deflects").empty());
  // Stopped by --max-periods: the histories are the period recorded after it, not steady.
  EXPECT_EQ(ok["run"]["history"], "not_steady");
}

// 1e7 N·m on the rig: δ_η = F/K(θ₀) with F = T/r_b (the mesh holds the pinion alone, ε = 0 on
// unmodified teeth), ≈ 0.35 m — far beyond 2 % of p_bn = π m cos α ≈ 8.86 mm: flagged with δ.
TEST(SimulateChecks, TorqueBeyondTheTeethsScaleIsFlaggedWithItsDeflection) {
  const nlohmann::json r =
      Report({"simulate", kRig, "--torque", "1e7", "--max-periods", "1"}, kExitNumericalIssue);
  const std::string w = Find(r["warnings"], "deflects");
  ASSERT_FALSE(w.empty()) << r["warnings"].dump();
  EXPECT_NE(w.find("1e+07 N·m: mesh pinion-wheel"), std::string::npos) << w;
  // The model at 1e7 N·m (ISO's stiffness depends on the line load).
  const SystemModel model =
      MakeSystemModel(LoadScene(kRig, {"operating_point.torque=1e7", "load.brake.torque=1e7"}));
  const auto& core = std::get<LinearMeshCore>(model.meshes()[0].core);
  const double rb = 0.070477;  // base radius [m] (docs/design.md, rig geometry)
  const double expected = 1e7 / rb / EvalStiffnessCore(core, 0.0)(0, 0);
  EXPECT_NEAR(NumberAfter(w, "deflects ") * 1e-6, expected, 0.02 * expected);
}

// A contact mesh with backlash (centre distance +0.2 mm) at zero torque: every position in the
// backlash is an equilibrium; the export succeeds and says "free play". The mesh force is 0 and
// K is 0 up to the round-off touch of the flanks at the rest position (Hertz tangent at
// δ ≈ 1e-17 m: < 1e-5 of the loaded K̄ ≈ 2.9e9 N/m).
TEST(SimulateChecks, QuasiStaticOfAContactMeshInFreePlay) {
  const nlohmann::json r = Report(
      {"simulate", kRig, "--quasi-static", "--samples-per-period", "8", "--torque", "0", "--set",
       "mesh.pinion-wheel.model=\"contact\"", "--set", "mesh.pinion-wheel.center_distance=0.1502"},
      kExitOk);
  ASSERT_EQ(r["status"], "success");
  const auto& run = r["runs"][0];
  EXPECT_FALSE(Find(run["warnings"], "free play").empty()) << run["warnings"].dump();
  ASSERT_EQ(run["meshes"][0]["stiffness_n_per_m"].size(), 8u);
  for (const auto& k : run["meshes"][0]["stiffness_n_per_m"]) EXPECT_LT(k.get<double>(), 3e4);
  for (const auto& f : run["meshes"][0]["force_n"]) EXPECT_LT(std::abs(f.get<double>()), 1e-9);
}

}  // namespace
}  // namespace geardyn::app
