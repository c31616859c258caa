// `geardyn campbell` front end and reports (campbell_report.hpp).
#include "geardyn/campbell_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/csv_cell.hpp"
#include "geardyn/models/system/speed_terms.hpp"
#include "geardyn/svg_plot.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

constexpr double kRadPerSecPerRpm = 2.0 * kPi / 60.0;
constexpr int kMaxCampbellSpeeds = 10000;

bool ParseNumber(const std::string& text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

std::vector<double> ParseSpeedRange(const std::string& spec, const char* flag) {
  std::vector<std::string> parts;
  std::stringstream ss(spec);
  for (std::string part; std::getline(ss, part, ':');) parts.push_back(part);
  double lo = 0.0;
  double hi = 0.0;
  double count = 0.0;
  GEARDYN_THROW_UNLESS(parts.size() == 3 && ParseNumber(parts[0], &lo) &&
                           ParseNumber(parts[1], &hi) && ParseNumber(parts[2], &count),
                       flag << ": '" << spec << "': expected lo:hi:n (rpm, rpm, count)");
  GEARDYN_THROW_UNLESS(std::isfinite(lo) && lo >= 0.0,
                       flag << ": lo must be a finite speed >= 0 [rpm], got " << lo);
  GEARDYN_THROW_UNLESS(std::isfinite(hi) && hi > lo,
                       flag << ": hi must be a finite speed > lo = " << lo << " [rpm], got " << hi);
  GEARDYN_THROW_UNLESS(
      count >= 2.0 && count <= kMaxCampbellSpeeds && count == std::floor(count),
      flag << ": n must be an integer in 2 … " << kMaxCampbellSpeeds << ", got " << count);
  const int n = static_cast<int>(count);
  std::vector<double> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / (n - 1);
  return out;
}

// Groups equal values (relative 1e-9), keeping the first name and counting the others.
struct Distinct {
  double value;
  std::string name;
  int count;
};
void AddDistinct(std::vector<Distinct>* list, double value, const std::string& name) {
  for (Distinct& d : *list) {
    if (std::abs(d.value - value) <= 1e-9 * std::max(d.value, value)) {
      ++d.count;
      return;
    }
  }
  list->push_back({value, name, 1});
}

std::string Fixed(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", digits, v);
  return buffer;
}

}  // namespace

CampbellSweep MakeCampbellSweep(const Scene& scene, const CampbellSettings& settings) {
  GEARDYN_THROW_UNLESS(!scene.oscillator,
                       scene.source << ": an oscillator scene has no speeds; campbell needs gears");
  GEARDYN_THROW_UNLESS(settings.speed.empty() != settings.carrier_speed.empty(),
                       "--speed, --carrier-speed: give exactly one of them (lo:hi:n rpm)");
  CampbellSweep sweep;
  double factor = 1.0;  // Ω_swept / s
  if (!settings.speed.empty()) {
    sweep.values_rpm = ParseSpeedRange(settings.speed, "--speed");
    sweep.kind = "operating_point";
    sweep.body = scene.operating_point.body;
  } else {
    sweep.values_rpm = ParseSpeedRange(settings.carrier_speed, "--carrier-speed");
    try {
      factor = std::abs(CarrierSpeedFactor(scene));
    } catch (const InvalidInput& e) {
      throw InvalidInput(std::string("--carrier-speed: ") + e.what());
    }
    sweep.kind = "carrier";
    for (const PlanetaryDef& set : scene.planetaries) {
      Scene unit = scene;
      unit.operating_point.speed = 1.0;
      if (std::abs(unit.GearSpeed(set.carrier)) == factor) {
        sweep.body = set.carrier;
        break;
      }
    }
  }
  sweep.rpm_per_reference = factor / kRadPerSecPerRpm;
  for (double rpm : sweep.values_rpm)
    sweep.reference_speeds.push_back(rpm / sweep.rpm_per_reference);
  return sweep;
}

