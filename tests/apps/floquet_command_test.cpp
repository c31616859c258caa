// `geardyn floquet`: the multipliers of a scene against a different Floquet method on the same
// scene (the general GSL stepper), the undamped reciprocal-pair invariant, the files written and
// the bad-input exits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "geardyn/models/scene/builtin_scenes.hpp"
#include "support/cli_run.hpp"

namespace geardyn {
namespace {

using test::RunGeardyn;
using test::RunJson;

constexpr const char* kRig = "builtin:kahraman-blankenship-rig";

std::vector<std::complex<double>> Multipliers(const nlohmann::json& j) {
  std::vector<std::complex<double>> out;
  for (const nlohmann::json& m : j["multipliers"]) {
    out.emplace_back(m["re"].get<double>(), m["im"].get<double>());
  }
  return out;
}

TEST(FloquetCommand, SpurRigExactStepsAgreeWithTheOdeStepper) {
  const nlohmann::json exact = RunJson({"floquet", kRig});
  const nlohmann::json ode =
      RunJson({"floquet", kRig, "--method", "ode_stepper", "--tolerance", "1e-9"});
  EXPECT_EQ(exact["method_requested"], "auto");
  EXPECT_EQ(exact["method_used"], "exact_steps");  // spur pair: piecewise-constant stiffness
  EXPECT_EQ(ode["method_used"], "ode_stepper");
  // 2400 rpm × 50 teeth / 60 = 2000 Hz (docs/scene-format.md, built-in scenes).
  EXPECT_NEAR(exact["mesh_frequency_hz"].get<double>(), 2000.0, 1e-9);
  const int n = exact["num_dofs"].get<int>();
  ASSERT_EQ(exact["multipliers"].size(), static_cast<std::size_t>(2 * n));
  const double tol = 1e-7 + ode["error_estimate"].get<double>();
  EXPECT_NEAR(exact["max_abs_multiplier"].get<double>(), ode["max_abs_multiplier"].get<double>(),
              tol);
  // Every multiplier of the exact product has a partner in the stepper's set.
  const auto a = Multipliers(exact), b = Multipliers(ode);
  for (const auto& l : a) {
    double nearest = 1e300;
    for (const auto& m : b) nearest = std::min(nearest, std::abs(l - m));
    EXPECT_LT(nearest, 1e-6) << l;
  }
}

TEST(FloquetCommand, UndampedRigHasReciprocalMultiplierPairs) {
  // The rig has no damping: Φ is symplectic, so 1/λ̄ is a multiplier whenever λ is, and the
  // product of all multipliers is det Φ = 1.
  const nlohmann::json j = RunJson({"floquet", kRig});
  const auto l = Multipliers(j);
  std::complex<double> product = 1.0;
  for (const auto& x : l) product *= x;
  EXPECT_NEAR(std::abs(product), 1.0, 1e-8);
  for (const auto& x : l) {
    double nearest = 1e300;
    for (const auto& y : l) nearest = std::min(nearest, std::abs(1.0 / std::conj(x) - y));
    EXPECT_LT(nearest, 1e-6) << x;
  }
  EXPECT_EQ(j["stable"].get<bool>(),
            j["max_abs_multiplier"].get<double>() <= 1.0 + j["error_estimate"].get<double>());
}

TEST(FloquetCommand, TextOutputAndFiles) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "floquet_command";
  std::filesystem::remove_all(dir);
  const test::CliRun run = RunGeardyn({"floquet", kRig, "--out", dir.string()});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.out.find("max|λ| = "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("method: exact_steps"), std::string::npos) << run.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "floquet.json"));
  std::ifstream csv(dir / "multipliers.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 1 + 2 * j["num_dofs"].get<int>());
}

// `--method arpack_monodromy --nev` end to end against the exact step product of the same damped
// rig: the largest |λ| agrees within the two error estimates (the ARPACK path itself is tested on
// ≥ 200 DOF in tests/analyses/floquet/arpack_monodromy_test.cpp).
TEST(FloquetCommand, ArpackDominantMultiplierMatchesExactSteps) {
  const std::vector<std::string> damped = {"--set", "mesh.pinion-wheel.damping_ratio=0.05"};
  std::vector<std::string> a = {"floquet", kRig, "--method", "arpack_monodromy", "--nev", "4"};
  std::vector<std::string> e = {"floquet", kRig};
  a.insert(a.end(), damped.begin(), damped.end());
  e.insert(e.end(), damped.begin(), damped.end());
  const nlohmann::json arpack = RunJson(a);
  const nlohmann::json exact = RunJson(e);
  EXPECT_EQ(arpack["method_used"], "arpack_monodromy");
  EXPECT_EQ(exact["method_used"], "exact_steps");
  // ≥ nev: blocks too small for ARPACK get all their multipliers from the dense path.
  EXPECT_GE(arpack["multipliers"].size(), 4u);
  const double tol =
      1e-9 + arpack["error_estimate"].get<double>() + exact["error_estimate"].get<double>();
  EXPECT_NEAR(arpack["max_abs_multiplier"].get<double>(), exact["max_abs_multiplier"].get<double>(),
              tol);
  const test::CliRun bad =
      RunGeardyn({"floquet", kRig, "--method", "arpack_monodromy", "--nev", "0"});
  EXPECT_EQ(bad.code, app::kExitBadInput);
  EXPECT_NE(bad.err.find("nev"), std::string::npos) << bad.err;
}

