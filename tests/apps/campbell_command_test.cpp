// `geardyn campbell`: the command's files and report against independent truths — the mesh-order
// lines are Willis' kinematics in closed form (f_mesh = z_s z_r/(z_s + z_r) · n_sun/60 for a
// fixed ring), the zero-speed column is `geardyn modes`, a crossing lies on its excitation line
// and between the track's grid values, the CSV has one row per (speed, mode) — and bad input
// exits with 2 naming the flag.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::RunGeardyn;
using test::RunJson;

std::filesystem::path TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("geardyn_campbell_" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

// The flexible (f > 0) frequencies of a `modes` report and the Campbell tracks at the first speed,
// both ascending.
std::pair<std::vector<double>, std::vector<double>> ZeroSpeedTracksAndModes(
    const nlohmann::json& campbell, const nlohmann::json& modes) {
  std::vector<double> want;
  for (double f : modes["frequencies_hz"].get<std::vector<double>>()) {
    if (f > 0.0) want.push_back(f);
  }
  std::vector<double> got;
  for (const auto& t : campbell["tracks"]) got.push_back(t["frequency_hz"][0].get<double>());
  std::sort(got.begin(), got.end());
  return {got, want};
}

int CountLines(const std::filesystem::path& file) {
  std::ifstream in(file);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

TEST(CampbellCommand, PlanetaryDiagramHasWillisOrdersModesAtZeroAndConsistentCrossings) {
  const auto dir = TempDir("lin_parker");
  const auto run = RunGeardyn({"campbell", "builtin:planetary-lin-parker", "--speed", "0:30000:31",
                               "--out", dir.string(), "--json"});
  ASSERT_EQ(run.code, 0) << run.err;
  const nlohmann::json r = nlohmann::json::parse(run.out);
  EXPECT_EQ(r["status"], "success");
  EXPECT_EQ(r["sweep"]["body"], "sun");
  // Sun 25, ring 95, ring fixed: f_mesh per sun rpm = z_s z_r /(z_s + z_r) / 60.
  const double h_mesh = 25.0 * 95.0 / 120.0 / 60.0;
  bool found_mesh = false;
  for (const auto& e : r["excitations"]) {
    if (e["kind"] == "mesh" && e["order"] == 1) {
      EXPECT_NEAR(e["hz_per_rpm"].get<double>(), h_mesh, 1e-12 * h_mesh);
      found_mesh = true;
    }
  }
  EXPECT_TRUE(found_mesh);
  // One mesh frequency in the set: 3 mesh orders + shaft orders of sun, planets, carrier.
  EXPECT_EQ(r["excitations"].size(), 6u);
  // Zero speed = `geardyn modes` (its elastic modes; the rigid-body mode is deflated).
  const nlohmann::json modes = RunJson({"modes", "builtin:planetary-lin-parker", "--modes", "200"});
  const auto [got, want] = ZeroSpeedTracksAndModes(r, modes);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-7 * want[i]);
  EXPECT_EQ(r["num_rigid_body_modes"].get<int>(),
            static_cast<int>(modes["frequencies_hz"].size() - want.size()));
  // Crossings: on the excitation line, and between the track's neighbouring grid values.
  ASSERT_FALSE(r["crossings"].empty());
  const auto speeds = r["sweep"]["speeds_rpm"].get<std::vector<double>>();
  for (const auto& c : r["crossings"]) {
    const double s = c["speed_rpm"].get<double>();
    const double f = c["frequency_hz"].get<double>();
    double h = 0.0;
    for (const auto& e : r["excitations"]) {
      if (e["name"] == c["excitation"]) h = e["hz_per_rpm"].get<double>();
    }
    EXPECT_NEAR(f, h * s, 1e-9 * f);
    const auto track = r["tracks"][c["track"].get<std::size_t>()]["frequency_hz"];
    const auto i = static_cast<std::size_t>(std::upper_bound(speeds.begin(), speeds.end(), s) -
                                            speeds.begin());
    ASSERT_GE(i, 1u);
    ASSERT_LT(i, speeds.size());
    const double lo = std::min(track[i - 1].get<double>(), track[i].get<double>());
    const double hi = std::max(track[i - 1].get<double>(), track[i].get<double>());
    EXPECT_GE(f, lo * (1 - 1e-12));
    EXPECT_LE(f, hi * (1 + 1e-12));
  }
  // Files: CSV one row per (speed, mode) plus the header; SVG; crossings.csv.
  EXPECT_EQ(CountLines(dir / "campbell.csv"),
            1 + static_cast<int>(speeds.size() * r["tracks"].size()));
  EXPECT_EQ(CountLines(dir / "crossings.csv"), 1 + static_cast<int>(r["crossings"].size()));
  std::ifstream svg(dir / "campbell.svg");
  std::stringstream svg_text;
  svg_text << svg.rdbuf();
  EXPECT_NE(svg_text.str().find("<svg"), std::string::npos);
  EXPECT_EQ(svg_text.str().find("nan"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "campbell.json"));
}

TEST(CampbellCommand, LoadedStartsFromTheLoadedModes) {
  // --loaded: at zero speed the tracks are `modes --loaded` (a different solver path: the
  // Campbell's quadratic eigenproblem vs the symmetric one), with the rigid-body mode kept.
  const nlohmann::json r =
      RunJson({"campbell", "builtin:planetary-lin-parker", "--speed", "0:3000:3", "--loaded"});
  EXPECT_EQ(r["status"], "success");
  const nlohmann::json modes =
      RunJson({"modes", "builtin:planetary-lin-parker", "--modes", "200", "--loaded"});
  const auto [got, want] = ZeroSpeedTracksAndModes(r, modes);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-7 * want[i]);
  EXPECT_EQ(r["num_rigid_body_modes"].get<int>(), 1);
  bool noted = false;
  for (const auto& n : r["terms"]) {
    noted = noted || n.get<std::string>().find("mesh preload (--loaded)") != std::string::npos;
  }
  EXPECT_TRUE(noted) << r["terms"].dump();
}

