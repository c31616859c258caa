#include "geardyn/hb_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/csv_cell.hpp"
#include "geardyn/svg_plot.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

// Parses a whole string as a double (no trailing characters).
bool ParseDouble(const std::string& text, double* value) {
  if (text.empty()) return false;
  std::size_t used = 0;
  try {
    *value = std::stod(text, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == text.size();
}

std::vector<double> ToStd(const Vector6& v) { return {v.data(), v.data() + 6}; }

// A CSV cell: empty for a value that does not exist (csv_cell.hpp).
std::string Num(double v) { return CsvNumber(v); }

// The stability of point i as JSON (null without a stability pass).
json PointStability(const HbStabilitySweep* stability, std::size_t i) {
  if (stability == nullptr || i >= stability->points.size()) return nullptr;
  const HbPointStability& s = stability->points[i];
  json j = {{"verdict", ToString(s.verdict)},     {"max_abs_multiplier", s.max_abs_multiplier},
            {"error_estimate", s.error_estimate}, {"marginal", s.marginal},
            {"method", ToString(s.method_used)},  {"status", StatusName(s.status)}};
  if (!s.message.empty()) j["message"] = s.message;
  return j;
}

// "unstable (parametric, max|λ| = 1.069)", "stable", "stable, marginal", "undetermined" or ""
// (no stability). "stable, marginal" (as `geardyn floquet` says it) where the JSON has
// `marginal: true`: a multiplier on the unit circle within the error estimate (undamped modes).
std::string StabilityText(const json& stability) {
  if (stability.is_null()) return "";
  const std::string verdict = stability["verdict"].get<std::string>();
  if (verdict == "stable" && stability.value("marginal", false)) return "stable, marginal";
  if (verdict != "unstable") return verdict;
  return "unstable (parametric, max|λ| = " +
         FormatMaxAbsMultiplier(stability["max_abs_multiplier"].get<double>()) + ")";
}

}  // namespace

std::vector<double> ParseMeshFrequencies(const std::string& spec, double nominal_hz) {
  if (spec.empty()) {
    GEARDYN_THROW_UNLESS(nominal_hz > 0.0,
                         "--mesh-frequency: required (the scene's operating "
                         "speed is 0, so there is no default range)");
    std::vector<double> out(200);
    for (int i = 0; i < 200; ++i) out[i] = nominal_hz * (0.2 + 2.3 * i / 199.0);
    return out;
  }
  std::vector<std::string> parts;
  std::stringstream ss(spec);
  for (std::string part; std::getline(ss, part, ':');) parts.push_back(part);
  const std::string expected = "expected lo:hi:n (Hz, Hz, count) or one frequency";
  double lo = 0.0, hi = 0.0, count = 1.0;
  if (parts.size() == 1) {
    GEARDYN_THROW_UNLESS(ParseDouble(parts[0], &lo),
                         "--mesh-frequency: '" << spec << "' is not a number; " << expected);
    hi = lo;
  } else {
    GEARDYN_THROW_UNLESS(parts.size() == 3 && ParseDouble(parts[0], &lo) &&
                             ParseDouble(parts[1], &hi) && ParseDouble(parts[2], &count),
                         "--mesh-frequency: '" << spec << "': " << expected);
  }
  GEARDYN_THROW_UNLESS(std::isfinite(lo) && lo > 0.0,
                       "--mesh-frequency: lo must be a positive frequency [Hz], got " << lo);
  GEARDYN_THROW_UNLESS(std::isfinite(hi) && hi >= lo,
                       "--mesh-frequency: hi must be >= lo = " << lo << ", got " << hi);
  GEARDYN_THROW_UNLESS(count >= 1.0 && count <= 100000.0 && count == std::floor(count),
                       "--mesh-frequency: n must be an integer in 1 … 100000, got " << count);
  const int n = static_cast<int>(count);
  GEARDYN_THROW_UNLESS(n == 1 || hi > lo,
                       "--mesh-frequency: hi must exceed lo for n = " << n << " points");
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) out[i] = n == 1 ? lo : lo + (hi - lo) * i / (n - 1);
  if (n > 1) out.back() = hi;  // exactly the requested end (lo + (hi − lo) may round)
  return out;
}

