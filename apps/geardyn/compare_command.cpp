// `geardyn compare SCENE`: one scene at every requested model level of its meshes, the requested
// analyses at each level, and how far each level is from the reference (compare_runner.hpp);
// with --vary KEY=lo:hi:n the comparison over a scene parameter (e.g. the helix angle), with
// the errors of every level against it (compare_report.hpp).
#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "geardyn/analysis_runs.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/compare_report.hpp"
#include "geardyn/compare_runner.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

constexpr int kMaxVaryValues = 200;

struct CompareCommandOptions {
  SceneCommandOptions scene;
  CompareSettings settings;
  std::string levels;
  std::string analyses = "modes,floquet,hb";
  std::string vary;
  CLI::Option* levels_option = nullptr;
};

// "KEY[,KEY...]=lo:hi:n" → the keys and the values (n ≥ 1 evenly spaced, lo when n = 1).
std::pair<std::vector<std::string>, std::vector<double>> ParseVary(const std::string& text) {
  const auto eq = text.find('=');
  GEARDYN_THROW_UNLESS(eq != std::string::npos && eq > 0,
                       "--vary: expected KEY=lo:hi:n (e.g. gear.pinion.helix_angle_deg,"
                       "gear.wheel.helix_angle_deg=0:35:8), got '"
                           << text << "'");
  std::vector<std::string> keys;
  std::istringstream key_stream(text.substr(0, eq));
  for (std::string k; std::getline(key_stream, k, ',');) {
    GEARDYN_THROW_UNLESS(!k.empty(), "--vary: an empty key in '" << text << "'");
    keys.push_back(k);
  }
  const std::string range = text.substr(eq + 1);
  double lo = 0.0, hi = 0.0;
  int n = 0;
  char c1 = 0, c2 = 0;
  std::istringstream in(range);
  in >> lo >> c1 >> hi >> c2 >> n;
  std::string rest;
  in >> rest;
  GEARDYN_THROW_UNLESS(in.eof() && rest.empty() && c1 == ':' && c2 == ':',
                       "--vary: the range must be lo:hi:n, got '" << range << "'");
  GEARDYN_THROW_UNLESS(std::isfinite(lo) && std::isfinite(hi) && hi >= lo,
                       "--vary: needs finite lo <= hi, got '" << range << "'");
  GEARDYN_THROW_UNLESS(n >= 1 && n <= kMaxVaryValues,
                       "--vary: n must be in [1, " << kMaxVaryValues << "] (each value runs a "
                                                   << "whole comparison), got " << n);
  std::vector<double> values;
  for (int k = 0; k < n; ++k) values.push_back(n == 1 ? lo : lo + (hi - lo) * k / (n - 1));
  return {keys, values};
}

std::string FormatValue(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

int RunCompareCommand(CompareCommandOptions opts, std::ostream& out, std::ostream& err) {
  CompareSettings& settings = opts.settings;
  settings.levels_given = opts.levels_option != nullptr && opts.levels_option->count() > 0;
  if (settings.levels_given) settings.levels = ParseCompareLevels(opts.levels);
  settings.analyses = ParseCompareAnalyses(opts.analyses);
  settings.scene_path = opts.scene.scene;
  settings.overrides = opts.scene.overrides;
  ValidateCompareSettings(settings);
  const std::string& dir = opts.scene.out_dir;
  if (opts.vary.empty()) {
    const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
    const CompareRun run = RunCompareAnalysis(scene, settings, dir, &err);
    out << (opts.scene.json ? run.report.dump(2) + "\n" : run.text);
    if (!dir.empty() && !opts.scene.json) out << "written to " << dir << "\n";
    return run.exit_code;
  }
  const auto [keys, values] = ParseVary(opts.vary);
  std::string key_text;
  for (const std::string& k : keys) key_text += (key_text.empty() ? "" : ",") + k;
  std::vector<CompareVaryPoint> points;
  bool ok = true;
  for (const double value : values) {
    std::vector<std::string> overrides = opts.scene.overrides;
    for (const std::string& k : keys) overrides.push_back(k + "=" + FormatValue(value));
    if (settings.progress) err << "geardyn compare: " << key_text << " = " << value << "\n";
    const Scene scene = LoadScene(opts.scene.scene, overrides);
    settings.overrides = overrides;
    CompareVaryPoint p{value, RunCompare(scene, settings, &err)};
    ok = ok && p.result.ok;
    points.push_back(std::move(p));
  }
  const std::string json_text = MakeCompareVaryReport(key_text, points).dump(2) + "\n";
  out << (opts.scene.json ? json_text : FormatCompareVaryText(key_text, points));
  if (!dir.empty()) {
    WriteOutputFile(dir, "compare_vary.json", json_text);
    WriteOutputFile(dir, "compare_vary.csv", FormatCompareVaryCsv(key_text, points));
    WriteOutputFile(dir, "compare_vary.svg", RenderCompareVaryPlot(key_text, points));
    if (!opts.scene.json) out << "written to " << dir << "\n";
  }
  return ok ? int{kExitOk} : int{kExitNumericalIssue};
}

}  // namespace