std::vector<CampbellExcitation> MakeCampbellExcitations(const Scene& scene, int orders) {
  GEARDYN_THROW_UNLESS(orders >= 1 && orders <= 50,
                       "--orders: must be an integer in 1 … 50, got " << orders);
  Scene unit = scene;
  unit.operating_point.speed = 1.0;
  std::vector<Distinct> meshes;
  for (const MeshDef& mesh : scene.meshes) {
    const double hz = unit.MeshFrequencyHz(mesh);
    if (hz > 0.0) AddDistinct(&meshes, hz, mesh.name);
  }
  std::vector<Distinct> shafts;
  for (const GearDef& gear : scene.gears) {
    double omega = 0.0;
    try {
      omega = std::abs(unit.GearSpeed(gear.name));
    } catch (const InvalidInput&) {
      continue;  // not connected to the reference gear: no defined speed
    }
    if (omega > 0.0) AddDistinct(&shafts, omega / (2.0 * kPi), gear.name);
  }
  std::vector<CampbellExcitation> out;
  for (const Distinct& d : meshes) {
    const std::string name =
        "mesh '" + d.name + "'" + (d.count > 1 ? " (+" + std::to_string(d.count - 1) + ")" : "");
    for (int k = 1; k <= orders; ++k) {
      out.push_back({name + " ×" + std::to_string(k), "mesh", k, k * d.value});
    }
  }
  for (const Distinct& d : shafts) {
    const std::string name =
        "shaft '" + d.name + "'" + (d.count > 1 ? " (+" + std::to_string(d.count - 1) + ")" : "");
    out.push_back({name + " ×1", "shaft", 1, d.value});
  }
  return out;
}

json MakeCampbellReport(const std::string& scene_source, const CampbellSweep& sweep,
                        const std::vector<CampbellExcitation>& excitations,
                        const std::vector<std::string>& notes, const std::vector<int>& kept_tracks,
                        const CampbellResult& result) {
  const double to_rpm = sweep.rpm_per_reference;
  json report;
  report["scene"] = scene_source;
  report["sweep"] = {{"body", sweep.body}, {"kind", sweep.kind}, {"speeds_rpm", sweep.values_rpm}};
  report["terms"] = notes;
  report["status"] = StatusName(result.summary.status);
  report["message"] = result.summary.message;
  report["warnings"] = result.summary.warnings;
  report["num_rigid_body_modes"] = result.num_rigid_body_modes;
  report["deflated"] = result.deflated;
  std::map<int, int> index_of;  // result track → report track
  json tracks = json::array();
  for (int t : kept_tracks) {
    const CampbellTrack& track = result.tracks[static_cast<std::size_t>(t)];
    index_of[t] = static_cast<int>(tracks.size());
    json j = {{"index", tracks.size()},
              {"label", ToString(track.labels.front())},
              {"frequency_hz", track.frequency_hz},
              {"growth_rate", track.growth_rate},
              {"mac", track.mac}};
    std::vector<int> unstable(track.unstable.begin(), track.unstable.end());
    j["unstable"] = unstable;
    if (!track.planetary_labels.empty()) {
      j["planetary_label"] = ToString(track.planetary_labels.front());
      std::vector<std::string> per_speed;
      for (PlanetaryModeType p : track.planetary_labels) per_speed.push_back(ToString(p));
      j["planetary_labels"] = per_speed;
    }
    tracks.push_back(j);
  }
  report["tracks"] = tracks;
  json ex = json::array();
  for (const CampbellExcitation& e : excitations) {
    ex.push_back({{"name", e.name},
                  {"kind", e.kind},
                  {"order", e.order},
                  {"hz_per_rpm", e.hz_per_speed / to_rpm}});
  }
  report["excitations"] = ex;
  json crossings = json::array();
  for (const CampbellCrossing& c : result.crossings) {
    const auto it = index_of.find(c.track);
    if (it == index_of.end()) continue;
    crossings.push_back(
        {{"track", it->second},
         {"label", tracks[static_cast<std::size_t>(it->second)].value(
                       "planetary_label",
                       tracks[static_cast<std::size_t>(it->second)]["label"].get<std::string>())},
         {"excitation", excitations[static_cast<std::size_t>(c.excitation)].name},
         {"speed_rpm", c.speed * to_rpm},
         {"frequency_hz", c.frequency_hz}});
  }
  report["crossings"] = crossings;
  json instabilities = json::array();
  for (const CampbellInstability& u : result.instabilities) {
    std::vector<int> kept;
    for (int t : u.tracks) {
      if (const auto it = index_of.find(t); it != index_of.end()) kept.push_back(it->second);
    }
    if (kept.empty()) continue;
    instabilities.push_back({{"modes", kept},
                             {"kind", u.kind},
                             {"speed_begin_rpm", u.speed_begin * to_rpm},
                             {"speed_end_rpm", u.speed_end * to_rpm},
                             {"max_growth_rate", u.max_growth_rate}});
  }
  report["instabilities"] = instabilities;
  std::vector<double> critical;
  for (double s : result.static_critical_speeds) critical.push_back(s * to_rpm);
  report["static_critical_speeds_rpm"] = critical;
  report["counters"] = result.summary.counters;
  report["wall_time_s"] = result.summary.wall_time_s;
  return report;
}

