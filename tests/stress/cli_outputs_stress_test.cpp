// Numerical stress suite, part A — the command-line path (issue 16): `geardyn modes | floquet |
// stability-chart ... --out DIR` on hard settings (repeated frequencies, damped modes, mesh
// frequencies of ~1e-3 Hz and ~1e6 Hz) exits cleanly and writes no "nan"/"inf" number into any
// JSON or CSV file. Truth: the invariant itself (issue 16: never NaN/Inf in results), plus the
// exit code and the files the command documents.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "stress/stress_cases.hpp"
#include "support/cli_run.hpp"

namespace geardyn::stress {
namespace {

struct CliCase {
  std::string name;
  std::vector<std::string> args;   // without --out
  std::vector<std::string> files;  // expected in the output directory
};
void PrintTo(const CliCase& c, std::ostream* os) { *os << c.name; }

std::vector<CliCase> Cases() {
  const std::string rig = "builtin:kahraman-blankenship-rig";
  return {
      {"modes_planetary_repeated_damped_shapes",
       {"modes", "builtin:planetary-lin-parker", "--damped", "--shapes"},
       {"modes.json", "modes.csv", "mode_shapes.csv"}},
      {"modes_rig_all_damped",
       {"modes", rig, "--modes", "40", "--damped"},
       {"modes.json", "modes.csv"}},
      {"modes_rig_arpack",
       {"modes", rig, "--method", "arpack", "--modes", "6"},
       {"modes.json", "modes.csv"}},
      // 2400 rpm ↔ 2000 Hz on the rig: 0.001 rpm ≈ 8e-4 Hz, 1e6 rpm ≈ 8e5 Hz.
      {"floquet_rig_very_low_speed",
       {"floquet", rig, "--set", "operating_point.speed_rpm=0.001"},
       {"floquet.json", "multipliers.csv"}},
      {"floquet_rig_very_high_speed",
       {"floquet", rig, "--set", "operating_point.speed_rpm=1e6"},
       {"floquet.json", "multipliers.csv"}},
      {"stability_chart_pair_small",
       {"stability-chart", "builtin:helical-pair", "--x", "operating_point.speed_rpm=3000:9000:3",
        "--y", "operating_point.torque=100:200:2", "--threads", "2", "--tolerance", "1e-6",
        "--quiet"},
       {"stability_chart.csv"}},
  };
}

class CliStress : public ::testing::TestWithParam<CliCase> {};

TEST_P(CliStress, CleanExitAndNoNonFiniteNumberInTheFiles) {
  const CliCase& c = GetParam();
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "stress_cli" / c.name;
  std::filesystem::remove_all(dir);
  std::vector<std::string> args = c.args;
  args.push_back("--out");
  args.push_back(dir.string());
  const test::CliRun run = test::RunGeardyn(args);
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_FALSE(HasNonFiniteToken(run.out)) << run.out;
  for (const std::string& name : c.files) {
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  }
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".json" && ext != ".csv") continue;
    ++files;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_FALSE(HasNonFiniteToken(text.str())) << entry.path() << " holds a nan/inf number";
  }
  EXPECT_GE(files, static_cast<int>(c.files.size()));
}

INSTANTIATE_TEST_SUITE_P(Cases, CliStress, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<CliCase>& param_info) {
                           return param_info.param.name;
                         });

// The detector itself (a test helper must be tested): JSON/CSV number tokens, not words.
TEST(CliStressHelper, NonFiniteTokenDetector) {
  EXPECT_TRUE(HasNonFiniteToken("[1, nan, 2]"));
  EXPECT_TRUE(HasNonFiniteToken("x,-inf,3"));
  EXPECT_TRUE(HasNonFiniteToken("{\"a\": Infinity}"));
  EXPECT_TRUE(HasNonFiniteToken("1,NaN\n"));
  EXPECT_FALSE(HasNonFiniteToken("\"dominant_dof\": \"pinion.z\", \"info\": 1"));
  EXPECT_FALSE(HasNonFiniteToken("{\"a\": null}"));
}

}  // namespace
}  // namespace geardyn::stress
