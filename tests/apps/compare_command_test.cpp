// `geardyn compare`: level differences that theory fixes, and one two-level comparison checked
// against separate calls of the existing commands (issue 15):
// * spur pair (β = 0, h ≡ 0): the 4-DOF coupling drops only the μ b² twist term, which loads the
//   tilt about the plane-of-action normal; the torsional/transverse block is the same operator, so
//   its modes and the DTE agree to round-off (spec 01 §6 spur limit);
// * LTI = the mean of the LTV model: modes (of the mean operator) identical;
// * a level compared with itself: MAC = 1 and Δf = 0;
// * compare's numbers equal `geardyn modes` / `hb --linear` / `floquet` run per level, and its
//   differences are those of the separate outputs;
// * bad input: exit code 2 with the option and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/cli.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;
using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

// Round-off of two dense solves / LU sweeps of the same operator, relative.
constexpr double kSameOperatorTol = 1e-9;
// The JSON carries 17 significant digits: the same computation agrees to round-off.
constexpr double kSamePathTol = 1e-12;

const json& Level(const json& report, const std::string& name) {
  for (const json& l : report["levels"]) {
    if (l["level"] == name) return l;
  }
  ADD_FAILURE() << "no level " << name;
  static const json none;
  return none;
}

TEST(CompareCommandTest, SpurFourDofEqualsSixDofInThePlaneOfTheGears) {
  const json r = RunJson({"compare", "builtin:kahraman-blankenship-rig", "--levels",
                          "blankenship_singh,coupling_4dof", "--analyses", "modes,hb",
                          "--mesh-frequency", "1000:6000:11"});
  EXPECT_EQ(r["references"]["modes"], "blankenship_singh");
  const json& c = Level(r, "coupling_4dof")["comparison"];
  int in_plane = 0;
  for (const json& m : c["modes"]) {
    const std::string type = m.value("type", "");
    if (type == "rotational" || type == "translational" || type == "rigid_body") {
      ++in_plane;
      ASSERT_FALSE(m["mode"].is_null()) << "in-plane mode " << m["reference_mode"] << " absent";
      EXPECT_NEAR(m["relative_difference"].get<double>(), 0.0, kSameOperatorTol)
          << "mode " << m["reference_mode"];
      EXPECT_NEAR(m["mac"].get<double>(), 1.0, kSameOperatorTol);
    }
  }
  EXPECT_GE(in_plane, 4);
  // The rig's tilt modes are near-repeated (identical gears on identical bearings) and held by
  // the 1e8 N·m/rad bearings: compared as a subspace they are all found.
  EXPECT_TRUE(c["absent"].empty()) << c["absent"];
  // The DTE is an in-plane quantity: identical.
  EXPECT_LT(c["dte"]["max_abs"].get<double>(), kSameOperatorTol);
  EXPECT_EQ(c["verdict"]["dte"], "agrees");
}

TEST(CompareCommandTest, LtiModesAreTheModesOfTheLtvMean) {
  const json r = RunJson({"compare", "builtin:helical-pair", "--levels", "blankenship_singh,lti",
                          "--analyses", "modes"});
  const json& c = Level(r, "lti")["comparison"];
  EXPECT_EQ(c["verdict"]["modes"], "agrees");
  for (const json& m : c["modes"]) {
    ASSERT_FALSE(m["mode"].is_null());
    EXPECT_NEAR(m["relative_difference"].get<double>(), 0.0, kSameOperatorTol);
    EXPECT_NEAR(m["mac"].get<double>(), 1.0, kSameOperatorTol);
  }
}

