#include "geardyn/hb_report.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "geardyn/common/check.hpp"
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

std::string Num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", v);
  return buffer;
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
                  const HbSweepResult& sweep, const std::vector<std::string>& scene_warnings) {
  json report;
  report["scene"] = scene_source;
  report["mode"] = "linear";
  report["harmonics"] = settings.harmonics;
  // The tolerance chooses H; with a fixed H it is not used (and not echoed).
  report["tolerance"] = settings.harmonics > 0 ? json(nullptr) : json(settings.tolerance);
  report["status"] = StatusName(sweep.summary.status);
  report["message"] = sweep.summary.message;
  json warnings = json::array();
  for (const std::string& w : scene_warnings) warnings.push_back("scene: " + w);
  for (const std::string& w : sweep.summary.warnings) warnings.push_back(w);
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
  for (const HbResult& r : sweep.points) {
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
    points.push_back(p);
  }
  report["points"] = points;
  report["wall_time_s"] = sweep.summary.wall_time_s;
  return report;
}

std::string FormatHbCsv(const HbSweepResult& sweep) {
  std::ostringstream os;
  os << "mesh_frequency_hz,harmonics,error_estimate,status";
  if (!sweep.points.empty()) {
    for (const HbMeshOutput& m : sweep.points.front().meshes) {
      os << "," << m.name << ":rms_dte_m," << m.name << ":peak_to_peak_dte_m," << m.name
         << ":mean_dte_m";
      for (int h = 1; h <= kCsvHarmonics; ++h) os << "," << m.name << ":a" << h << "_m";
      os << "," << m.name << ":rms_force_n";
    }
  }
  os << "\n";
  for (const HbResult& r : sweep.points) {
    os << Num(r.mesh_frequency_hz) << "," << r.harmonics << "," << Num(r.summary.error_estimate)
       << "," << StatusName(r.summary.status);
    for (const HbMeshOutput& m : r.meshes) {
      os << "," << Num(m.rms_dte) << "," << Num(m.peak_to_peak_dte) << "," << Num(m.mean_dte);
      for (int h = 1; h <= kCsvHarmonics; ++h) {
        os << ",";
        if (h < m.dte_amplitudes.size()) os << Num(m.dte_amplitudes(h));
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
  std::snprintf(line, sizeof(line), "%12s %4s  %-24s %12s %12s %12s\n", "f_mesh [Hz]", "H", "mesh",
                "RMS DTE [um]", "p-p [um]", "RMS F [N]");
  os << line;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const auto& p = points[i];
    for (const auto& m : p["meshes"]) {
      std::snprintf(line, sizeof(line), "%12.2f %4d  %-24s %12.5g %12.5g %12.5g%s\n",
                    p["mesh_frequency_hz"].get<double>(), p["harmonics"].get<int>(),
                    m["name"].get<std::string>().c_str(), 1e6 * m["rms_dte_m"].get<double>(),
                    1e6 * m["peak_to_peak_dte_m"].get<double>(), m["rms_force_n"].get<double>(),
                    p["status"].get<std::string>() == "success" ? "" : "  (!)");
      os << line;
    }
  }
  if (!report["message"].get<std::string>().empty()) {
    os << "message: " << report["message"].get<std::string>() << "\n";
  }
  for (const auto& w : report["warnings"]) os << "warning: " << w.get<std::string>() << "\n";
  return os.str();
}

std::string RenderHbPlot(const HbSweepResult& sweep, const std::string& title) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "mesh frequency [Hz]";
  PlotPanel panel;
  panel.y_label = "RMS DTE [um]";
  const std::size_t meshes = sweep.points.empty() ? 0 : sweep.points.front().meshes.size();
  for (std::size_t k = 0; k < meshes; ++k) {
    PlotSeries series;
    series.label = sweep.points.front().meshes[k].name;
    for (const HbResult& r : sweep.points) {
      series.x.push_back(r.mesh_frequency_hz);
      series.y.push_back(r.summary.ok() ? 1e6 * r.meshes[k].rms_dte
                                        : std::numeric_limits<double>::quiet_NaN());
    }
    panel.series.push_back(series);
  }
  spec.panels.push_back(panel);
  return RenderSvg(spec);
}

}  // namespace geardyn::app