TEST(CampbellCommand, CarrierSpeedSweepIsTheSameDiagramInCarrierRpm) {
  // Ring fixed: n_c = n_s z_s/(z_s + z_r) = 25/120 n_s.
  const nlohmann::json by_sun =
      RunJson({"campbell", "builtin:planetary-lin-parker", "--speed", "0:12000:3"});
  const nlohmann::json by_carrier =
      RunJson({"campbell", "builtin:planetary-lin-parker", "--carrier-speed", "0:2500:3"});
  EXPECT_EQ(by_carrier["sweep"]["body"], "carrier");
  ASSERT_EQ(by_sun["tracks"].size(), by_carrier["tracks"].size());
  for (std::size_t t = 0; t < by_sun["tracks"].size(); ++t) {
    for (std::size_t s = 0; s < 3; ++s) {
      const double a = by_sun["tracks"][t]["frequency_hz"][s].get<double>();
      const double b = by_carrier["tracks"][t]["frequency_hz"][s].get<double>();
      EXPECT_NEAR(a, b, 1e-9 * std::max(a, 1.0));
    }
  }
}

TEST(CampbellCommand, EveryBuiltinGearSceneRunsAtItsOperatingRange) {
  for (const std::string scene :
       {"builtin:helical-pair", "builtin:kahraman-blankenship-rig", "builtin:geared-shafts",
        "builtin:planetary-wind-turbine", "builtin:planetary-lin-parker"}) {
    const auto run = RunGeardyn({"campbell", scene, "--speed", "0:20000:5", "--json"});
    ASSERT_EQ(run.code, 0) << scene << "\n" << run.err;
    const nlohmann::json r = nlohmann::json::parse(run.out);
    EXPECT_EQ(r["status"], "success") << scene;
    EXPECT_FALSE(r["tracks"].empty()) << scene;
    EXPECT_EQ(run.out.find("nan"), std::string::npos) << scene;
  }
}

TEST(CampbellCommand, BadInputExitsWithTwoNamingTheFlag) {
  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {{"campbell", "builtin:helical-pair", "--carrier-speed", "0:1000:3"},
       {"--carrier-speed", "needs a planetary set"}},
      {{"campbell", "builtin:helical-pair"}, {"--speed, --carrier-speed", "exactly one"}},
      {{"campbell", "builtin:planetary-lin-parker", "--speed", "0:1000:3", "--carrier-speed",
        "0:100:3"},
       {"exactly one"}},
      {{"campbell", "builtin:helical-pair", "--speed", "0:1000"}, {"--speed", "lo:hi:n"}},
      {{"campbell", "builtin:helical-pair", "--speed", "0:1000:1"}, {"--speed", "n must be"}},
      {{"campbell", "builtin:helical-pair", "--speed", "100:10:5"}, {"--speed", "hi must be"}},
      {{"campbell", "builtin:helical-pair", "--speed", "-5:10:5"}, {"--speed", "lo must be"}},
      {{"campbell", "builtin:helical-pair", "--speed", "0:nan:5"}, {"--speed"}},
      {{"campbell", "builtin:helical-pair", "--speed", "0:10:5", "--orders", "0"}, {"--orders"}},
      {{"campbell", "builtin:kahraman-singh-oscillator", "--speed", "0:10:5"}, {"oscillator"}},
      {{"campbell", "builtin:planetary-lin-parker", "--speed", "0:10:5", "--set",
        "bearing.sun-support.stiffness=[1e8, 2e8, 1e8, 1e6, 1e6, 0]"},
       {"sun-support", "isotropic"}},
  };
  for (const Case& c : cases) {
    const auto run = RunGeardyn(c.args);
    EXPECT_EQ(run.code, 2) << c.args.back() << "\n" << run.err << run.out;
    for (const std::string& part : c.expected) {
      EXPECT_NE(run.err.find(part), std::string::npos) << "expected '" << part << "' in\n"
                                                       << run.err;
    }
  }
}

}  // namespace
}  // namespace geardyn::app