HbOptions MakeHbOptions(const HbSettings& settings) {
  GEARDYN_THROW_UNLESS(
      settings.harmonics >= 0,
      "--harmonics: must be >= 1 (or 0 for --tolerance), got " << settings.harmonics);
  GEARDYN_THROW_UNLESS(std::isfinite(settings.tolerance) && settings.tolerance > 0.0,
                       "--tolerance: must be > 0, got " << settings.tolerance);
  HbOptions options;
  options.harmonics = settings.harmonics;
  options.tolerance = settings.tolerance;
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why),
                       (settings.harmonics > kMaxHbHarmonics ? "--harmonics: " : "") << why);
  return options;
}

json MakeHbReport(const std::string& scene_source, const HbSettings& settings,
                  const HbSweepResult& sweep, const std::vector<std::string>& scene_warnings,
                  const HbStabilitySweep* stability) {
  json report;
  report["scene"] = scene_source;
  report["mode"] = "linear";
  report["harmonics"] = settings.harmonics;
  // The tolerance chooses H; with a fixed H it is not used (and not echoed).
  report["tolerance"] = settings.harmonics > 0 ? json(nullptr) : json(settings.tolerance);
  // An undetermined verdict is a numerical problem of the run (docs/design.md "Linear HB
  // stability"); the HB's own failure, when any, is reported first.
  const bool stability_failed =
      stability != nullptr && sweep.summary.ok() && !stability->summary.ok();
  report["status"] =
      StatusName(stability_failed ? stability->summary.status : sweep.summary.status);
  report["message"] = stability_failed ? stability->summary.message : sweep.summary.message;
  report["stability"] = stability != nullptr ? "floquet" : "none";
  json warnings = json::array();
  for (const std::string& w : scene_warnings) warnings.push_back("scene: " + w);
  for (const std::string& w : sweep.summary.warnings) warnings.push_back(w);
  json ranges = json::array();
  if (stability != nullptr) {
    for (const std::string& w : stability->summary.warnings) warnings.push_back(w);
    if (!sweep.summary.ok() && !stability->summary.ok()) {
      warnings.push_back(stability->summary.message);
    }
    for (const HbUnstableRange& r : stability->unstable_ranges) {
      ranges.push_back({{"lo_hz", r.lo_hz},
                        {"hi_hz", r.hi_hz},
                        {"points", r.points},
                        {"max_abs_multiplier", r.max_abs_multiplier}});
    }
  }
  report["unstable_ranges"] = ranges;
  report["warnings"] = warnings;
  report["meshes"] = json::array();
  report["elements"] = json::array();
  if (!sweep.points.empty()) {
    for (const HbMeshOutput& m : sweep.points.front().meshes) report["meshes"].push_back(m.name);
    for (const HbElementOutput& e : sweep.points.front().elements) {
      report["elements"].push_back(e.name);
    }
  }
  json points = json::array();
  for (std::size_t i = 0; i < sweep.points.size(); ++i) {
    const HbResult& r = sweep.points[i];
    json p;
    p["mesh_frequency_hz"] = r.mesh_frequency_hz;
    p["harmonics"] = r.harmonics;
    p["highest_harmonic"] = r.highest_harmonic;
    p["period_meshes"] = r.period_meshes;
    p["reciprocal_condition"] = r.reciprocal_condition;
    p["method"] = ToString(r.method_used);
    p["error_estimate"] = r.summary.error_estimate;
    p["status"] = StatusName(r.summary.status);
    if (!r.summary.ok()) p["message"] = r.summary.message;
    if (r.sparse_harmonics) {
      // dte_amplitudes_m are then at these harmonics of ω_m/P (harmonic_balance.hpp).
      p["sparse_harmonics"] = true;
      p["kept_harmonics"] = r.kept_harmonics;
      p["time_samples_per_operator_period"] = r.time_samples;
    }
    json meshes = json::array();
    for (const HbMeshOutput& m : r.meshes) {
      meshes.push_back({{"name", m.name},
                        {"rms_dte_m", m.rms_dte},
                        {"peak_to_peak_dte_m", m.peak_to_peak_dte},
                        {"mean_dte_m", m.mean_dte},
                        {"dte_amplitudes_m",
                         std::vector<double>(m.dte_amplitudes.data(),
                                             m.dte_amplitudes.data() + m.dte_amplitudes.size())},
                        {"mean_force_n", m.mean_force},
                        {"rms_force_n", m.rms_force},
                        {"peak_to_peak_force_n", m.peak_to_peak_force}});
    }
    p["meshes"] = meshes;
    json elements = json::array();
    for (const HbElementOutput& e : r.elements) {
      elements.push_back({{"name", e.name},
                          {"mean_force", ToStd(e.mean_force)},
                          {"rms_force", ToStd(e.rms_force)}});
    }
    p["elements"] = elements;
    p["stability"] = PointStability(stability, i);
    points.push_back(p);
  }
  report["points"] = points;
  report["wall_time_s"] = sweep.summary.wall_time_s;
  report["stability_wall_time_s"] = stability != nullptr ? stability->summary.wall_time_s : 0.0;
  return report;
}