CompareRun RunCompareAnalysis(const Scene& scene, const CompareSettings& settings,
                              const std::string& dir, std::ostream* progress) {
  ValidateCompareSettings(settings);
  const CompareResult result = RunCompare(scene, settings, progress);
  CompareRun run;
  run.report = MakeCompareReport(result);
  run.text = FormatCompareText(result);
  if (!dir.empty()) {
    WriteOutputFile(dir, "compare.json", run.report.dump(2) + "\n");
    WriteOutputFile(dir, "compare_levels.csv", FormatCompareLevelsCsv(result));
    WriteOutputFile(dir, "compare_modes.csv", FormatCompareModesCsv(result));
    if (std::any_of(result.runs.begin(), result.runs.end(),
                    [](const LevelRun& l) { return l.chart.has_value(); })) {
      WriteOutputFile(dir, "compare_chart.svg", RenderCompareChartPlot(result));
      WriteOutputFile(dir, "compare_chart.csv", FormatCompareChartCsv(result));
    }
    if (!result.frequencies_hz.empty()) {
      WriteOutputFile(dir, "compare_dte.csv", FormatCompareDteCsv(result));
      WriteOutputFile(dir, "compare_dte.svg", RenderCompareDtePlot(result));
    }
  }
  run.exit_code = result.ok ? int{kExitOk} : int{kExitNumericalIssue};
  return run;
}

Command AddCompareCommand(CLI::App& app) {
  auto opts = std::make_shared<CompareCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "one scene at several model levels (contact, slices, B–S 6-DOF, 5-DOF, 4-DOF, LTI, "
      "torsional) side by side: modes matched by MAC, Floquet verdicts, DTE curves, differences "
      "to the reference level");
  AddSceneOptions(cmd, &opts->scene);
  opts->levels_option =
      cmd->add_option("--levels", opts->levels,
                      "comma-separated levels: contact, slices, blankenship_singh, bs_projected, "
                      "five_dof, coupling_4dof, lti, torsional (default: all but contact; a listed "
                      "level the scene cannot build is an error, a default one is skipped with the "
                      "reason)");
  cmd->add_option("--analyses", opts->analyses,
                  "comma-separated: modes, floquet, hb, simulate (default modes,floquet,hb). The "
                  "DTE of a level comes from its harmonic balance with hb, else from the time "
                  "domain with simulate (the contact level needs simulate)");
  cmd->add_option("--reference", opts->settings.reference,
                  "the reference level (default: the most detailed level that ran each analysis)");
  cmd->add_option("--mesh", opts->settings.mesh, "the compared mesh (default: the first)");
  cmd->add_option("--mesh-frequency", opts->settings.mesh_frequency,
                  "DTE grid [Hz] lo:hi:n or one value (default 0.2 to 2.5 times the scene's, 60 "
                  "points); nonlinear levels trace the range with resolution n and are read on "
                  "the grid along the up- and down-sweep branches");
  cmd->add_option("--modes", opts->settings.num_modes,
                  "number of the reference's lowest modes compared (default 12)");
  cmd->add_option("--mac-threshold", opts->settings.mac_threshold,
                  "least MAC (mass-weighted) of a mode match; below it the mode is absent "
                  "(default 0.8)");
  cmd->add_option("--frequency-tolerance", opts->settings.frequency_tolerance,
                  "|Δf/f| of a matched mode accepted as agreement (default 0.01)");
  cmd->add_option("--dte-tolerance", opts->settings.dte_tolerance,
                  "|Δ RMS DTE| accepted as agreement, as a fraction of the reference's peak "
                  "(default 0.05)");
  cmd->add_option("--harmonics", opts->settings.nonlinear_harmonics,
                  "harmonics H of the nonlinear harmonic balance (default 24)");
  cmd->add_option("--branch-search", opts->settings.branch_search,
                  "nonlinear HB: frequencies searched for branches off the traced curve "
                  "(default 8, 0: off; as `geardyn hb --branch-search`)");
  cmd->add_option("--simulate-tolerance", opts->settings.simulate_tolerance,
                  "time domain: local relative error per step (default 1e-6)");
  cmd->add_option("--steady-tolerance", opts->settings.steady_tolerance,
                  "time domain: relative period-to-period change of a steady state (default "
                  "1e-6)");
  cmd->add_option("--max-periods", opts->settings.max_periods,
                  "time domain: periods per speed before the point is not steady (default 3000)");
  cmd->add_option("--vary", opts->vary,
                  "KEY[,KEY...]=lo:hi:n: repeat the comparison with the scene value(s) KEY set to "
                  "n values in [lo, hi] and report every level's errors against it "
                  "(compare_vary.csv/.json/.svg), e.g. gear.pinion.helix_angle_deg,"
                  "gear.wheel.helix_angle_deg=0:35:8");
  cmd->add_flag("!--no-match-contact", opts->settings.match_contact,
                "with the contact level: keep the scene's stiffness (ISO 6336) and mesh damping in "
                "the other levels instead of the contact model's mean stiffness and its law's "
                "damping at the mean load");
  cmd->add_option("--chart-x", opts->settings.chart_x,
                  "with floquet: a stability chart per level over path=lo:hi:n (as "
                  "`geardyn stability-chart --x`), the levels' transition curves overlaid in "
                  "compare_chart.svg over the reference's regions");
  cmd->add_option("--chart-y", opts->settings.chart_y, "the chart's second axis, path=lo:hi:n");
  cmd->add_option("--threads", opts->settings.threads,
                  "threads of the charts and time-domain runs (0: OpenMP's default)")
      ->check(CLI::Range(0, 1024));
  cmd->add_flag("--progress", opts->settings.progress, "print the progress on the error stream");
  Command command{cmd, nullptr};
  command.run_with_err = [opts](std::ostream& out, std::ostream& err) {
    return RunCompareCommand(*opts, out, err);
  };
  return command;
}

}  // namespace geardyn::app
