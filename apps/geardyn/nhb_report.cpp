#include "geardyn/nhb_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "geardyn/csv_cell.hpp"
#include "geardyn/svg_plot.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxTableRows = 60;

// A number, or null when it is not finite (JSON has no NaN or infinity).
json Finite(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json FiniteArray(const double* data, Eigen::Index n) {
  json a = json::array();
  for (Eigen::Index i = 0; i < n; ++i) a.push_back(Finite(data[i]));
  return a;
}

// A CSV cell: empty for a value that does not exist (csv_cell.hpp).
std::string Num(double v) { return CsvNumber(v); }

// A number in the text report: "—" for a value that does not exist.
std::string Text(double v) { return std::isfinite(v) ? CsvNumber(v) : std::string("—"); }

// A JSON number for the table, NaN for null.
double Get(const json& v) { return v.is_number() ? v.get<double>() : kNaN; }

bool PointOk(const SystemNhbPoint& p) { return p.point.status == Status::kSuccess; }

}  // namespace

json MakeNhbReport(const std::string& scene_source, const NhbRunInfo& info,
                   const SystemNhbCurve& curve, const std::vector<std::string>& scene_warnings) {
  json report;
  report["scene"] = scene_source;
  report["mode"] = "nonlinear";
  report["mesh_frequency"] = {
      {"start_hz", info.start_hz}, {"end_hz", info.end_hz}, {"resolution", info.resolution}};
  report["harmonics"] = curve.harmonics_used;
  report["harmonics_requested"] = info.harmonics_requested;
  report["tolerance"] = info.tolerance;
  report["period_multiple"] = curve.period_multiple;
  report["stability"] = info.stability;
  report["status"] = StatusName(curve.summary.status);
  report["message"] = curve.summary.message;
  report["error_estimate"] = Finite(curve.summary.error_estimate);
  json warnings = json::array();
  for (const std::string& w : scene_warnings) warnings.push_back("scene: " + w);
  for (const std::string& w : curve.summary.warnings) warnings.push_back(w);
  report["warnings"] = warnings;
  report["meshes"] = json::array();
  report["elements"] = json::array();
  if (!curve.points.empty()) {
    for (const SystemNhbMeshOutput& m : curve.points.front().meshes) {
      report["meshes"].push_back(m.name);
    }
    for (const SystemNhbElementOutput& e : curve.points.front().elements) {
      report["elements"].push_back(e.name);
    }
  }
  json points = json::array();
  for (const SystemNhbPoint& r : curve.points) {
    json p;
    p["mesh_frequency_hz"] = Finite(r.mesh_frequency_hz);
    p["branch"] = r.point.branch;
    p["segment"] = r.point.segment;
    // true / false, null when undetermined (a non-finite multiplier or a failed point) or not
    // computed (--stability none: no verdict is printed for a computation that did not run).
    const bool computed = info.stability != "none";
    p["stable"] = !computed || r.point.stable == FloquetVerdict::kUndetermined
                      ? json(nullptr)
                      : json(r.point.stable == FloquetVerdict::kStable);
    p["verdict"] = computed ? ToString(r.point.stable) : "not computed";
    // max|μ| = 0 means "not computed" (NhbPoint: a failed point gets no monodromy); a real
    // monodromy has det Φ = exp(−∫tr M⁻¹C dt) > 0 (Liouville), so max|μ| > 0. It printed
    // "0.000000" next to "undetermined".
    p["max_multiplier"] =
        computed && r.point.max_multiplier != 0.0 ? Finite(r.point.max_multiplier) : json(nullptr);
    p["error_estimate"] = computed ? Finite(r.point.error_estimate) : json(nullptr);
    p["status"] = StatusName(r.point.status);
    json meshes = json::array();
    for (const SystemNhbMeshOutput& m : r.meshes) {
      meshes.push_back(
          {{"name", m.name},
           {"rms_dte_m", Finite(m.rms_dte)},
           {"peak_to_peak_dte_m", Finite(m.peak_to_peak_dte)},
           {"mean_dte_m", Finite(m.mean_dte)},
           {"dte_amplitudes_m", FiniteArray(m.dte_amplitudes.data(), m.dte_amplitudes.size())},
           {"mean_force_n", Finite(m.mean_force)},
           {"rms_force_n", Finite(m.rms_force)},
           {"min_force_n", Finite(m.min_force)},
           {"max_force_n", Finite(m.max_force)},
           {"contact_loss_fraction", Finite(m.contact_loss_fraction)},
           {"back_contact", m.back_contact}});
    }
    p["meshes"] = meshes;
    json elements = json::array();
    for (const SystemNhbElementOutput& e : r.elements) {
      elements.push_back({{"name", e.name},
                          {"mean_force", FiniteArray(e.mean_force.data(), 6)},
                          {"rms_force", FiniteArray(e.rms_force.data(), 6)}});
    }
    p["elements"] = elements;
    points.push_back(p);
  }
  report["points"] = points;
  report["folds_hz"] = FiniteArray(curve.fold_frequencies_hz.data(),
                                   static_cast<Eigen::Index>(curve.fold_frequencies_hz.size()));
  report["fold_errors_hz"] = FiniteArray(curve.fold_errors_hz.data(),
                                         static_cast<Eigen::Index>(curve.fold_errors_hz.size()));
  json jumps = json::array();
  for (const SystemNhbJump& j : curve.jumps) {
    jumps.push_back({{"direction", j.up_sweep ? "up" : "down"},
                     {"mesh_frequency_hz", Finite(j.mesh_frequency_hz)},
                     {"rms_dte_before_m", Finite(j.rms_dte_before)},
                     {"rms_dte_after_m", Finite(j.rms_dte_after)},
                     {"rms_dte_landings_m",
                      FiniteArray(j.rms_dte_landings.data(),
                                  static_cast<Eigen::Index>(j.rms_dte_landings.size()))}});
  }
  report["jumps"] = jumps;
  // Asymptotes of branches whose amplitude grows without bound (each explained in a warning).
  report["unbounded_branches_hz"] =
      FiniteArray(curve.unbounded_branches_hz.data(),
                  static_cast<Eigen::Index>(curve.unbounded_branches_hz.size()));
  report["wall_time_s"] = curve.summary.wall_time_s;
  return report;
}