std::string FormatHbCsv(const HbSweepResult& sweep, const HbStabilitySweep* stability) {
  std::ostringstream os;
  os << "mesh_frequency_hz,harmonics,error_estimate,status";
  if (stability != nullptr) os << ",stability,max_abs_multiplier";
  if (!sweep.points.empty()) {
    for (const HbMeshOutput& m : sweep.points.front().meshes) {
      os << "," << m.name << ":rms_dte_m," << m.name << ":peak_to_peak_dte_m," << m.name
         << ":mean_dte_m";
      for (int h = 1; h <= kCsvHarmonics; ++h) os << "," << m.name << ":a" << h << "_m";
      os << "," << m.name << ":rms_force_n";
    }
  }
  os << "\n";
  for (std::size_t i = 0; i < sweep.points.size(); ++i) {
    const HbResult& r = sweep.points[i];
    os << Num(r.mesh_frequency_hz) << "," << r.harmonics << "," << Num(r.summary.error_estimate)
       << "," << StatusName(r.summary.status);
    if (stability != nullptr) {
      const HbPointStability& s = stability->points[i];
      os << "," << ToString(s.verdict) << "," << Num(s.max_abs_multiplier);
    }
    for (const HbMeshOutput& m : r.meshes) {
      os << "," << Num(m.rms_dte) << "," << Num(m.peak_to_peak_dte) << "," << Num(m.mean_dte);
      for (int h = 1; h <= kCsvHarmonics; ++h) {
        os << ",";
        if (r.sparse_harmonics) {  // amplitudes at the kept harmonics only: 0 elsewhere
          const auto it = std::lower_bound(r.kept_harmonics.begin(), r.kept_harmonics.end(), h);
          const bool kept = it != r.kept_harmonics.end() && *it == h;
          os << Num(kept ? m.dte_amplitudes(it - r.kept_harmonics.begin()) : 0.0);
        } else if (h < m.dte_amplitudes.size()) {
          os << Num(m.dte_amplitudes(h));
        }
      }
      os << "," << Num(m.rms_force);
    }
    os << "\n";
  }
  return os.str();
}