std::string FormatCampbellText(const json& report) {
  std::ostringstream out;
  const auto& speeds = report["sweep"]["speeds_rpm"];
  const std::string body = report["sweep"]["body"].get<std::string>();
  out << "campbell: " << report["scene"].get<std::string>() << ", " << speeds.size()
      << " speeds of '" << body << "' from " << speeds.front().get<double>() << " to "
      << speeds.back().get<double>() << " rpm, " << report["tracks"].size() << " tracked modes";
  if (report["num_rigid_body_modes"].get<int>() > 0) {
    out << " (" << report["num_rigid_body_modes"].get<int>() << " rigid-body modes left out)";
  }
  out << "\n";
  for (const auto& note : report["terms"]) out << "  with " << note.get<std::string>() << "\n";
  out << "status: " << report["status"].get<std::string>();
  if (!report["message"].get<std::string>().empty()) {
    out << " (" << report["message"].get<std::string>() << ")";
  }
  out << "\n\n  mode  type            f at " << speeds.front().get<double>() << " rpm  f at "
      << speeds.back().get<double>() << " rpm  [Hz]\n";
  for (const auto& t : report["tracks"]) {
    std::string type = t["label"].get<std::string>();
    if (t.contains("planetary_label")) type = t["planetary_label"].get<std::string>();
    char line[160];
    std::snprintf(line, sizeof(line), "  %4d  %-14s %12.2f %16.2f%s\n", t["index"].get<int>(),
                  type.c_str(), t["frequency_hz"].front().get<double>(),
                  t["frequency_hz"].back().get<double>(),
                  std::find(t["unstable"].begin(), t["unstable"].end(), 1) != t["unstable"].end()
                      ? "  unstable"
                      : "");
    out << line;
  }
  const auto& instabilities = report["instabilities"];
  out << "\ninstabilities: " << (instabilities.empty() ? "none" : "") << "\n";
  for (const auto& u : instabilities) {
    std::string modes;
    for (const auto& t : u["modes"])
      modes += (modes.empty() ? "" : ", ") + std::to_string(t.get<int>());
    out << "  " << u["kind"].get<std::string>() << " (mode " << modes << ") from "
        << Fixed(u["speed_begin_rpm"].get<double>(), 1) << " to "
        << Fixed(u["speed_end_rpm"].get<double>(), 1) << " rpm (max growth rate "
        << u["max_growth_rate"].get<double>() << " 1/s)\n";
  }
  const auto& critical = report["static_critical_speeds_rpm"];
  if (!critical.empty()) {
    out << "zero-frequency (static critical) speeds of '" << body << "':";
    for (std::size_t i = 0; i < std::min<std::size_t>(critical.size(), 5); ++i) {
      out << " " << Fixed(critical[i].get<double>(), 1);
    }
    out << " rpm" << (critical.size() > 5 ? " …" : "") << "\n";
  }
  const auto& crossings = report["crossings"];
  out << "\ncrossings with the excitation orders: " << crossings.size() << "\n";
  constexpr std::size_t kShown = 40;
  for (std::size_t i = 0; i < std::min(crossings.size(), kShown); ++i) {
    const auto& c = crossings[i];
    char line[256];
    std::snprintf(line, sizeof(line), "  %10.1f rpm  %10.2f Hz  mode %3d (%s) × %s\n",
                  c["speed_rpm"].get<double>(), c["frequency_hz"].get<double>(),
                  c["track"].get<int>(), c["label"].get<std::string>().c_str(),
                  c["excitation"].get<std::string>().c_str());
    out << line;
  }
  if (crossings.size() > kShown) {
    out << "  … " << crossings.size() - kShown << " more (crossings.csv, --json)\n";
  }
  for (const auto& w : report["warnings"]) out << "warning: " << w.get<std::string>() << "\n";
  return out.str();
}

