// `geardyn hb` on a scene with two mesh frequencies (issue 18): the quasi-periodic path. Truths:
// the bases follow from the tooth counts (parallel mesh z_w Ω_s, planetary z_r Ω_c, Ω_s/Ω_c =
// 1 + z_r/z_s: ratio z_r z_s / (z_w (z_s + z_r)) = 99·21/(99·120) = 7/40), the periodic path's
// refusals are replaced by named errors (exit code 2), and no stability verdict is claimed.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::RunGeardyn;

const std::string kTwoStage =
    std::string(GEARDYN_SOURCE_DIR) + "/examples/multi-stage/wind-turbine-two-stage.toml";

TEST(HbQuasiPeriodicCommand, SolvesTheTwoStageTrainOnTheTorusWithoutAVerdict) {
  const auto run =
      RunGeardyn({"hb", kTwoStage, "--mesh-frequency", "208.37", "--harmonics", "4", "--json"});
  ASSERT_EQ(run.code, 0) << run.err << run.out.substr(0, 2000);
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["mode"], "linear, quasi-periodic");
  ASSERT_EQ(j["quasi_periodic"]["bases"].size(), 2u);
  EXPECT_NEAR(j["quasi_periodic"]["bases"][1]["phase_ratio"].get<double>(), 7.0 / 40.0, 1e-12);
  EXPECT_NEAR(j["quasi_periodic"]["bases"][1]["frequency_hz"].get<double>(), 208.37 * 7 / 40, 1e-9);
  EXPECT_EQ(j["quasi_periodic"]["bases"][1]["meshes"].size(), 6u);  // 3 planets × 2 meshes
  EXPECT_EQ(j["stability"], "none");
  EXPECT_TRUE(j.contains("stability_note"));
  const auto& p = j["points"][0];
  EXPECT_EQ(p["status"], "success");
  ASSERT_EQ(p["meshes"].size(), 7u);
  for (const auto& m : p["meshes"]) {
    EXPECT_GT(m["rms_dte_m"].get<double>(), 0.0) << m["name"];
    // Bhatia–Davis: a signal in [m, M] has variance ≤ ((M − m)/2)², so p-p ≥ 2·RMS (the torus
    // grid samples the p-p from below: 1 % margin).
    EXPECT_GE(m["peak_to_peak_dte_m"].get<double>(), 2.0 * m["rms_dte_m"].get<double>() * 0.99)
        << m["name"];
    // The largest line of each mesh is its own mesh frequency (order 1 of its own base).
    const auto& top = m["lines"][0];
    const int base = m["base"].get<int>();
    EXPECT_EQ(top["order"][base].get<int>(), 1) << m["name"];
    EXPECT_EQ(top["order"][1 - base].get<int>(), 0) << m["name"];
  }
}

// Without --harmonics the order is searched (H = 4, 8, … until the RMS DTE of every mesh moves by
// at most 2 % of the largest): it stops at H = 8 on this scene, whose H = 8 → 12 change is 0.06 %
// (docs/benchmarks.md), and the answer is the fixed-H = 8 one.
TEST(HbQuasiPeriodicCommand, DefaultOrderSearchSettlesAtAnAffordableOrder) {
  const auto searched = RunGeardyn({"hb", kTwoStage, "--mesh-frequency", "208.37", "--json"});
  ASSERT_EQ(searched.code, 0) << searched.err << searched.out.substr(0, 1000);
  const nlohmann::json a = nlohmann::json::parse(searched.out)["points"][0];
  EXPECT_EQ(a["harmonics"].get<int>(), 8);
  const auto fixed =
      RunGeardyn({"hb", kTwoStage, "--mesh-frequency", "208.37", "--harmonics", "8", "--json"});
  ASSERT_EQ(fixed.code, 0) << fixed.err;
  const nlohmann::json b = nlohmann::json::parse(fixed.out)["points"][0];
  for (std::size_t k = 0; k < b["meshes"].size(); ++k) {
    EXPECT_DOUBLE_EQ(a["meshes"][k]["rms_dte_m"].get<double>(),
                     b["meshes"][k]["rms_dte_m"].get<double>());
  }
  // The error estimate is the H/2 → H change, below the 2 % it accepts (not the torus estimate
  // of the H = 8 solution, 0.044).
  EXPECT_LE(a["error_estimate"].get<double>(), 0.02);
}