TEST(CompareCommandTest, ALevelComparedWithItselfHasMacOne) {
  const json r = RunJson({"compare", "builtin:helical-pair", "--levels",
                          "blankenship_singh,torsional", "--analyses", "modes"});
  const json& c = Level(r, "blankenship_singh")["comparison"];
  EXPECT_EQ(c["verdict"]["modes"], "reference");
  ASSERT_EQ(c["modes"].size(), 12u);
  for (const json& m : c["modes"]) {
    EXPECT_EQ(m["mode"], m["reference_mode"]);
    EXPECT_NEAR(m["mac"].get<double>(), 1.0, kSamePathTol);
    EXPECT_EQ(m["relative_difference"].get<double>(), 0.0);
  }
}

TEST(CompareCommandTest, TwoLevelsEqualSeparateCallsOfTheCommands) {
  const std::vector<std::string> levels = {"blankenship_singh", "coupling_4dof"};
  const std::string grid = "1500:4500:7";
  const json r =
      RunJson({"compare", "builtin:helical-pair", "--levels", levels[0] + "," + levels[1],
               "--analyses", "modes,floquet,hb", "--mesh-frequency", grid});
  std::vector<std::vector<double>> rms;
  for (const std::string& level : levels) {
    const std::string set = "mesh.pinion-wheel.model=" + level;
    const json& l = Level(r, level);
    // modes
    const json modes = RunJson({"modes", "builtin:helical-pair", "--set", set, "--modes", "12"});
    const auto f_cli = modes["frequencies_hz"].get<std::vector<double>>();
    const auto f_cmp = l["modes"]["frequencies_hz"].get<std::vector<double>>();
    ASSERT_GE(f_cmp.size(), f_cli.size());
    for (std::size_t k = 0; k < f_cli.size(); ++k) {
      EXPECT_NEAR(f_cmp[k], f_cli[k], kSamePathTol * f_cli.back()) << level << " mode " << k;
    }
    // Floquet (compare asks for 1e-8, floquet's default is 1e-10)
    const json floquet = RunJson({"floquet", "builtin:helical-pair", "--set", set});
    EXPECT_NEAR(l["floquet"]["max_abs_multiplier"].get<double>(),
                floquet["max_abs_multiplier"].get<double>(), 1e-7);
    EXPECT_EQ(l["floquet"]["verdict"], floquet["verdict"]);
    // DTE: no modification or error here, so δ_η is the DTE of `geardyn hb`.
    const json hb = RunJson({"hb", "builtin:helical-pair", "--set", set, "--linear", "--stability",
                             "none", "--mesh-frequency", grid});
    std::vector<double> level_rms;
    for (std::size_t k = 0; k < hb["points"].size(); ++k) {
      const double expected = hb["points"][k]["meshes"][0]["rms_dte_m"].get<double>();
      EXPECT_NEAR(l["dte"]["rms_up_m"][k].get<double>(), expected, kSamePathTol * expected);
      level_rms.push_back(expected);
    }
    rms.push_back(level_rms);
  }
  // The difference compare reports, from the separate outputs.
  double peak = 0.0;
  for (const double v : rms[0]) peak = std::max(peak, v);
  const json& d = Level(r, levels[1])["comparison"]["dte"];
  double max_abs = 0.0;
  for (std::size_t k = 0; k < rms[0].size(); ++k) {
    const double expected = (rms[1][k] - rms[0][k]) / peak;
    EXPECT_NEAR(d["difference_up"][k].get<double>(), expected, 1e-12);
    max_abs = std::max(max_abs, std::abs(expected));
  }
  EXPECT_NEAR(d["max_abs"].get<double>(), max_abs, 1e-12);
  EXPECT_GT(max_abs, 0.0);  // the helical 4-DOF form is not the 6-DOF one
}