std::string FormatCampbellCsv(const json& report) {
  std::ostringstream out;
  out << "speed_rpm,mode,frequency_hz,growth_rate_per_s,mac,label,planetary_label,unstable\n";
  const auto& speeds = report["sweep"]["speeds_rpm"];
  for (std::size_t si = 0; si < speeds.size(); ++si) {
    for (const auto& t : report["tracks"]) {
      out << CsvNumber(speeds[si].get<double>()) << "," << t["index"].get<int>() << ","
          << CsvNumber(t["frequency_hz"][si].get<double>()) << ","
          << CsvNumber(t["growth_rate"][si].get<double>()) << ","
          << CsvNumber(t["mac"][si].get<double>()) << "," << t["label"].get<std::string>() << ","
          << (t.contains("planetary_labels") ? t["planetary_labels"][si].get<std::string>() : "")
          << "," << t["unstable"][si].get<int>() << "\n";
    }
  }
  return out.str();
}

std::string FormatCrossingsCsv(const json& report) {
  std::ostringstream out;
  out << "speed_rpm,frequency_hz,mode,label,excitation\n";
  for (const auto& c : report["crossings"]) {
    out << CsvNumber(c["speed_rpm"].get<double>()) << ","
        << CsvNumber(c["frequency_hz"].get<double>()) << "," << c["track"].get<int>() << ","
        << c["label"].get<std::string>() << ",\"" << c["excitation"].get<std::string>() << "\"\n";
  }
  return out.str();
}

std::string RenderCampbellSvg(const json& report) {
  const auto& speeds_json = report["sweep"]["speeds_rpm"];
  const std::vector<double> speeds = speeds_json.get<std::vector<double>>();
  PlotPanel panel;
  panel.y_label = "f [Hz]";
  double f_max = 0.0;
  for (const auto& t : report["tracks"]) {
    for (const auto& f : t["frequency_hz"]) f_max = std::max(f_max, f.get<double>());
  }
  f_max = std::max(f_max * 1.05, 1e-9);
  const double s_max = speeds.back();
  for (const auto& e : report["excitations"]) {
    const double h = e["hz_per_rpm"].get<double>();
    const double s_end = std::min(s_max, f_max / h);
    PlotSeries line;
    line.x = {0.0, s_end};
    line.y = {0.0, h * s_end};
    line.dashed = true;
    line.colour = e["kind"].get<std::string>() == "mesh" ? "#999999" : "#cccccc";
    panel.series.push_back(line);
  }
  std::size_t colour = 0;
  for (const auto& t : report["tracks"]) {
    PlotSeries stable;
    PlotSeries unstable;
    stable.colour = unstable.colour = PlotColour(colour++);
    unstable.dashed = true;
    const auto f = t["frequency_hz"].get<std::vector<double>>();
    const auto u = t["unstable"].get<std::vector<int>>();
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      const double nan = std::nan("");
      const bool bad = u[i] != 0;
      const bool bad_next = i + 1 < speeds.size() && u[i + 1] != 0;
      stable.x.push_back(speeds[i]);
      unstable.x.push_back(speeds[i]);
      stable.y.push_back(bad ? nan : f[i]);
      unstable.y.push_back(bad || bad_next ? f[i] : nan);
    }
    panel.series.push_back(stable);
    panel.series.push_back(unstable);
  }
  for (const auto& c : report["crossings"]) {
    panel.markers.push_back(
        {c["speed_rpm"].get<double>(), c["frequency_hz"].get<double>(), "", "#d62728"});
  }
  PlotSpec spec;
  spec.title = "Campbell diagram: " + report["scene"].get<std::string>() +
               " (dashed grey: excitation orders; dashed colour: unstable)";
  spec.x_label = "speed of '" + report["sweep"]["body"].get<std::string>() + "' [rpm]";
  spec.panels.push_back(panel);
  spec.panel_height = 480;
  return RenderSvg(spec);
}

}  // namespace geardyn::app
