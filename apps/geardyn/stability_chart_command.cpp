// `geardyn stability-chart SCENE --x PATH=LO:HI:N --y PATH=LO:HI:N`: max|λ| of the Floquet
// multipliers over two scene parameters (stability_chart_runner.hpp), the unstable regions
// labelled by their nearest parametric resonance and the transition curves; writes
// stability_chart.csv, transition_curves.csv, stability_chart.json and stability_chart.svg to
// --out, and progress lines to the error stream (unless --json or --quiet).
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geardyn/analysis_runs.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/csv_cell.hpp"
#include "geardyn/output_files.hpp"
#include "geardyn/region_plot.hpp"
#include "geardyn/stability_chart_runner.hpp"

namespace geardyn::app {
namespace {

struct ChartCommandOptions {
  SceneCommandOptions scene;
  ChartRunSettings settings;
  bool no_curves = false;
  bool quiet = false;
};

std::string RegionLabel(const ChartRegion& r) {
  return r.labelled ? r.resonance.label : std::string("unstable");
}

nlohmann::json MakeChartReport(const SceneChartSettings& settings, const SceneChart& run) {
  const StabilityChartResult& c = run.chart;
  nlohmann::json regions = nlohmann::json::array();
  for (std::size_t r = 0; r < c.regions.size(); ++r) {
    const ChartRegion& g = c.regions[r];
    nlohmann::json j = {{"id", r},
                        {"label", RegionLabel(g)},
                        {"labelled", g.labelled},
                        {"num_points", g.num_points},
                        {"centroid", {{"x", g.centroid_x}, {"y", g.centroid_y}}},
                        {"max_abs_multiplier", g.max_abs_multiplier},
                        {"mean_mesh_frequency_hz", g.mean_mesh_frequency_hz}};
    if (g.labelled) {
      j["kind"] = ToString(g.resonance.kind);
      j["k"] = g.resonance.k;
      j["p"] = g.resonance.p;
      j["q"] = g.resonance.q;
      j["resonance_mesh_frequency_hz"] = g.resonance.mesh_frequency_hz;
      j["vote_share"] = g.vote_share;
      if (run.speed_axis == "x" && run.mesh_hz_per_rpm > 0.0) {
        j["resonance_speed_rpm"] = g.resonance.mesh_frequency_hz / run.mesh_hz_per_rpm;
      }
    }
    regions.push_back(j);
  }
  long curve_points = 0;
  for (const TransitionCurve& t : c.curves) curve_points += static_cast<long>(t.x.size());
  const auto axis = [](const ChartAxis& a) {
    return nlohmann::json{{"path", a.name}, {"lo", a.lo}, {"hi", a.hi}, {"n", a.num_points}};
  };
  long unstable = 0, undetermined = 0;
  for (std::size_t i = 0; i < c.stable.size(); ++i) {
    unstable += c.ok[i] && !c.stable[i];
    undetermined += c.ok[i] ? 0 : 1;
  }
  return {{"scene", settings.scene},
          {"overrides", settings.overrides},
          {"x", axis(c.x_axis)},
          {"y", axis(c.y_axis)},
          {"speed_axis", run.speed_axis},
          {"mesh_hz_per_rpm", run.mesh_hz_per_rpm},
          {"method", ToString(settings.floquet.method)},
          {"tolerance", settings.floquet.tolerance},
          {"boundary_tolerance", settings.chart.boundary_tolerance},
          {"natural_frequencies_hz", run.natural_frequencies_hz},
          {"status", StatusName(c.summary.status)},
          {"message", c.summary.message},
          {"error_estimate", c.summary.error_estimate},
          {"wall_time_s", c.summary.wall_time_s},
          {"counters", c.summary.counters},
          {"model_builds", run.model_builds},
          {"refined_points", run.refined_points},
          {"prepared_rows", run.prepared_rows},
          {"verdict_tolerance", settings.verdict_tolerance},
          {"num_points", c.stable.size()},
          {"num_unstable_points", unstable},
          {"num_undetermined_points", undetermined},
          {"num_curves", c.curves.size()},
          {"num_curve_points", curve_points},
          {"regions", regions},
          {"warnings", run.warnings}};
}

std::string PointsCsv(const StabilityChartResult& c) {
  std::ostringstream s;
  s << std::setprecision(17)
    << "x,y,mesh_frequency_hz,max_abs_multiplier,error_estimate,stable,ok,region,label\n";
  for (int iy = 0; iy < c.y_axis.num_points; ++iy) {
    for (int ix = 0; ix < c.x_axis.num_points; ++ix) {
      const int i = c.index(ix, iy);
      const int r = c.region[i];
      // An undetermined point's `stable` is empty, not 0 (it read as unstable; only `ok` showed
      // the failure), and so are its non-finite numbers (csv_cell.hpp).
      s << CsvNumber(c.x_axis.Value(ix), "%.17g") << "," << CsvNumber(c.y_axis.Value(iy), "%.17g")
        << "," << CsvNumber(c.mesh_frequency_hz[i], "%.17g") << ","
        << CsvNumber(c.max_abs_multiplier[i], "%.17g") << ","
        << CsvNumber(c.error_estimate[i], "%.17g") << "," << CsvVerdict(c.ok[i], c.stable[i]) << ","
        << int{c.ok[i]} << "," << r << "," << (r >= 0 ? RegionLabel(c.regions[r]) : "") << "\n";
    }
  }
  return s.str();
}

std::string CurvesCsv(const StabilityChartResult& c) {
  std::ostringstream s;
  s << std::setprecision(17) << "curve,point,x,y,closed\n";
  for (std::size_t k = 0; k < c.curves.size(); ++k) {
    const TransitionCurve& t = c.curves[k];
    for (std::size_t p = 0; p < t.x.size(); ++p) {
      s << k << "," << p << "," << t.x[p] << "," << t.y[p] << "," << int{t.closed} << "\n";
    }
  }
  return s.str();
}

std::string ChartSvg(const SceneChart& run, const std::string& title) {
  const StabilityChartResult& c = run.chart;
  RegionPlotSpec spec = MakeRegionPlotGrid(c, title);
  for (const TransitionCurve& t : c.curves) spec.curves.push_back({t.x, t.y, t.closed, "", ""});
  // Each region's label at its most unstable point (always inside the region), or, when that
  // place is taken, at its next most unstable points (RenderRegionSvg lays them out).
  std::vector<std::vector<int>> points(c.regions.size());
  for (std::size_t i = 0; i < c.region.size(); ++i) {
    if (c.region[i] >= 0) points[c.region[i]].push_back(static_cast<int>(i));
  }
  std::vector<std::string> marked;
  const int nx = c.x_axis.num_points;
  for (std::size_t r = 0; r < c.regions.size(); ++r) {
    std::vector<int>& p = points[r];
    std::stable_sort(p.begin(), p.end(), [&c](int a, int b) {
      return c.max_abs_multiplier[a] > c.max_abs_multiplier[b];
    });
    RegionPlotLabel label{
        c.x_axis.Value(p[0] % nx), c.y_axis.Value(p[0] / nx), RegionLabel(c.regions[r]), {}};
    for (std::size_t k = 1; k < p.size(); ++k) {
      label.anchors.push_back({c.x_axis.Value(p[k] % nx), c.y_axis.Value(p[k] / nx)});
    }
    spec.labels.push_back(std::move(label));
    const ChartRegion& g = c.regions[r];
    if (g.labelled && run.speed_axis == "x" && run.mesh_hz_per_rpm > 0.0 &&
        std::find(marked.begin(), marked.end(), g.resonance.label) == marked.end()) {
      marked.push_back(g.resonance.label);
      spec.markers.push_back(
          {g.resonance.mesh_frequency_hz / run.mesh_hz_per_rpm, g.resonance.label});
    }
  }
  return RenderRegionSvg(spec);
}

std::string FormatChartText(const nlohmann::json& j) {
  std::ostringstream s;
  s << std::setprecision(6);
  const auto axis = [](const nlohmann::json& a) {
    std::ostringstream t;
    t << a["path"].get<std::string>() << " " << a["lo"].get<double>() << " … "
      << a["hi"].get<double>() << " (" << a["n"].get<int>() << ")";
    return t.str();
  };
  s << "stability chart: " << j["scene"].get<std::string>() << "\n  x: " << axis(j["x"])
    << "\n  y: " << axis(j["y"]) << "\n  " << j["num_points"].get<long>() << " points, "
    << j["num_unstable_points"].get<long>() << " unstable, "
    << j["num_undetermined_points"].get<long>() << " undetermined, " << j["regions"].size()
    << " region(s), " << j["num_curves"].get<long>() << " transition curve(s) ("
    << j["num_curve_points"].get<long>() << " points), method " << j["method"].get<std::string>()
    << ", " << j["counters"]["evaluations"].get<long>() << " evaluations on "
    << j["counters"]["threads"].get<long>() << " thread(s) in " << j["wall_time_s"].get<double>()
    << " s\n";
  s << "  status " << j["status"].get<std::string>();
  if (!j["message"].get<std::string>().empty()) s << ": " << j["message"].get<std::string>();
  s << "\n";
  for (const nlohmann::json& r : j["regions"]) {
    s << "  region " << r["id"].get<int>() << ": " << r["label"].get<std::string>() << ", "
      << r["num_points"].get<int>() << " point(s), max|λ| "
      << r["max_abs_multiplier"].get<double>();
    if (r["labelled"].get<bool>()) {
      s << ", resonance f_m " << r["resonance_mesh_frequency_hz"].get<double>() << " Hz";
      if (r.contains("resonance_speed_rpm")) {
        s << " (" << r["resonance_speed_rpm"].get<double>() << " rpm)";
      }
      s << ", region mean f_m " << r["mean_mesh_frequency_hz"].get<double>() << " Hz";
    }
    s << "\n";
  }
  for (const nlohmann::json& w : j["warnings"]) s << "warning: " << w.get<std::string>() << "\n";
  return s.str();
}

int RunChart(const ChartCommandOptions& opts, std::ostream& out, std::ostream& err) {
  ChartRunSettings settings = opts.settings;
  settings.curves = !opts.no_curves;
  ProgressLine progress;
  if (!opts.scene.json && !opts.quiet) progress = [&err](const std::string& line) { err << line; };
  const ChartRun run = RunChartAnalysis(opts.scene.scene, {}, opts.scene.overrides, settings,
                                        opts.scene.out_dir, progress);
  out << (opts.scene.json ? run.report.dump(2) + "\n" : run.text);
  if (!opts.scene.out_dir.empty() && !opts.scene.json) {
    out << "written to " << opts.scene.out_dir << "\n";
  }
  return run.exit_code;
}

}  // namespace

ChartRun RunChartAnalysis(const std::string& scene, const std::string& scene_text,
                          const std::vector<std::string>& overrides, const ChartRunSettings& opts,
                          const std::string& out_dir, const ProgressLine& progress) {
  // The command line checks these with CLI11; the library API (Python) reaches here directly.
  GEARDYN_THROW_UNLESS(opts.threads >= 0, "--threads: must be >= 0, got " << opts.threads);
  GEARDYN_THROW_UNLESS(
      std::isfinite(opts.tolerance) && opts.tolerance > 0.0 && opts.tolerance < 1.0,
      "--tolerance: must be a finite number in (0, 1), got " << opts.tolerance);
  GEARDYN_THROW_UNLESS(
      opts.boundary_tolerance >= 1e-15 && opts.boundary_tolerance <= 0.5,
      "--boundary-tolerance: must be in [1e-15, 0.5], got " << opts.boundary_tolerance);
  GEARDYN_THROW_UNLESS(opts.max_order >= 1 && opts.max_order <= 50,
                       "--max-order: must be in [1, 50], got " << opts.max_order);
  SceneChartSettings settings;
  settings.scene = scene;
  settings.scene_text = scene_text;
  settings.overrides = overrides;
  settings.x = ParseChartAxis("--x", opts.x);
  settings.y = ParseChartAxis("--y", opts.y);
  settings.floquet.method = ParseFloquetMethod(opts.method, "--method");
  settings.floquet.tolerance = opts.tolerance;
  settings.chart.num_threads = opts.threads;
  settings.chart.boundary_tolerance = opts.boundary_tolerance;
  settings.chart.max_resonance_order = opts.max_order;
  settings.chart.difference_combinations = opts.difference;
  settings.chart.trace_curves = opts.curves;
  if (progress) {
    // One line per 10 % of each phase.
    auto last = std::make_shared<std::pair<std::string, long>>("", -1);
    settings.chart.progress = [last, progress](const ChartProgress& p) {
      const long decile = p.total > 0 ? 10 * p.done / p.total : 10;
      if (last->first == p.phase && decile <= last->second) return;
      *last = {p.phase, decile};
      progress(std::string("stability-chart: ") + p.phase + " " + std::to_string(10 * decile) +
               " % (" + std::to_string(p.done) + "/" + std::to_string(p.total) + " evaluations)\n");
    };
  }
  ChartRun out;
  out.run = ComputeSceneStabilityChart(settings);
  out.report = MakeChartReport(settings, out.run);
  out.text = FormatChartText(out.report);
  if (!out_dir.empty()) {
    WriteOutputFile(out_dir, "stability_chart.json", out.report.dump(2) + "\n");
    WriteOutputFile(out_dir, "stability_chart.csv", PointsCsv(out.run.chart));
    WriteOutputFile(out_dir, "transition_curves.csv", CurvesCsv(out.run.chart));
    WriteOutputFile(out_dir, "stability_chart.svg",
                    ChartSvg(out.run, scene + " — stability chart (max|λ| > 1 shaded)"));
  }
  out.exit_code = out.run.chart.summary.ok() ? int{kExitOk} : int{kExitNumericalIssue};
  return out;
}

Command AddStabilityChartCommand(CLI::App& app) {
  auto opts = std::make_shared<ChartCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "stability-chart",
      "Floquet stability chart over two scene parameters: unstable regions labelled by their "
      "parametric resonance, transition curves (CSV, JSON, SVG)");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option("--x", opts->settings.x,
                  "x axis PATH=LO:HI:N over any --set path, e.g. "
                  "operating_point.speed_rpm=500:6000:60")
      ->required();
  cmd->add_option("--y", opts->settings.y,
                  "y axis PATH=LO:HI:N, e.g. mesh.pinion-wheel.parameters.stiffness.1=0:1e8:20")
      ->required();
  cmd->add_option("--threads", opts->settings.threads, "threads (default 0 = all cores)")
      ->check(FiniteNumberIn(0, std::numeric_limits<int>::max()));  // clamped to the work, warned
  std::vector<std::string> methods;
  for (FloquetMethod m : kFloquetMethods) methods.push_back(ToString(m));
  cmd->add_option("--method", opts->settings.method,
                  "Floquet method: auto, exact_steps, magnus, ode_stepper, hill, "
                  "modal_projection or arpack_monodromy (default auto)")
      ->check(CLI::IsMember(methods));
  cmd->add_option("--tolerance", opts->settings.tolerance,
                  "Floquet error target of every point (default 1e-6; points whose verdict lies "
                  "within twice the estimate are recomputed at 1e-10)")
      ->check(FiniteNumberIn(0.0, 1.0, true, true));  // FloquetOptions::tolerance's bound
  cmd->add_option("--boundary-tolerance", opts->settings.boundary_tolerance,
                  "transition-curve bisection tolerance, a fraction of the axis span (default "
                  "1e-3: below a pixel of the SVG's 780-px frame)")
      ->check(CLI::Range(1e-15, 0.5));
  cmd->add_option("--max-order", opts->settings.max_order,
                  "largest resonance order k of the labels (3)")
      ->check(CLI::Range(1, 50));
  cmd->add_flag("--difference", opts->settings.difference,
                "also label difference combinations (f_q - f_p)/k");
  cmd->add_flag("--no-curves", opts->no_curves, "skip the transition curves");
  cmd->add_flag("--quiet", opts->quiet, "no progress lines on the error stream");
  return {cmd, nullptr,
          [opts](std::ostream& out, std::ostream& err) { return RunChart(*opts, out, err); }};
}

}  // namespace geardyn::app