std::string FormatHbText(const json& report) {
  std::ostringstream os;
  os << "harmonic balance (" << report["mode"].get<std::string>() << ") of "
     << report["scene"].get<std::string>() << ": " << report["points"].size()
     << " mesh frequencies, "
     << (report["harmonics"].get<int>() > 0
             ? "H = " + std::to_string(report["harmonics"].get<int>())
             : "tolerance " + Num(report["tolerance"].get<double>()))
     << ", status " << report["status"].get<std::string>() << "\n";
  const auto& points = report["points"];
  const std::size_t stride = points.size() > 40 ? points.size() / 20 : 1;
  char line[256];
  const bool with_stability = report.value("stability", "none") != "none";
  std::snprintf(line, sizeof(line), "%12s %4s  %-24s %12s %12s %12s%s\n", "f_mesh [Hz]", "H",
                "mesh", "RMS DTE [um]", "p-p [um]", "RMS F [N]",
                with_stability ? "  stability" : "");
  os << line;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    const std::string stability = StabilityText(p.value("stability", json(nullptr)));
    // Every unstable or undetermined point is listed, whatever the stride.
    const bool flagged = !stability.empty() && stability.rfind("stable", 0) != 0;
    if (i % stride != 0 && !flagged) continue;
    for (const auto& m : p["meshes"]) {
      std::snprintf(line, sizeof(line), "%12.2f %4d  %-24s %12.5g %12.5g %12.5g%s%s%s\n",
                    p["mesh_frequency_hz"].get<double>(), p["harmonics"].get<int>(),
                    m["name"].get<std::string>().c_str(), 1e6 * m["rms_dte_m"].get<double>(),
                    1e6 * m["peak_to_peak_dte_m"].get<double>(), m["rms_force_n"].get<double>(),
                    stability.empty() ? "" : "  ", stability.c_str(),
                    p["status"].get<std::string>() == "success" ? "" : "  (!)");
      os << line;
    }
  }
  if (!report["message"].get<std::string>().empty()) {
    os << "message: " << report["message"].get<std::string>() << "\n";
  }
  for (const auto& p : points) {
    if (!p.value("sparse_harmonics", false)) continue;
    const auto period = p["period_meshes"].get<std::int64_t>();
    os << "note: hunting period of " << period
       << " mesh cycles solved with sparse harmonics (the runout's sidebands of each kept mesh "
          "order): means and RMS from the harmonics (DTE exact, forces from "
       << p["time_samples_per_operator_period"].get<int>()
       << " samples per mesh period); p-p sampled over at most " << kHbPeakWindowPeriods
       << " mesh periods spread over the hunting period (a lower bound)\n";
    break;
  }
  for (const auto& w : report["warnings"]) os << "warning: " << w.get<std::string>() << "\n";
  return os.str();
}

std::string RenderHbPlot(const HbSweepResult& sweep, const std::string& title,
                         const HbStabilitySweep* stability) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "mesh frequency [Hz]";
  PlotPanel panel;
  panel.y_label = "RMS DTE [µm]";
  const std::size_t meshes = sweep.points.empty() ? 0 : sweep.points.front().meshes.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < meshes; ++k) {
    PlotSeries series;
    series.label = sweep.points.front().meshes[k].name;
    if (stability == nullptr) {
      for (const HbResult& r : sweep.points) {
        series.x.push_back(r.mesh_frequency_hz);
        series.y.push_back(r.summary.ok() ? 1e6 * r.meshes[k].rms_dte : nan);
      }
      panel.series.push_back(series);
      continue;
    }
    // Solid over stable points; each run of unstable points one dashed series in the same
    // colour, from its stable neighbour before to the one after so that the curve stays
    // connected (as the nonlinear plot). Failed points and undetermined verdicts break it.
    series.colour = PlotColour(k);
    const std::size_t count = sweep.points.size();
    std::vector<double> y(count, nan);
    std::vector<bool> unstable(count, false);
    for (std::size_t i = 0; i < count; ++i) {
      const HbResult& r = sweep.points[i];
      const FloquetVerdict v = stability->points[i].verdict;
      if (!r.summary.ok() || v == FloquetVerdict::kUndetermined) continue;
      y[i] = 1e6 * r.meshes[k].rms_dte;
      unstable[i] = v == FloquetVerdict::kUnstable;
    }
    for (std::size_t i = 0; i < count; ++i) {
      series.x.push_back(sweep.points[i].mesh_frequency_hz);
      series.y.push_back(unstable[i] ? nan : y[i]);
    }
    panel.series.push_back(series);
    bool labelled = k > 0;
    for (std::size_t i = 0; i < count;) {
      if (!unstable[i]) {
        ++i;
        continue;
      }
      PlotSeries run;
      run.colour = series.colour;
      run.dashed = true;
      if (!labelled) run.label = "parametrically unstable (dashed)";
      labelled = true;
      const std::size_t first = i > 0 ? i - 1 : i;  // a NaN neighbour draws nothing
      while (i < count && unstable[i]) ++i;
      const std::size_t last = i < count ? i : count - 1;
      for (std::size_t m = first; m <= last; ++m) {
        run.x.push_back(sweep.points[m].mesh_frequency_hz);
        run.y.push_back(y[m]);
      }
      panel.series.push_back(run);
    }
  }
  spec.panels.push_back(panel);
  return RenderSvg(spec);
}

}  // namespace geardyn::app