std::string FormatNhbCsv(const SystemNhbCurve& curve, bool stability_computed) {
  static const char* const kComponents[6] = {"fx_n", "fy_n", "fz_n", "mx_nm", "my_nm", "mz_nm"};
  std::ostringstream os;
  os << "mesh_frequency_hz,branch,stable,max_multiplier,error_estimate,status";
  if (!curve.points.empty()) {
    for (const SystemNhbMeshOutput& m : curve.points.front().meshes) {
      const std::string& n = m.name;
      os << "," << n << ":rms_dte_m," << n << ":peak_to_peak_dte_m," << n << ":mean_dte_m";
      for (int h = 1; h <= kNhbCsvHarmonics; ++h) os << "," << n << ":a" << h << "_m";
      os << "," << n << ":mean_force_n," << n << ":rms_force_n," << n << ":min_force_n," << n
         << ":max_force_n," << n << ":contact_loss_fraction," << n << ":back_contact";
    }
    for (const SystemNhbElementOutput& e : curve.points.front().elements) {
      for (const char* which : {"mean_", "rms_"}) {
        for (const char* c : kComponents) os << "," << e.name << ":" << which << c;
      }
    }
  }
  os << "\n";
  for (const SystemNhbPoint& r : curve.points) {
    os << Num(r.mesh_frequency_hz) << "," << r.point.branch << ","
       << (stability_computed ? CsvVerdict(r.point.stable != FloquetVerdict::kUndetermined,
                                           r.point.stable == FloquetVerdict::kStable)
                              : "")
       << ","
       << (!stability_computed || r.point.max_multiplier == 0.0  // 0: not computed (failed point)
               ? std::string()
               : Num(r.point.max_multiplier))
       << "," << (stability_computed ? Num(r.point.error_estimate) : std::string()) << ","
       << StatusName(r.point.status);
    for (const SystemNhbMeshOutput& m : r.meshes) {
      os << "," << Num(m.rms_dte) << "," << Num(m.peak_to_peak_dte) << "," << Num(m.mean_dte);
      for (int h = 1; h <= kNhbCsvHarmonics; ++h) {
        os << ",";
        if (h < m.dte_amplitudes.size()) os << Num(m.dte_amplitudes(h));
      }
      os << "," << Num(m.mean_force) << "," << Num(m.rms_force) << "," << Num(m.min_force) << ","
         << Num(m.max_force) << "," << Num(m.contact_loss_fraction) << ","
         << (m.back_contact ? 1 : 0);
    }
    for (const SystemNhbElementOutput& e : r.elements) {
      for (int c = 0; c < 6; ++c) os << "," << Num(e.mean_force(c));
      for (int c = 0; c < 6; ++c) os << "," << Num(e.rms_force(c));
    }
    os << "\n";
  }
  return os.str();
}