TEST(CompareCommandTest, KahramanSinghOscillatorLevelsAgreeWhereTheTheorySaysSo) {
  // x'' + 2ζx' + g(x) = F_m + F_a cos Ωt with α = 0: the LTV (torsional) and LTI levels are the
  // same equation, and while the teeth stay in contact their alternating response is the linear
  // FRF F_a/|1 − r² + 2iζr| (RMS /√2) with r = Ω/ω_n = the grid value (the model is scaled to a
  // 1 Hz natural frequency). At r = 0.3 the amplitude (0.02) stays far below the mean deflection
  // F_m = 0.1, so the clearance level loses no contact and agrees too. (From r = 0.4 to 0.6 it
  // differs by up to 3e-3 relative, around the superharmonic Ω = ω_n/2, without contact loss:
  // not explained yet, see docs/design.md.)
  const double zeta = 0.05, fa = 0.02;
  const json r = RunJson({"compare", "builtin:kahraman-singh-oscillator", "--levels",
                          "slices,torsional,lti", "--analyses", "modes,hb", "--mesh-frequency",
                          "0.3:1.6:14", "--harmonics", "16", "--branch-search", "0"});
  EXPECT_EQ(r["references"]["dte"], "slices");
  const auto grid = r["frequencies_hz"].get<std::vector<double>>();
  const json& torsional = Level(r, "torsional");
  const json& lti = Level(r, "lti");
  const json& slices = Level(r, "slices");
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const double ratio = grid[k];
    const double closed = fa / std::sqrt(2.0) / std::hypot(1.0 - ratio * ratio, 2.0 * zeta * ratio);
    EXPECT_NEAR(torsional["dte"]["rms_up_m"][k].get<double>(), closed, 1e-9 * closed) << ratio;
    EXPECT_NEAR(lti["dte"]["rms_up_m"][k].get<double>(), closed, 1e-9 * closed) << ratio;
    if (ratio < 0.35) {
      EXPECT_NEAR(slices["dte"]["rms_up_m"][k].get<double>(), closed, 1e-6 * closed) << ratio;
    }
  }
  // One mode at the 1 Hz natural frequency in every level, matched with MAC 1.
  for (const json* l : {&torsional, &lti}) {
    const json& m = (*l)["comparison"]["modes"][0];
    EXPECT_NEAR(m["hz"].get<double>(), 1.0, 1e-12);
    EXPECT_NEAR(m["mac"].get<double>(), 1.0, 1e-12);
  }
  // Near the resonance the clearance opens: the linear levels differ from it there.
  EXPECT_EQ(torsional["comparison"]["verdict"]["dte"], "differs");
}

TEST(CompareCommandTest, ChartsOfTheLtiLevelHaveNoParametricInstability) {
  // An LTI system cannot be parametrically unstable: with damping every point of its chart is
  // stable, while the LTV level of the same pair has the principal tongue of its mesh mode (the
  // stiffness variation is raised to make it wide). Each level's chart equals `geardyn
  // stability-chart` of the scene at that level.
  const std::vector<std::string> sets = {
      "--set", "mesh.pinion-wheel.parameters={form=\"fourier\", stiffness=[4e8, 1.2e8, 0]}",
      "--set", "mesh.pinion-wheel.damping_ratio=0.01"};
  std::vector<std::string> args = {"compare",    "builtin:helical-pair",
                                   "--levels",   "blankenship_singh,lti",
                                   "--analyses", "floquet",
                                   "--chart-x",  "operating_point.speed_rpm=5000:40000:15",
                                   "--chart-y",  "mesh.pinion-wheel.damping_ratio=0.005:0.02:2"};
  args.insert(args.end(), sets.begin(), sets.end());
  const json r = RunJson(args);
  const json& lti = Level(r, "lti");
  const json& bs = Level(r, "blankenship_singh");
  ASSERT_TRUE(lti.contains("chart"));
  EXPECT_EQ(lti["chart"]["unstable_points"], 0);
  EXPECT_EQ(lti["chart"]["undetermined_points"], 0);
  EXPECT_GT(bs["chart"]["unstable_points"].get<int>(), 0);
  // The agreement is the share of B–S's points that are stable too.
  const double points = bs["chart"]["grid_points"].get<double>();
  EXPECT_NEAR(lti["comparison"]["chart_agreement"].get<double>(),
              1.0 - bs["chart"]["unstable_points"].get<double>() / points, 1e-12);
  // Against the chart command at the B–S level.
  std::vector<std::string> chart = {"stability-chart",
                                    "builtin:helical-pair",
                                    "--x",
                                    "operating_point.speed_rpm=5000:40000:15",
                                    "--y",
                                    "mesh.pinion-wheel.damping_ratio=0.005:0.02:2",
                                    "--set",
                                    "mesh.pinion-wheel.model=blankenship_singh"};
  chart.insert(chart.end(), sets.begin(), sets.end());
  const json c = RunJson(chart);
  EXPECT_EQ(bs["chart"]["unstable_points"], c["num_unstable_points"]);
  EXPECT_EQ(bs["chart"]["grid_points"], c["num_points"]);
}

