// The oscillator scenes through the commands: `geardyn hb` (nonlinear, with the jump), `geardyn
// floquet` (linear LTV level, principal tongue), `geardyn modes` and `info`, and the exit code 2
// with FILE:LINE: KEY: REASON on bad oscillator input; the commands that need gears refuse
// clearly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/cli_run.hpp"

namespace geardyn {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

constexpr const char* kBk = "builtin:blankenship-kahraman-oscillator";

TEST(OscillatorCommand, HbIsNonlinearAndFindsTheJump) {
  const nlohmann::json j =
      RunJson({"hb", kBk, "--mesh-frequency", "0.5:1.5:40", "--branch-search", "0"});
  EXPECT_EQ(j["mode"], "nonlinear");
  EXPECT_EQ(j["status"], "success") << j["message"];
  ASSERT_GE(j["jumps"].size(), 2u);  // the up- and down-sweep jumps of the softening resonance
  ASSERT_GE(j["folds_hz"].size(), 2u);
  for (const auto& f : j["folds_hz"]) {
    EXPECT_GT(f.get<double>(), 0.3);  // a branch may turn back below the range's start
    EXPECT_LT(f.get<double>(), 1.0);  // softening: below the linear resonance Ω = 1
  }
}

TEST(OscillatorCommand, LinearLevelsRunTheLinearHb) {
  const nlohmann::json j = RunJson({"hb", kBk, "--set", "oscillator.model=lti", "--mesh-frequency",
                                    "0.5:1.5:11", "--stability", "none"});
  EXPECT_NE(j["mode"], "nonlinear");
  const CliRun bad = RunGeardyn({"hb", kBk, "--set", "oscillator.model=lti", "--nonlinear"});
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("oscillator.model=slices"), std::string::npos) << bad.err;
}

TEST(OscillatorCommand, FloquetOfTheLtvLevelInAndOutOfThePrincipalTongue) {
  // α = 0.2 against the first-order threshold 4ζ = 0.08 (ζ = 0.02): inside the tongue at Ω = 2.
  const nlohmann::json in =
      RunJson({"floquet", kBk, "--set", "oscillator.model=torsional", "--set",
               "oscillator.zeta=0.02", "--set", "oscillator.frequency_ratio=2.0"});
  EXPECT_NEAR(in["mesh_frequency_hz"].get<double>(), 2.0, 1e-15);
  EXPECT_EQ(in["verdict"], "unstable");
  const nlohmann::json out = RunJson({"floquet", kBk, "--set", "oscillator.model=torsional",
                                      "--set", "oscillator.frequency_ratio=1.5"});
  EXPECT_EQ(out["verdict"], "stable");
}

TEST(OscillatorCommand, ModesAndInfo) {
  const nlohmann::json modes = RunJson({"modes", kBk});
  ASSERT_GE(modes["frequencies_hz"].size(), 1u);
  EXPECT_NEAR(modes["frequencies_hz"][0].get<double>(), 1.0, 1e-12);
  const CliRun info = RunGeardyn({"info", kBk});
  EXPECT_EQ(info.code, 0);
  EXPECT_NE(info.out.find("1 Hz"), std::string::npos) << info.out;
  const CliRun mesh = RunGeardyn({"mesh", kBk});
  EXPECT_EQ(mesh.code, 2);
  EXPECT_NE(mesh.err.find("oscillator"), std::string::npos) << mesh.err;
}

TEST(OscillatorCommand, BadOscillatorInputExitsTwoNamingFileKeyAndReason) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "geardyn_bad_oscillator.toml";
  {
    std::ofstream f(path);
    f << "[oscillator]\nzeta = 0.05\nalpha = 1.2\n";
  }
  const CliRun run = RunGeardyn({"hb", path.string()});
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.err.find(path.string() + ":3: oscillator.alpha: "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("|alpha| < 1"), std::string::npos) << run.err;
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace geardyn