std::string FormatNhbText(const json& report) {
  std::ostringstream os;
  const auto& points = report["points"];
  os << "harmonic balance (nonlinear: contact loss, back-flank contact) of "
     << report["scene"].get<std::string>() << ": " << points.size()
     << " points, H = " << report["harmonics"].get<int>();
  if (report["period_multiple"].get<int>() > 1) {
    os << " of f_mesh/" << report["period_multiple"].get<int>();
  }
  os << ", stability " << report["stability"].get<std::string>() << ", status "
     << report["status"].get<std::string>() << "\n";
  const std::size_t stride = (points.size() + kMaxTableRows - 1) / kMaxTableRows;
  char line[320];
  std::snprintf(line, sizeof(line), "%12s %6s %-8s %10s  %-16s %11s %11s %11s %11s %11s %6s\n",
                "f_mesh [Hz]", "branch", "stable", "max|mu|", "mesh", "RMS DTE[um]", "p-p DTE[um]",
                "mean F [N]", "min F [N]", "max F [N]", "loss");
  os << line;
  std::vector<std::size_t> rows;  // every stride-th point and the last one
  for (std::size_t i = 0; i < points.size(); i += std::max<std::size_t>(stride, 1))
    rows.push_back(i);
  if (!points.empty() && rows.back() + 1 != points.size()) rows.push_back(points.size() - 1);
  for (const std::size_t i : rows) {
    const auto& p = points[i];
    // max|μ|: "-" when not computed (--stability none) or not finite.
    char multiplier[32] = "-";
    if (p["max_multiplier"].is_number()) {
      std::snprintf(multiplier, sizeof(multiplier), "%.6f", Get(p["max_multiplier"]));
    }
    for (const auto& m : p["meshes"]) {
      std::snprintf(line, sizeof(line),
                    "%12.2f %6d %-8s %10s  %-16s %11.5g %11.5g %11.5g %11.5g %11.5g %5.1f%%%s\n",
                    Get(p["mesh_frequency_hz"]), p["branch"].get<int>(),
                    p["verdict"] == "stable"         ? "yes"
                    : p["verdict"] == "unstable"     ? "no"
                    : p["verdict"] == "not computed" ? "-"
                                                     : "undetermined",
                    multiplier, m["name"].get<std::string>().c_str(), 1e6 * Get(m["rms_dte_m"]),
                    1e6 * Get(m["peak_to_peak_dte_m"]), Get(m["mean_force_n"]),
                    Get(m["min_force_n"]), Get(m["max_force_n"]),
                    100.0 * Get(m["contact_loss_fraction"]),
                    p["status"].get<std::string>() == "success" ? "" : "  (!)");
      os << line;
    }
  }
  if (!report["folds_hz"].empty()) {
    os << "folds [Hz] (estimated error of locating each):";
    const json& errors = report["fold_errors_hz"];
    for (size_t i = 0; i < report["folds_hz"].size(); ++i) {
      os << " " << Text(Get(report["folds_hz"][i]));
      if (i < errors.size()) os << " (±" << Text(Get(errors[i])) << ")";
    }
    os << "\n";
  }
  if (report["jumps"].empty()) {
    os << "jumps: none in the traced range\n";
  } else {
    os << "jumps (first mesh):\n";
    for (const auto& j : report["jumps"]) {
      std::snprintf(line, sizeof(line), "  %-4s sweep at %10.2f Hz: RMS DTE %.5g um -> ",
                    j["direction"].get<std::string>().c_str(), Get(j["mesh_frequency_hz"]),
                    1e6 * Get(j["rms_dte_before_m"]));
      os << line;
      // No landing value: every traced branch at this frequency is unstable (or none is
      // traced), so the sweep lands on a response that is not a stable T-periodic orbit of
      // this basis (subharmonic, quasi-periodic or an untraced branch).
      if (j["rms_dte_after_m"].is_number()) {
        std::snprintf(line, sizeof(line), "%.5g um", 1e6 * Get(j["rms_dte_after_m"]));
        os << line;
        // Several stable branches here: the transient decides (issue 13: the integration of
        // the spur pair with backlash lands on the farther one).
        const auto& landings = j["rms_dte_landings_m"];
        if (landings.is_array() && landings.size() > 1) {
          os << " or";
          for (size_t k = 1; k < landings.size(); ++k) {
            std::snprintf(line, sizeof(line), " %.5g um", 1e6 * Get(landings[k]));
            os << line;
          }
          os << " (" << landings.size() << " stable branches at this frequency: which one a "
             << "sweep lands on depends on the transient)";
        }
        os << "\n";
      } else {
        os << "no stable periodic response traced at this frequency\n";
      }
    }
  }
  if (!report["message"].get<std::string>().empty()) {
    os << "message: " << report["message"].get<std::string>() << "\n";
  }
  for (const auto& w : report["warnings"]) os << "warning: " << w.get<std::string>() << "\n";
  return os.str();
}