TEST(CompareCommandTest, DefaultLevelsSkipWhatTheSceneCannotBuildWithTheReason) {
  // User K tables: no contact lines, so no slices (skipped, not an error, by default).
  const CliRun run = RunGeardyn(
      {"compare", "builtin:helical-pair", "--analyses", "modes", "--set",
       "mesh.pinion-wheel.parameters={form=\"fourier\", stiffness=[4e8, 0, 0]}", "--json"});
  ASSERT_EQ(run.code, kExitOk) << run.err;
  const json r = json::parse(run.out);
  const json& slices = Level(r, "slices");
  ASSERT_TRUE(slices["skipped"].contains("modes"));
  EXPECT_NE(slices["skipped"]["modes"].get<std::string>().find("cannot be built"),
            std::string::npos);
  EXPECT_EQ(slices["comparison"]["verdict"]["modes"], "skipped");
  EXPECT_EQ(r["references"]["modes"], "blankenship_singh");
}

TEST(CompareCommandTest, BadInputIsExitCodeTwoWithTheReason) {
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"--levels", "sdof"}, "--levels: unknown level 'sdof'"},
      {{"--levels", "lti,lti"}, "listed twice"},
      {{"--levels", ""}, "--levels"},
      {{"--analyses", "modes,fft"}, "--analyses: unknown analysis 'fft'"},
      {{"--analyses", "hb,hb"}, "listed twice"},
      {{"--levels", "slices", "--set",
        "mesh.pinion-wheel.parameters={form=\"fourier\", stiffness=[4e8, 0, 0]}"},
       "cannot be built at level 'slices'"},
      {{"--levels", "contact"}, "needs --analyses simulate"},
      {{"--reference", "torsional", "--levels", "lti,blankenship_singh"},
       "--reference: 'torsional' is not one of the compared --levels"},
      {{"--reference", "nonsense"}, "--reference: unknown level"},
      {{"--mesh", "nope"}, "--mesh: the scene has no mesh 'nope'"},
      {{"--mesh-frequency", "3000:1000:5"}, "--mesh-frequency"},
      {{"--modes", "0"}, "--modes"},
      {{"--mac-threshold", "1.5"}, "--mac-threshold"},
      {{"--frequency-tolerance", "-1"}, "--frequency-tolerance"},
      {{"--dte-tolerance", "nan"}, "--dte-tolerance"},
      {{"--vary", "gear.pinion.teeth"}, "--vary: expected KEY=lo:hi:n"},
      {{"--vary", "gear.pinion.teeth=20:30"}, "--vary: the range must be lo:hi:n"},
      {{"--vary", "gear.pinion.teeth=20:30:1000"}, "--vary: n must be in"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"compare", "builtin:helical-pair"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliRun run = RunGeardyn(args);
    std::string joined;
    for (const std::string& a : c.args) joined += a + " ";
    EXPECT_EQ(run.code, kExitBadInput) << joined << "\n" << run.err;
    EXPECT_NE(run.err.find(c.message), std::string::npos)
        << joined << "\nexpected: " << c.message << "\ngot: " << run.err;
  }
}

}  // namespace
}  // namespace geardyn::app