// Issue 12: the two commands that printed "max|λ| = inf → stable". Whatever they now answer, a
// "stable" verdict must rest on finite multipliers and status success, and an undetermined one
// must exit 1 (the rules of FloquetVerdict, checked on the JSON a script reads).
void ExpectHonestVerdict(const std::vector<std::string>& args) {
  std::vector<std::string> with_json = args;
  with_json.push_back("--json");
  const test::CliRun run = RunGeardyn(with_json);
  ASSERT_TRUE(run.code == app::kExitOk || run.code == app::kExitNumericalIssue) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  const std::string verdict = j["verdict"].get<std::string>();
  const std::string status = j["status"].get<std::string>();
  const bool finite =
      j["max_abs_multiplier"].is_number() && std::isfinite(j["max_abs_multiplier"].get<double>()) &&
      j["error_estimate"].is_number() && std::isfinite(j["error_estimate"].get<double>());
  SCOPED_TRACE(args[1] + " " + (args.size() > 2 ? args.back() : std::string()) + ": " + verdict +
               ", status " + status + ", " + j["message"].get<std::string>());
  if (verdict == "stable") {
    EXPECT_TRUE(finite);
    EXPECT_EQ(status, "success");
    EXPECT_LE(j["max_abs_multiplier"].get<double>(), 1.0 + j["error_estimate"].get<double>());
    for (const nlohmann::json& m : j["multipliers"]) {
      EXPECT_TRUE(m["abs"].is_number() && std::isfinite(m["abs"].get<double>()));
    }
    EXPECT_EQ(run.code, app::kExitOk);
  } else if (verdict == "unstable") {
    EXPECT_TRUE(status == "success" || status == "tolerance_not_met");
    EXPECT_FALSE(j["stable"].get<bool>());
  } else {
    EXPECT_EQ(verdict, "undetermined");
    EXPECT_EQ(run.code, app::kExitNumericalIssue);
    // Three-valued in JSON too: null, never false (which a script reads as "unstable").
    EXPECT_TRUE(j["stable"].is_null());
  }
}

TEST(FloquetCommand, IssueTwelveCasesAreNeverStableWithInfiniteMultipliers) {
  ExpectHonestVerdict({"floquet", "builtin:planetary-wind-turbine"});
  ExpectHonestVerdict(
      {"floquet", "builtin:helical-pair", "--set", "operating_point.speed_rpm=200"});
}

// Every built-in scene (`geardyn scenes`) at its own operating point: a verdict that follows the
// rules (never stable with inf/NaN or a failed status; undetermined exits 1).
TEST(FloquetCommand, BuiltinScenesAtTheirOperatingPointsHaveHonestVerdicts) {
  int checked = 0;
  for (const std::string& name : BuiltinSceneNames()) {
    ExpectHonestVerdict({"floquet", "builtin:" + name});
    ++checked;
  }
  EXPECT_GE(checked, 3);
}

// The built-in rig has no damping at all (examples/scenes, docs/scene-format.md): stable is then
// only marginal, and every flexible mode of `geardyn modes` (a different command and solver path)
// is listed as undamped.
TEST(FloquetCommand, UndampedRigIsMarginalAndNamesItsModes) {
  const nlohmann::json j = RunJson({"floquet", kRig});
  ASSERT_EQ(j["verdict"], "stable");
  EXPECT_TRUE(j["marginal"].get<bool>());
  const nlohmann::json modes = RunJson({"modes", kRig});
  std::size_t flexible = 0;
  for (const nlohmann::json& m : modes["modes"]) flexible += m["frequency_hz"].get<double>() > 0.0;
  EXPECT_EQ(j["undamped_modes"].size(), flexible);
  const test::CliRun text = RunGeardyn({"floquet", kRig});
  EXPECT_NE(text.out.find("stable, marginal (undamped modes: mode "), std::string::npos)
      << text.out;
}