// Slice meshes on the two-stage train: the nonlinear quasi-periodic HB (contact loss possible).
// At the rated load every mesh stays in contact, and then the slice force is the linear mesh
// force with every slice loaded: the RMS DTE of every mesh equals the linear quasi-periodic HB's
// (--linear, the same slices linearized) up to the AFT's sampling of the helical slice
// stiffness (measured ≤ 0.25 %, the planet–ring meshes).
TEST(HbQuasiPeriodicCommand, SliceMeshesInFullContactEqualTheLinearModel) {
  const std::vector<std::string> slices = {"--set", "mesh.sun-planet.model=\"slices\"",
                                           "--set", "mesh.planet-ring.model=\"slices\"",
                                           "--set", "mesh.hs-pinion-hs-wheel.model=\"slices\""};
  std::vector<std::string> args = {"hb", kTwoStage, "--mesh-frequency", "208.37", "--harmonics",
                                   "8",  "--json"};
  args.insert(args.end(), slices.begin(), slices.end());
  const auto nonlinear = RunGeardyn(args);
  ASSERT_EQ(nonlinear.code, 0) << nonlinear.err << nonlinear.out.substr(0, 1000);
  args.push_back("--linear");
  const auto linear = RunGeardyn(args);
  ASSERT_EQ(linear.code, 0) << linear.err;
  const nlohmann::json a = nlohmann::json::parse(nonlinear.out);
  const nlohmann::json b = nlohmann::json::parse(linear.out);
  EXPECT_EQ(a["mode"], "nonlinear, quasi-periodic");
  EXPECT_EQ(b["mode"], "linear, quasi-periodic");
  EXPECT_EQ(a["stability"], "none");
  const auto& pa = a["points"][0];
  const auto& pb = b["points"][0];
  EXPECT_EQ(pa["method"], "quasi_periodic_nonlinear");
  ASSERT_EQ(pa["meshes"].size(), 7u);
  for (std::size_t k = 0; k < 7; ++k) {
    const auto& ma = pa["meshes"][k];
    EXPECT_EQ(ma["contact_loss_fraction"].get<double>(), 0.0) << ma["name"];
    EXPECT_GT(ma["min_force_n"].get<double>(), 0.0) << ma["name"];
    const double rms = pb["meshes"][k]["rms_dte_m"].get<double>();
    EXPECT_NEAR(ma["rms_dte_m"].get<double>(), rms, 5e-3 * rms) << ma["name"];
    const double mean = pb["meshes"][k]["mean_dte_m"].get<double>();
    EXPECT_NEAR(ma["mean_dte_m"].get<double>(), mean, 5e-3 * std::abs(mean)) << ma["name"];
  }
}

TEST(HbQuasiPeriodicCommand, BadInputExitsWithTwoNamingTheFlag) {
  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {{"hb", kTwoStage, "--mesh-frequency", "208.37", "--harmonics", "200"},
       {"--harmonics", "GB", "lower --harmonics"}},
      {{"hb", kTwoStage, "--mesh-frequency", "208.37", "--harmonics", "1000"}, {"--harmonics"}},
      {{"hb", kTwoStage, "--mesh-frequency", "208.37", "--nonlinear"},
       {"--nonlinear", "no slice mesh"}},
      {{"hb", kTwoStage, "--mesh-frequency", "208.37", "--harmonics", "4", "--tolerance", "1e-3"},
       {"--tolerance"}},
      // A runout on the 99-tooth wheel: the mesh frequency is order 2277 of its base (the
      // hunting period); before, H = 8 returned 0.023 µm RMS DTE instead of 1.85 µm, with
      // status success (the mesh harmonic lost).
      {{"hb", kTwoStage, "--mesh-frequency", "208.37", "--set",
        "mesh.hs-pinion-hs-wheel.errors.gear_runout=5e-6"},
       {"--harmonics", "2277", "mesh frequency"}},
      {{"hb", kTwoStage, "--mesh-frequency", "208.37", "--harmonics", "8", "--set",
        "mesh.hs-pinion-hs-wheel.errors.gear_runout=5e-6"},
       {"--harmonics", "tooth errors"}},
      // Floquet over the common period is there, but Hill expands one frequency's harmonics.
      {{"floquet", kTwoStage, "--method", "hill"}, {"hill", "several"}},
  };
  for (const Case& c : cases) {
    const auto run = RunGeardyn(c.args);
    EXPECT_EQ(run.code, 2) << c.args.back() << "\n" << run.err << run.out.substr(0, 500);
    for (const std::string& part : c.expected) {
      EXPECT_NE(run.err.find(part), std::string::npos) << "expected '" << part << "' in\n"
                                                       << run.err;
    }
  }
}

}  // namespace
}  // namespace geardyn::app