std::string RenderNhbPlot(const SystemNhbCurve& curve, const std::string& title,
                          bool stability_computed) {
  static const std::string kCurveColour = "#1f77b4";
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "mesh frequency [Hz]";
  PlotPanel panel;
  const bool has_mesh = !curve.points.empty() && !curve.points.front().meshes.empty();
  panel.y_label =
      "RMS DTE [µm]" + (has_mesh ? " (" + curve.points.front().meshes.front().name + ")" : "");
  if (has_mesh) {
    // Runs of equal stability; a new run starts at the last point of the previous one so that
    // the curve stays connected. A point that did not converge breaks the curve.
    bool have_previous = false;
    bool labelled_stable = false, labelled_unstable = false;
    double previous_x = 0.0, previous_y = 0.0;
    int previous_segment = 0;
    for (const SystemNhbPoint& r : curve.points) {
      // A branch-search segment is not joined to the point before it.
      if (!PointOk(r) || r.point.segment != previous_segment) have_previous = false;
      previous_segment = r.point.segment;
      if (!PointOk(r)) continue;
      const double x = r.mesh_frequency_hz, y = 1e6 * r.meshes.front().rms_dte;
      // Undetermined: dashed. Not computed (--stability none): solid, without a legend.
      const bool stable = !stability_computed || r.point.stable == FloquetVerdict::kStable;
      if (!have_previous || panel.series.back().dashed == stable) {
        PlotSeries run;
        run.colour = kCurveColour;
        run.dashed = !stable;
        bool& labelled = stable ? labelled_stable : labelled_unstable;
        if (!labelled && stability_computed) run.label = stable ? "stable" : "unstable (dashed)";
        labelled = true;
        if (have_previous) {
          run.x.push_back(previous_x);
          run.y.push_back(previous_y);
        }
        panel.series.push_back(run);
      }
      panel.series.back().x.push_back(x);
      panel.series.back().y.push_back(y);
      previous_x = x;
      previous_y = y;
      have_previous = true;
    }
    for (const SystemNhbJump& j : curve.jumps) {
      const std::string colour = j.up_sweep ? "#d62728" : "#2ca02c";
      const double before = 1e6 * j.rms_dte_before, after = 1e6 * j.rms_dte_after;
      char label[64];
      std::snprintf(label, sizeof(label), "%s %.0f Hz", j.up_sweep ? "up" : "down",
                    j.mesh_frequency_hz);
      panel.markers.push_back({j.mesh_frequency_hz, before, label, colour});
      if (std::isfinite(after)) {
        PlotSeries arrow;
        arrow.colour = "#7f7f7f";
        arrow.x = {j.mesh_frequency_hz, j.mesh_frequency_hz};
        arrow.y = {before, after};
        panel.series.push_back(arrow);
        panel.markers.push_back({j.mesh_frequency_hz, after, "", colour});
      }
    }
  }
  spec.panels.push_back(panel);
  return RenderSvg(spec);
}

}  // namespace geardyn::app