// Every multiplier of a has one of b within 1e-10.
void ExpectSameMultipliers(const nlohmann::json& a_json, const nlohmann::json& b_json) {
  const auto a = Multipliers(a_json), b = Multipliers(b_json);
  ASSERT_EQ(a.size(), b.size());
  for (const auto& l : a) {
    double nearest = 1e300;
    for (const auto& m : b) nearest = std::min(nearest, std::abs(l - m));
    EXPECT_LT(nearest, 1e-10) << l;
  }
}

// Tooth errors give ε a hunting period but do not change K or C: the homogeneous problem's
// multipliers with a gear runout are those without it (truth: the run without the runout, one
// mesh period), and the reported period is the mesh period. floquet builds no ε at all, so the
// model's load period is one mesh cycle too.
TEST(FloquetCommand, RunoutDoesNotChangeTheMultipliers) {
  const nlohmann::json plain = RunJson({"floquet", kRig});
  const nlohmann::json runout =
      RunJson({"floquet", kRig, "--set", "mesh.pinion-wheel.errors.gear_runout=1e-5"});
  EXPECT_EQ(runout["period_meshes"].get<long>(), 1);
  // Reported only when the model's load period differs from the operator's: no ε, none.
  EXPECT_FALSE(runout["counters"].contains("load_period_meshes"));
  EXPECT_DOUBLE_EQ(runout["period_s"].get<double>(), plain["period_s"].get<double>());
  ExpectSameMultipliers(plain, runout);
}

// Coprime tooth counts 997/991 with a runout: a hunting period of 988 027 mesh cycles, whose ε
// table (2.5·10⁸ samples, 4 GB) floquet used to build before anything else. Truth: the same
// pair without the runout (ε does not enter M q̈ + C q̇ + K(θ) q = 0).
TEST(FloquetCommand, CoprimeTeethWithRunoutNeedNoHuntingPeriod) {
  const std::vector<std::string> teeth = {"--set", "gear.pinion.teeth=997", "--set",
                                          "gear.wheel.teeth=991"};
  std::vector<std::string> plain_args = {"floquet", "builtin:helical-pair"};
  plain_args.insert(plain_args.end(), teeth.begin(), teeth.end());
  std::vector<std::string> runout_args = plain_args;
  runout_args.insert(runout_args.end(), {"--set", "mesh.pinion-wheel.errors.gear_runout=1e-5"});
  const nlohmann::json plain = RunJson(plain_args);
  const nlohmann::json runout = RunJson(runout_args);
  EXPECT_FALSE(runout["counters"].contains("load_period_meshes"));
  EXPECT_EQ(runout["verdict"], plain["verdict"]);
  ExpectSameMultipliers(plain, runout);
}

TEST(FloquetCommand, BadInputExitsWithTwo) {
  const test::CliRun method = RunGeardyn({"floquet", kRig, "--method", "rk4"});
  EXPECT_EQ(method.code, app::kExitBadInput);
  EXPECT_NE(method.err.find("--method"), std::string::npos) << method.err;
  const test::CliRun tol = RunGeardyn({"floquet", kRig, "--tolerance", "-1"});
  EXPECT_EQ(tol.code, app::kExitBadInput);
  const test::CliRun speed = RunGeardyn({"floquet", kRig, "--set", "operating_point.speed_rpm=0"});
  EXPECT_EQ(speed.code, app::kExitBadInput);
  EXPECT_NE(speed.err.find("mesh frequency is 0"), std::string::npos) << speed.err;
  // The rational-approximant bound is FloquetOptions' [0, 10⁴] mesh cycles.
  for (const char* bound : {"-1", "20000", "ten"}) {
    const test::CliRun approximant =
        RunGeardyn({"floquet", kRig, "--max-approximant-period", bound});
    EXPECT_EQ(approximant.code, app::kExitBadInput) << bound;
    EXPECT_NE(approximant.err.find("--max-approximant-period"), std::string::npos)
        << approximant.err;
  }
}

TEST(FloquetCommand, OneMeshFrequencyHasNoApproximants) {
  // The study is for incommensurate trains only: a single-frequency scene reports none, and the
  // bound (0 included) does not change its answer.
  const nlohmann::json j = RunJson({"floquet", kRig});
  const nlohmann::json off = RunJson({"floquet", kRig, "--max-approximant-period", "0"});
  EXPECT_TRUE(j["approximants"].empty());
  EXPECT_EQ(j["max_abs_multiplier"], off["max_abs_multiplier"]);
  EXPECT_EQ(j["verdict"], off["verdict"]);
}

}  // namespace
}  // namespace geardyn
