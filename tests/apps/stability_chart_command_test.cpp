// `geardyn stability-chart`: bad axes, the files of a small chart on the helical pair, and the
// helical pair's chart over speed × mesh-stiffness variation against the parametric resonances
// 2f_p/k and (f_p + f_q)/k of its LTI modes (computed here by ComputeModes on the same scene).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/cli_run.hpp"

namespace geardyn {
namespace {

using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

constexpr const char* kPair = "builtin:helical-pair";

void ExpectBadAxis(const std::vector<std::string>& axes, const std::string& message) {
  std::vector<std::string> args = {"stability-chart", kPair};
  args.insert(args.end(), axes.begin(), axes.end());
  const CliRun run = RunGeardyn(args);
  EXPECT_EQ(run.code, app::kExitBadInput) << run.out;
  EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
}

TEST(StabilityChartCommand, BadAxesExitWithTwoAndAClearMessage) {
  const std::string y = "operating_point.torque=100:200:3";
  ExpectBadAxis({"--x", "foo=1:2", "--y", y}, "--x foo=1:2: expected PATH=LO:HI:N");
  ExpectBadAxis({"--x", "operating_point.speed_rpm=1000:2000:1", "--y", y},
                "the number of points must be at least 2");
  ExpectBadAxis({"--x", "operating_point.speed_rpm=2000:1000:4", "--y", y},
                "the lower bound must be below the upper bound");
  ExpectBadAxis({"--x", "operating_point.speed_rpm=1000:1000:4", "--y", y},
                "the lower bound must be below the upper bound");
  ExpectBadAxis({"--x", "operating_point.speed_rpm=a:1000:4", "--y", y},
                "the lower bound 'a' is not a finite number");
  ExpectBadAxis({"--x", "operating_point.speed_rpm=0:1000:4", "--y", y}, "must be > 0");
  ExpectBadAxis({"--x", "operating_point.speed_rpm=1000:2000:3", "--y",
                 "mesh.pinion-wheel.stiffnes_per_length=1e10:2e10:3"},
                "--y mesh.pinion-wheel.stiffnes_per_length=");
  ExpectBadAxis(
      {"--x", "operating_point.speed_rpm=1000:2000:3", "--y", "gear.pinion.teeth=10:-5:3"},
      "the lower bound must be below the upper bound");
  ExpectBadAxis(
      {"--x", "operating_point.speed_rpm=1000:2000:3", "--y", "operating_point.speed_rpm=1:2:3"},
      "name the same scene path");
}

TEST(StabilityChartCommand, SmallChartWritesOneCsvRowPerPoint) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "stability_chart_small";
  std::filesystem::remove_all(dir);
  const int nx = 3, ny = 2;
  const CliRun run = RunGeardyn(
      {"stability-chart", kPair, "--x", "operating_point.speed_rpm=3000:9000:" + std::to_string(nx),
       "--y", "operating_point.torque=100:200:" + std::to_string(ny), "--threads", "2",
       "--tolerance", "1e-6", "--no-curves", "--out", dir.string()});
  ASSERT_EQ(run.code, 0) << run.err;
  EXPECT_NE(run.err.find("stability-chart: grid 100 %"), std::string::npos) << run.err;
  std::ifstream csv(dir / "stability_chart.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "x,y,mesh_frequency_hz,max_abs_multiplier,error_estimate,stable,ok,region,label");
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    // f_m = 25 teeth × rpm / 60 (column 3) at the row's speed (column 1).
    const double rpm = std::stod(line.substr(0, line.find(',')));
    const std::size_t c2 = line.find(',', line.find(',') + 1);
    const double f_m = std::stod(line.substr(c2 + 1));
    EXPECT_NEAR(f_m, 25.0 * rpm / 60.0, 1e-9 * f_m);
  }
  EXPECT_EQ(rows, nx * ny);
  EXPECT_TRUE(std::filesystem::exists(dir / "transition_curves.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "stability_chart.svg"));
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "stability_chart.json"));
  EXPECT_EQ(j["num_points"].get<int>(), nx * ny);
  EXPECT_EQ(j["speed_axis"], "x");
  // Speed only changes f_m: the model is built once per torque value plus the two axis-end
  // checks (no bisection here), not once per point.
  EXPECT_EQ(j["model_builds"].get<long>(), ny + 2);
}

TEST(StabilityChartCommand, HelicalPairPrincipalRegionOfTheMeshModeSitsOnItsResonance) {
  // K(θ) = 4e8 + a cos θ N/m (user Fourier parameters), a = 0 … 1.6e8 N/m; speed around the
  // principal resonance f_m = 2 f_p of the mode with the most mesh strain energy (issue 5 "Must
  // show"; the full chart over 10 000–40 000 rpm is in docs/benchmarks.md).
  const std::string set = "mesh.pinion-wheel.parameters={form=\"fourier\", stiffness=[4e8, 0, 0]}";
  // Truth: the LTI modes of the same scene (a = 0), by ComputeModes.
  const SystemModel model = MakeSystemModel(LoadScene(kPair, {set}));
  const ModalResult modes = ComputeModes(model, {});
  int mesh_mode = -1;
  double best = 0.0;
  for (std::size_t c = 0; c < modes.strain_names.size(); ++c) {
    if (modes.strain_names[c] != "mesh:pinion-wheel") continue;
    for (Eigen::Index m = 0; m < modes.strain_fractions.rows(); ++m) {
      if (modes.strain_fractions(m, c) > best) {
        best = modes.strain_fractions(m, c);
        mesh_mode = static_cast<int>(m);
      }
    }
  }
  ASSERT_GE(mesh_mode, 0);
  const double rpm = 2.0 * modes.frequencies_hz[mesh_mode] * 60.0 / 25.0;  // f_m = 25 n / 60
  const nlohmann::json j = RunJson({"stability-chart", kPair, "--set", set, "--x",
                                    "operating_point.speed_rpm=" + std::to_string(0.94 * rpm) +
                                        ":" + std::to_string(1.06 * rpm) + ":7",
                                    "--y", "mesh.pinion-wheel.parameters.stiffness.1=0:1.6e8:3",
                                    "--tolerance", "1e-6", "--no-curves"});
  const std::string label = "2f_" + std::to_string(mesh_mode) + "/1";
  bool found = false;
  for (const nlohmann::json& r : j["regions"]) {
    if (r["label"] != label) continue;
    found = true;
    EXPECT_EQ(r["kind"], "principal");
    EXPECT_NEAR(r["resonance_speed_rpm"].get<double>(), rpm, 1e-6 * rpm);
    // The tongue is centred on the resonance (within its half-width at a ≤ 0.4 K̄).
    EXPECT_NEAR(r["centroid"]["x"].get<double>(), rpm, 0.03 * rpm);
  }
  EXPECT_TRUE(found) << j["regions"].dump(2);
}

}  // namespace
}  // namespace geardyn
