// `geardyn hb` on a scene with a slice mesh: the nonlinear harmonic balance (contact loss). The
// Kahraman–Blankenship rig at 100 N·m has its primary-resonance up-sweep jump near 2686 Hz
// (H = 32, traced by the library), so a short trace across it must show an unstable branch and
// an up-sweep jump. Truths: Parseval (the RMS DTE is √(Σ a_k²/2) of the reported amplitudes),
// the geometry of a fold (an up-sweep jump is a local maximum of f_m along the trace, and the
// stability changes between neighbouring points within one continuation step of it), the static
// balance of the mean mesh force with the pinion torque over the base radius, the CSV shape, the
// dashed unstable branch in the SVG, and the error for --nonlinear without slices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "geardyn/cli.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;
using test::CliRun;
using test::RunGeardyn;
using test::RunJson;

// ~50 points (the continuation steps ~0.5 Hz along the unstable branch until it is half the
// range below lo); about 6 s in Debug.
constexpr double kLoHz = 2680.0, kHiHz = 2700.0;
constexpr int kResolution = 2;

std::vector<std::string> SliceRig(std::vector<std::string> head) {
  const std::vector<std::string> sets = {"--set", "mesh.pinion-wheel.model=\"slices\"",
                                         "--set", "mesh.pinion-wheel.slices=10",
                                         "--set", "mesh.pinion-wheel.center_distance=0.1502",
                                         "--set", "mesh.pinion-wheel.damping_ratio=0.05"};
  std::vector<std::string> args = {"hb", "builtin:kahraman-blankenship-rig"};
  args.insert(args.end(), head.begin(), head.end());
  args.insert(args.end(), sets.begin(), sets.end());
  return args;
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

bool AllNumbers(const json& v) {
  if (v.is_array()) {
    for (const json& e : v) {
      if (!e.is_number()) return false;
    }
    return true;
  }
  return v.is_number() && std::isfinite(v.get<double>());
}

// RMS² of DTE − mean from the one-sided amplitudes a_k = 2|Y_k|, k ≥ 1: Σ a_k²/2 (Parseval).
double ParsevalRms(const json& amplitudes) {
  double sum = 0.0;
  for (std::size_t k = 1; k < amplitudes.size(); ++k) {
    const double a = amplitudes[k].get<double>();
    sum += 0.5 * a * a;
  }
  return std::sqrt(sum);
}

void ExpectFinitePoint(const json& p) {
  EXPECT_TRUE(AllNumbers(p["mesh_frequency_hz"]));
  EXPECT_TRUE(AllNumbers(p["max_multiplier"]));
  EXPECT_TRUE(AllNumbers(p["error_estimate"]));
  for (const json& m : p["meshes"]) {
    for (const char* key :
         {"rms_dte_m", "peak_to_peak_dte_m", "mean_dte_m", "dte_amplitudes_m", "mean_force_n",
          "rms_force_n", "min_force_n", "max_force_n", "contact_loss_fraction"}) {
      EXPECT_TRUE(AllNumbers(m[key])) << key << " at " << p["mesh_frequency_hz"];
    }
  }
  for (const json& e : p["elements"]) {
    EXPECT_TRUE(AllNumbers(e["mean_force"]) && AllNumbers(e["rms_force"])) << e["name"];
  }
}

TEST(HbNonlinearCommandTest, TraceAcrossThePrimaryResonanceFoldShowsTheJump) {
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "hb_nonlinear_command_test";
  std::filesystem::remove_all(dir);
  const std::string range =
      std::to_string(kLoHz) + ":" + std::to_string(kHiHz) + ":" + std::to_string(kResolution);
  const CliRun run = RunGeardyn(SliceRig({"--mesh-frequency", range, "--harmonics", "16",
                                          "--progress", "--json", "--out", dir.string()}));
  ASSERT_EQ(run.code, kExitOk) << run.err;
  EXPECT_NE(run.err.find("geardyn hb: "), std::string::npos) << run.err;  // --progress
  const json report = json::parse(run.out);
  EXPECT_EQ(report["mode"], "nonlinear");
  EXPECT_EQ(report["harmonics"], 16);
  const json& points = report["points"];
  ASSERT_GE(points.size(), static_cast<std::size_t>(kResolution));
  // The sweep starts at the requested start exactly; it ends at the requested end exactly
  // unless the branch turns back at the fold inside the range and leaves it below the start
  // (as here: after the up-sweep fold the upper branch runs down in frequency), which a
  // warning says (issue 13).
  EXPECT_EQ(points.front()["mesh_frequency_hz"].get<double>(), kLoHz);
  bool turned_back = false;
  for (const json& w : report["warnings"]) {
    turned_back = turned_back || w.get<std::string>().find("turned back") != std::string::npos;
  }
  EXPECT_TRUE(turned_back || points.back()["mesh_frequency_hz"].get<double>() == kHiHz);
  // Every fold located to the default fold tolerance (1e-8 relative, below --tolerance 1e-4).
  ASSERT_EQ(report["fold_errors_hz"].size(), report["folds_hz"].size());
  for (std::size_t k = 0; k < report["folds_hz"].size(); ++k) {
    EXPECT_LE(report["fold_errors_hz"][k].get<double>(),
              1e-8 * report["folds_hz"][k].get<double>());
  }

  int unstable = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const json& p = points[i];
    ExpectFinitePoint(p);
    if (i > 0) {
      EXPECT_GE(p["branch"].get<int>(), points[i - 1]["branch"].get<int>());
    }
    if (!p["stable"].get<bool>()) ++unstable;
    const json& m = p["meshes"][0];
    ASSERT_EQ(m["dte_amplitudes_m"].size(), 17u);  // |mean| and harmonics 1 … 16
    EXPECT_NEAR(m["rms_dte_m"].get<double>(), ParsevalRms(m["dte_amplitudes_m"]),
                1e-8 * m["rms_dte_m"].get<double>());
    EXPECT_NEAR(std::abs(m["mean_dte_m"].get<double>()), m["dte_amplitudes_m"][0].get<double>(),
                1e-12);
  }
  EXPECT_GE(unstable, 1);

  // Every jump sits at a fold; the branch id increments there. An up-sweep jump is a local
  // maximum of f_m along the trace (both neighbours at most at f_jump), and the stability
  // flips between neighbouring points within one step (≤ range/n in f_m) of the fold, at most
  // 5 points away (near the fold |μ| ≈ 1 and the verdict settles a few points later).
  // [2680, 2700] Hz holds exactly one fold of the rig's curve, the primary resonance's up-sweep
  // jump (the down-sweep fold lies near 1 942 Hz, the super-harmonic ones below 1 500 Hz; pinned
  // against a time-integration sweep in analyses/system_nhb/kb_rig_jumps_test).
  ASSERT_EQ(report["jumps"].size(), 1u);
  EXPECT_EQ(report["jumps"][0]["direction"], "up");
  const double step_hz = (kHiHz - kLoHz) / kResolution;
  const json& folds = report["folds_hz"];
  for (const json& jump : report["jumps"]) {
    const double f = jump["mesh_frequency_hz"].get<double>();
    EXPECT_GE(f, kLoHz);
    EXPECT_LE(f, kHiHz);
    std::size_t fold = folds.size();
    for (std::size_t k = 0; k < folds.size(); ++k) {
      if (folds[k].get<double>() == f) fold = k;
    }
    ASSERT_LT(fold, folds.size()) << "jump at " << f << " Hz is not a fold";
    std::size_t first = 0;  // the first point after the fold: branch id fold + 1
    while (first < points.size() &&
           points[first]["branch"].get<int>() < static_cast<int>(fold) + 1) {
      ++first;
    }
    ASSERT_TRUE(first > 0 && first < points.size());
    const double before = points[first - 1]["mesh_frequency_hz"].get<double>();
    const double after = points[first]["mesh_frequency_hz"].get<double>();
    if (jump["direction"] == "up") {
      EXPECT_GE(f, std::max(before, after) - 1e-5 * f);
    } else {
      EXPECT_LE(f, std::min(before, after) + 1e-5 * f);
    }
    bool flips = false;
    for (std::size_t i = first > 5 ? first - 5 : 1; i < std::min(points.size(), first + 6); ++i) {
      const bool a = points[i - 1]["stable"].get<bool>(), b = points[i]["stable"].get<bool>();
      const double fa = points[i - 1]["mesh_frequency_hz"].get<double>();
      const double fb = points[i]["mesh_frequency_hz"].get<double>();
      if (a != b && std::abs(fa - f) <= step_hz && std::abs(fb - f) <= step_hz) flips = true;
    }
    EXPECT_TRUE(flips) << "no stability change next to the " << jump["direction"] << " jump at "
                       << f << " Hz";
  }

  // CSV: a header with units and one row per traced point.
  std::istringstream csv(ReadFile(dir / "nhb.csv"));
  std::vector<std::string> lines;
  for (std::string line; std::getline(csv, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), points.size() + 1);
  EXPECT_EQ(lines[0].rfind("mesh_frequency_hz,branch,stable,max_multiplier", 0), 0u);
  EXPECT_NE(lines[0].find("pinion-wheel:rms_dte_m"), std::string::npos);
  EXPECT_NE(lines[0].find("pinion-wheel:max_force_n"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "nhb.json"));
  // SVG: the unstable branch dashed, the jump marked.
  const std::string svg = ReadFile(dir / "nhb_rms_dte.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("<circle"), std::string::npos);
}

// The up-sweep fold of the first super-harmonic hysteresis loop (1475 Hz) jumps into a band
// (≈ 1476–1501 Hz) where the upper branch is unstable (a secondary instability, checked against
// a GSL variational integration over 1440–1480 Hz in session 22): no stable T-periodic landing
// exists. The JSON says so with a null landing RMS, and the text must say it in words instead
// of printing "nan" (a NaN may never reach an output).
TEST(HbNonlinearCommandTest, JumpWithoutAStableLandingBranchIsSaidInWords) {
  const CliRun text = RunGeardyn(SliceRig({"--mesh-frequency", "1440:1520:20"}));
  ASSERT_EQ(text.code, kExitOk) << text.err;
  EXPECT_EQ(text.out.find("nan"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("inf"), std::string::npos) << text.out;
  const CliRun run = RunGeardyn(SliceRig({"--mesh-frequency", "1440:1520:20", "--json"}));
  ASSERT_EQ(run.code, kExitOk) << run.err;
  const json report = json::parse(run.out);
  ASSERT_EQ(report["jumps"].size(), 1u);
  const json& jump = report["jumps"][0];
  EXPECT_EQ(jump["direction"], "up");
  EXPECT_NEAR(jump["mesh_frequency_hz"].get<double>(), 1475.13, 0.05);
  EXPECT_TRUE(jump["rms_dte_after_m"].is_null());
  EXPECT_NE(text.out.find("no stable periodic response traced at this frequency"),
            std::string::npos)
      << text.out;
}

// One frequency well below the resonance: one periodic solution. Its mean mesh force balances
// the pinion torque (100 N·m) over the pinion base radius (damping forces have zero mean in a
// periodic state), with the base radius from `geardyn info`.
TEST(HbNonlinearCommandTest, SingleFrequencyMeanForceBalancesTheTorque) {
  const json report =
      RunJson(SliceRig({"--mesh-frequency", "1000", "--harmonics", "8", "--nonlinear"}));
  EXPECT_EQ(report["mode"], "nonlinear");
  ASSERT_EQ(report["points"].size(), 1u);
  const json& m = report["points"][0]["meshes"][0];
  EXPECT_NEAR(m["rms_dte_m"].get<double>(), ParsevalRms(m["dte_amplitudes_m"]),
              1e-8 * m["rms_dte_m"].get<double>());
  const json info = RunJson({"info", "builtin:kahraman-blankenship-rig"});
  const double base_radius = info["meshes"][0]["base_radius_pinion"].get<double>();
  EXPECT_NEAR(m["mean_force_n"].get<double>(), 100.0 / base_radius, 1e-3 * 100.0 / base_radius);
}

// --stability none skips the Floquet pass: no point may carry a verdict it never computed (the
// struct's default used to print every point as "stable").
TEST(HbNonlinearCommandTest, StabilityNonePrintsNoVerdict) {
  const json report = RunJson(
      SliceRig({"--mesh-frequency", "1440:1480:20", "--harmonics", "8", "--stability", "none"}));
  EXPECT_EQ(report["stability"], "none");
  ASSERT_FALSE(report["points"].empty());
  for (const json& p : report["points"]) {
    EXPECT_TRUE(p["stable"].is_null()) << p["mesh_frequency_hz"];
    EXPECT_EQ(p["verdict"], "not computed") << p["mesh_frequency_hz"];
    EXPECT_TRUE(p["max_multiplier"].is_null()) << p["mesh_frequency_hz"];
  }
}

// A runout makes the period the hunting period, P = lcm(50, 50) = 50 mesh cycles on the rig, and
// H counts harmonics of f_mesh/P: the default H = 24 has no mesh harmonic at all. It returned the
// runout alone (a1 = 5 µm, RMS 3.54 µm = 5/√2 µm, no contact loss) with status success; it must
// be refused before any solve, naming the period (closed form: lcm of the tooth counts).
TEST(HbNonlinearCommandTest, ToothErrorsNeedHarmonicsReachingTheMeshFrequency) {
  for (const std::vector<std::string>& head :
       {std::vector<std::string>{"--mesh-frequency", "1800"},
        std::vector<std::string>{"--mesh-frequency", "1800", "--harmonics", "49"},
        std::vector<std::string>{"--mesh-frequency", "1800:1900:4", "--tolerance", "1e-3"}}) {
    std::vector<std::string> args = SliceRig(head);
    args.insert(args.end(), {"--set", "mesh.pinion-wheel.errors.gear_runout=5e-6"});
    const CliRun run = RunGeardyn(args);
    EXPECT_EQ(run.code, kExitBadInput) << run.out;
    EXPECT_NE(run.err.find("harmonics of f_mesh/50"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("does not contain the mesh frequency (harmonic 50)"), std::string::npos)
        << run.err;
  }
}

// A point whose Newton solve fails gets no monodromy: its max|μ| is unknown, not 0 (a computed
// monodromy has det Φ = exp(−∫tr M⁻¹C dt) > 0 by Liouville, so max|μ| > 0). The rig with a
// runout at H = P = 50 (one mesh order) does not converge at 1800 Hz and printed max|μ| 0.000000
// beside "undetermined".
TEST(HbNonlinearCommandTest, FailedPointCarriesNoMultiplier) {
  std::vector<std::string> args = SliceRig({"--mesh-frequency", "1800", "--harmonics", "50"});
  args.insert(args.end(), {"--set", "mesh.pinion-wheel.errors.gear_runout=5e-6", "--json"});
  const CliRun run = RunGeardyn(args);
  const json report = json::parse(run.out);
  ASSERT_EQ(report["points"].size(), 1u);
  const json& p = report["points"][0];
  if (p["status"] == "success") GTEST_SKIP() << "the point converged; nothing to check";
  EXPECT_EQ(run.code, kExitNumericalIssue);
  EXPECT_EQ(p["verdict"], "undetermined");
  EXPECT_TRUE(p["stable"].is_null());
  EXPECT_TRUE(p["max_multiplier"].is_null()) << p["max_multiplier"];
}

TEST(HbNonlinearCommandTest, SliceRigMonodromyIsExactWhateverTheSteps) {
  // The trace over the super-harmonic fold (≈ 1 475 Hz) returns along the unstable branch
  // (|μ| up to ≈ 3). The spur slice law is integrated exactly (its projected form): ∂g/∂u is
  // piecewise constant between the located contact switches and the stiffness steps, so the
  // monodromy is an exact product of matrix exponentials and --monodromy-steps cannot change
  // it (an invariant of the exact product; the multipliers themselves are checked against a
  // GSL variational-equation monodromy in tests/analyses/system_nhb/
  // monodromy_reference_test.cpp).
  auto multipliers = [](const std::string& steps) {
    const json report = RunJson(SliceRig(
        {"--mesh-frequency", "1440:1480:20", "--harmonics", "8", "--monodromy-steps", steps}));
    std::vector<double> mu;
    for (const json& p : report["points"]) mu.push_back(p["max_multiplier"].get<double>());
    return mu;
  };
  const std::vector<double> coarse = multipliers("32"), finest = multipliers("512");
  ASSERT_EQ(coarse.size(), finest.size());
  ASSERT_FALSE(finest.empty());
  EXPECT_GT(*std::max_element(finest.begin(), finest.end()), 1.5);
  for (std::size_t i = 0; i < finest.size(); ++i) {
    EXPECT_NEAR(coarse[i], finest[i], 1e-12 * finest[i]) << "point " << i;
  }
  const CliRun run = RunGeardyn(SliceRig({"--mesh-frequency", "1700", "--monodromy-steps", "-1"}));
  EXPECT_EQ(run.code, kExitBadInput);
  EXPECT_NE(run.err.find("--monodromy-steps"), std::string::npos) << run.err;
}

TEST(HbNonlinearCommandTest, NonlinearWithoutSliceMeshIsAnError) {
  const CliRun run = RunGeardyn(
      {"hb", "builtin:kahraman-blankenship-rig", "--nonlinear", "--mesh-frequency", "1000"});
  EXPECT_EQ(run.code, kExitBadInput);
  EXPECT_NE(run.err.find("--nonlinear"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("mesh.pinion-wheel.model=\"slices\""), std::string::npos) << run.err;
}

TEST(HbNonlinearCommandTest, LinearFlagKeepsTheLinearReport) {
  const json report =
      RunJson(SliceRig({"--mesh-frequency", "1000:2000:3", "--harmonics", "4", "--linear"}));
  EXPECT_EQ(report["mode"], "linear");
  ASSERT_EQ(report["points"].size(), 3u);
  EXPECT_EQ(report["points"][0]["method"].is_string(), true);
}

}  // namespace
}  // namespace geardyn::app

namespace geardyn::app {
namespace {

// Issue 13: the stiff-bearing spur pair with backlash (spur_backlash_sweep_test's scene) has a
// detached stable branch above the lower branch's fold (≈ 2 917 Hz) that continuation from the
// start of 2 800–3 100 Hz cannot reach. Truth: the single-frequency solve at 3 000 Hz (Newton
// from the contact guess, no continuation) lands on it; with the default branch search the
// sweep holds a stable point on a separate segment with that RMS, without it no point does.
TEST(HbNonlinearCommandTest, BranchSearchAddsTheDetachedBranchAsASegment) {
  const std::vector<std::string> spur = {
      "--harmonics", "16",
      "--set",       "planar=true",
      "--set",       "mesh.pinion-wheel.model=\"slices\"",
      "--set",       "mesh.pinion-wheel.slices=10",
      "--set",       "mesh.pinion-wheel.center_distance=0.15001",
      "--set",       "mesh.pinion-wheel.damping_ratio=0.05",
      "--set",       "bearing.pinion-support.stiffness=[3e11,3e11,1e9,1e8,1e8,0.0]",
      "--set",       "bearing.wheel-support.stiffness=[3e11,3e11,1e9,1e8,1e8,0.0]"};
  auto args = [&](std::vector<std::string> head) {
    std::vector<std::string> a = {"hb", "builtin:kahraman-blankenship-rig"};
    a.insert(a.end(), head.begin(), head.end());
    a.insert(a.end(), spur.begin(), spur.end());
    return a;
  };
  const json single = RunJson(args({"--mesh-frequency", "3000"}));
  ASSERT_EQ(single["points"].size(), 1u);
  const double detached = single["points"][0]["meshes"][0]["rms_dte_m"].get<double>();
  // Stable points within 5 Hz of 3 000 Hz whose RMS is the detached branch's (1e-2: the
  // continuation's points are not exactly at 3 000 Hz), and their segments.
  auto near_detached = [&](const json& report) {
    std::vector<int> segments;
    for (const json& p : report["points"]) {
      if (std::abs(p["mesh_frequency_hz"].get<double>() - 3000.0) > 5.0) continue;
      if (p["verdict"] != "stable") continue;
      const double rms = p["meshes"][0]["rms_dte_m"].get<double>();
      if (std::abs(rms - detached) < 1e-2 * detached) segments.push_back(p["segment"].get<int>());
    }
    return segments;
  };
  const json with = RunJson(args({"--mesh-frequency", "2800:3100:30"}));
  EXPECT_EQ(with["status"], "success");
  const std::vector<int> found = near_detached(with);
  ASSERT_FALSE(found.empty()) << "the detached branch (" << detached << " m) is not in the sweep";
  for (int s : found) EXPECT_GE(s, 1);
  const json without = RunJson(args({"--mesh-frequency", "2800:3100:30", "--branch-search", "0"}));
  EXPECT_TRUE(near_detached(without).empty());
}

}  // namespace
}  // namespace geardyn::app
