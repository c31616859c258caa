#include "geardyn/simulate_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

#include "geardyn/csv_cell.hpp"
#include "geardyn/svg_plot.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

std::string Num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", v);
  return buffer;
}

// CSV cell: the number, or empty for NaN / ∞ (csv_cell.hpp).
std::string Cell(double v) { return CsvNumber(v); }

// JSON number or null (NaN and ∞ are not JSON).
json JsonNumber(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

double At(const std::vector<double>& v, std::size_t i) {
  return i < v.size() ? v[i] : std::numeric_limits<double>::quiet_NaN();
}

// Worst status of the points (the order of Status is by severity of the outcome: success first).
Status WorstStatus(const std::vector<SimulatePoint>& points, std::string* message) {
  Status worst = Status::kSuccess;
  for (const SimulatePoint& p : points) {
    if (p.point.status != Status::kSuccess && worst == Status::kSuccess) {
      worst = p.point.status;
      char where[96];
      std::snprintf(where, sizeof(where), "%s %.6g Hz, %.6g N·m: ", p.branch.c_str(),
                    p.point.mesh_frequency_hz, p.torque_nm);
      *message = where + p.point.message;
    }
  }
  return worst;
}

}  // namespace

const char* ToString(SimulateMode mode) {
  switch (mode) {
    case SimulateMode::kSingle:
      return "single";
    case SimulateMode::kIndependent:
      return "independent";
    case SimulateMode::kSweep:
      return "sweep";
  }
  return "?";
}

TimeSweepPoint ToSweepPoint(const TimeResponse& r) {
  TimeSweepPoint p;
  p.mesh_frequency_hz = r.mesh_frequency_hz;
  for (const MeshTimeHistory& m : r.meshes) {
    p.rms_dte.push_back(m.rms_dte);
    p.mean_dte.push_back(m.mean_dte);
    p.peak_to_peak_dte.push_back(m.peak_to_peak_dte);
    p.contact_loss_fraction.push_back(m.contact_loss_fraction);
  }
  p.periods = r.periods;
  p.steady = r.steady;
  // No balance without an integrated period (a run that failed before its first one).
  p.max_energy_error = r.energy.empty() ? std::nan("") : r.max_energy_error;
  p.status = r.summary.status;
  p.message = r.summary.message;
  return p;
}

json MakeSimulateReport(const SimulateRunInfo& info, const std::vector<std::string>& mesh_names,
                        const std::vector<SimulatePoint>& points,
                        const std::vector<std::string>& warnings, const TimeResponse* single,
                        const std::vector<std::pair<double, Summary>>& summaries) {
  json report;
  report["scene"] = info.scene;
  report["mode"] = ToString(info.mode);
  report["integrator"] = info.integrator;
  report["tolerance"] = info.tolerance;
  report["steady_tolerance"] = info.steady_tolerance;
  report["max_periods"] = info.max_periods;
  report["record_periods"] = info.record_periods;
  std::string message;
  Status status = WorstStatus(points, &message);
  if (info.interrupted) {
    status = Status::kInterrupted;
    if (message.empty()) message = "interrupted";
  }
  report["status"] = StatusName(status);
  report["message"] = message;
  report["interrupted"] = info.interrupted;
  report["warnings"] = warnings;
  report["meshes"] = mesh_names;
  json rows = json::array();
  for (const SimulatePoint& sp : points) {
    const TimeSweepPoint& p = sp.point;
    json meshes = json::array();
    for (std::size_t k = 0; k < mesh_names.size(); ++k) {
      meshes.push_back({{"name", mesh_names[k]},
                        {"rms_dte_m", JsonNumber(At(p.rms_dte, k))},
                        {"peak_to_peak_dte_m", JsonNumber(At(p.peak_to_peak_dte, k))},
                        {"mean_dte_m", JsonNumber(At(p.mean_dte, k))},
                        {"contact_loss_fraction", JsonNumber(At(p.contact_loss_fraction, k))}});
    }
    json row = {{"torque_nm", sp.torque_nm},
                {"branch", sp.branch},
                {"mesh_frequency_hz", p.mesh_frequency_hz},
                {"status", StatusName(p.status)},
                {"message", p.message},
                {"steady", ToString(p.steady)},
                {"periods", p.periods},
                {"max_energy_error", JsonNumber(p.max_energy_error)},
                {"meshes", meshes}};
    if (!sp.integrator.empty()) row["integrator"] = sp.integrator;
    if (sp.steps >= 0) row["steps"] = sp.steps;
    if (sp.events >= 0) row["events"] = sp.events;
    rows.push_back(row);
  }
  report["points"] = rows;
  if (single != nullptr) {
    const Summary& s = single->summary;
    report["run"] = {
        {"integrator", ToString(single->integrator_used)},
        {"steps", single->steps},
        {"events", single->events},
        {"periods", single->periods},
        {"period_meshes", single->period_meshes},
        {"steady", ToString(single->steady)},
        {"max_energy_error",
         single->energy.empty() ? json(nullptr) : JsonNumber(single->max_energy_error)},
        {"summary",
         {{"status", StatusName(s.status)},
          {"message", s.message},
          {"error_estimate", JsonNumber(s.error_estimate)},
          {"wall_time_s", s.wall_time_s},
          {"counters", s.counters},
          {"warnings", s.warnings}}}};
  }
  json sets = json::array();
  for (const auto& [torque, s] : summaries) {
    sets.push_back({{"torque_nm", torque},
                    {"status", StatusName(s.status)},
                    {"message", s.message},
                    {"error_estimate", JsonNumber(s.error_estimate)},
                    {"wall_time_s", s.wall_time_s},
                    {"counters", s.counters}});
  }
  report["summaries"] = sets;
  report["wall_time_s"] = info.wall_time_s;
  return report;
}

std::string FormatSimulateText(const json& report) {
  std::ostringstream out;
  out << "geardyn simulate: " << report["scene"].get<std::string>() << " ("
      << report["mode"].get<std::string>() << ", integrator "
      << report["integrator"].get<std::string>() << ")\n";
  const auto& names = report["meshes"];
  const std::string first = names.empty() ? "" : names[0].get<std::string>();
  char line[256];
  std::snprintf(line, sizeof(line), "%10s %-11s %12s %14s %14s %8s %-12s %11s\n", "torque",
                "branch", "f_mesh [Hz]", "RMS DTE [µm]", "p-p DTE [µm]", "periods", "steady",
                "energy err");
  out << line;
  for (const auto& p : report["points"]) {
    const auto& m = p["meshes"].empty() ? json() : p["meshes"][0];
    const auto um = [&](const char* key) {
      return m.is_null() || m[key].is_null() ? std::string("–") : Num(1e6 * m[key].get<double>());
    };
    const std::string energy =
        p["max_energy_error"].is_null() ? "–" : Num(p["max_energy_error"].get<double>());
    std::snprintf(line, sizeof(line), "%10s %-11s %12s %14s %14s %8d %-12s %11s",
                  Num(p["torque_nm"].get<double>()).c_str(), p["branch"].get<std::string>().c_str(),
                  Num(p["mesh_frequency_hz"].get<double>()).c_str(), um("rms_dte_m").c_str(),
                  um("peak_to_peak_dte_m").c_str(), p["periods"].get<int>(),
                  p["steady"].get<std::string>().c_str(), energy.c_str());
    out << line;
    if (p["status"] != "success") {
      out << "  " << p["status"].get<std::string>() << ": " << p["message"].get<std::string>();
    }
    out << "\n";
  }
  if (names.size() > 1) out << "(DTE of the first mesh, " << first << "; all meshes in --json)\n";
  if (report.contains("run")) {
    const auto& run = report["run"];
    const bool ran = run["steps"].get<long>() > 0;
    out << "integrator used: " << (ran ? run["integrator"].get<std::string>() : "none (no step)")
        << ", " << run["steps"].get<long>() << " steps, " << run["events"].get<long>()
        << " located contact events, " << Num(run["summary"]["wall_time_s"].get<double>()) << " s";
    const auto& counters = run["summary"]["counters"];
    if (counters.contains("rejected_steps")) {
      out << " (" << counters["rejected_steps"].get<long>() << " rejected steps";
      if (counters.contains("force_evaluations")) {
        out << ", " << counters["force_evaluations"].get<long>() << " force evaluations";
      }
      out << ")";
    }
    out << "\n";
  }
  out << "status: " << report["status"].get<std::string>();
  if (!report["message"].get<std::string>().empty()) {
    out << " (" << report["message"].get<std::string>() << ")";
  }
  out << "\n";
  for (const auto& w : report["warnings"]) out << "warning: " << w.get<std::string>() << "\n";
  return out.str();
}

std::string FormatSimulateSweepCsv(const std::vector<std::string>& mesh_names,
                                   const std::vector<SimulatePoint>& points) {
  std::ostringstream out;
  out << "torque_nm,branch,mesh_frequency_hz,status,steady,periods,max_energy_error";
  for (const std::string& m : mesh_names) {
    out << "," << m << ":rms_dte_m," << m << ":peak_to_peak_dte_m," << m << ":mean_dte_m," << m
        << ":contact_loss_fraction";
  }
  out << "\n";
  for (const SimulatePoint& sp : points) {
    const TimeSweepPoint& p = sp.point;
    out << Num(sp.torque_nm) << "," << sp.branch << "," << Num(p.mesh_frequency_hz) << ","
        << StatusName(p.status) << "," << ToString(p.steady) << "," << p.periods << ","
        << Cell(p.max_energy_error);
    for (std::size_t k = 0; k < mesh_names.size(); ++k) {
      out << "," << Cell(At(p.rms_dte, k)) << "," << Cell(At(p.peak_to_peak_dte, k)) << ","
          << Cell(At(p.mean_dte, k)) << "," << Cell(At(p.contact_loss_fraction, k));
    }
    out << "\n";
  }
  return out.str();
}

std::string FormatDteHistoryCsv(const TimeResponse& r, double initial_phase) {
  std::ostringstream out;
  out << "time_s,theta_rad";
  for (const MeshTimeHistory& m : r.meshes) {
    out << "," << m.name << ":dte_m";
    if (m.force.size() > 0) out << "," << m.name << ":force_n";
  }
  out << "\n";
  const double omega = 2.0 * std::numbers::pi * r.mesh_frequency_hz;
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    out << Num(r.time(i)) << "," << Num(initial_phase + omega * r.time(i));
    for (const MeshTimeHistory& m : r.meshes) {
      out << "," << (i < m.dte.size() ? Num(m.dte(i)) : "");
      if (m.force.size() > 0) out << "," << (i < m.force.size() ? Num(m.force(i)) : "");
    }
    out << "\n";
  }
  return out.str();
}

std::string FormatChannelHistoryCsv(const TimeResponse& r, int decimation) {
  Eigen::Index columns = 0;
  for (const MeshTimeHistory& m : r.meshes) columns = std::max(columns, m.channels.cols());
  if (columns == 0) return "";
  std::ostringstream out;
  out << "time_s";
  for (const MeshTimeHistory& m : r.meshes) {
    for (const std::string& c : m.channel_names) out << "," << m.name << ":" << c;
  }
  out << "\n";
  for (Eigen::Index j = 0; j < columns; ++j) {
    const Eigen::Index i = j * decimation;
    out << (i < r.time.size() ? Num(r.time(i)) : "");
    for (const MeshTimeHistory& m : r.meshes) {
      for (Eigen::Index c = 0; c < static_cast<Eigen::Index>(m.channel_names.size()); ++c) {
        out << "," << (c < m.channels.rows() && j < m.channels.cols() ? Num(m.channels(c, j)) : "");
      }
    }
    out << "\n";
  }
  return out.str();
}

std::string FormatElementForceCsv(const SystemModel& model, const TimeResponse& r) {
  if (r.element_forces.empty()) return "";
  static const char* kComponents[] = {"fx", "fy", "fz", "mx", "my", "mz"};
  std::ostringstream out;
  out << "time_s";
  for (std::size_t e = 0; e < r.element_forces.size(); ++e) {
    const std::string name =
        e < model.elements().size() ? model.elements()[e].name : "element" + std::to_string(e);
    for (Eigen::Index c = 0; c < r.element_forces[e].rows(); ++c) {
      out << "," << name << ":b" << c / 6 << ":" << kComponents[c % 6];
    }
  }
  out << "\n";
  for (Eigen::Index i = 0; i < r.time.size(); ++i) {
    out << Num(r.time(i));
    for (const MatrixX& f : r.element_forces) {
      for (Eigen::Index c = 0; c < f.rows(); ++c) out << "," << (i < f.cols() ? Num(f(c, i)) : "");
    }
    out << "\n";
  }
  return out.str();
}

std::string FormatEnergyCsv(const TimeResponse& r) {
  std::ostringstream out;
  out << "period,input_work_j,stored_change_j,dissipated_j,gross_flow_j,relative_error\n";
  for (std::size_t k = 0; k < r.energy.size(); ++k) {
    const EnergyBalancePeriod& e = r.energy[k];
    out << k << "," << Num(e.input_work) << "," << Num(e.stored_change) << "," << Num(e.dissipated)
        << "," << Num(e.gross_flow) << "," << Num(e.relative_error) << "\n";
  }
  return out.str();
}

std::string RenderSimulatePlot(const std::string& title, const std::vector<std::string>& mesh_names,
                               const std::vector<SimulatePoint>& points,
                               const std::vector<HbOverlay>& overlays) {
  static const std::string kUp = "#d62728", kDown = "#1f77b4", kOther = "#2ca02c",
                           kOverlay = "#7f7f7f";
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "mesh frequency [Hz]";
  // One panel per torque, in the order the torques first appear.
  std::vector<double> torques;
  for (const SimulatePoint& p : points) {
    if (std::find(torques.begin(), torques.end(), p.torque_nm) == torques.end()) {
      torques.push_back(p.torque_nm);
    }
  }
  for (const HbOverlay& o : overlays) {
    if (std::find(torques.begin(), torques.end(), o.torque_nm) == torques.end()) {
      torques.push_back(o.torque_nm);
    }
  }
  // The mesh goes into the title: a rotated y label longer than its panel would run into the
  // next panel's.
  if (!mesh_names.empty()) spec.title += ", mesh " + mesh_names.front();
  for (const double torque : torques) {
    PlotPanel panel;
    panel.y_label = "RMS DTE [µm]" + (torques.size() > 1 ? " at " + Num(torque) + " N·m" : "");
    for (const HbOverlay& o : overlays) {
      if (o.torque_nm != torque) continue;
      PlotSeries s;
      s.label = o.label;
      s.colour = kOverlay;
      s.x = o.frequency;
      for (const double y : o.rms_dte) s.y.push_back(1e6 * y);
      panel.series.push_back(s);
    }
    // One series per branch; a failed point breaks the line (NaN).
    for (const std::string branch : {"up", "down", "independent", "single"}) {
      PlotSeries s;
      s.colour = branch == "up" ? kUp : branch == "down" ? kDown : kOther;
      s.dashed = branch == "down";
      s.label = branch == "up"     ? "sweep up"
                : branch == "down" ? "sweep down (dashed)"
                                   : "time integration";
      for (const SimulatePoint& p : points) {
        if (p.torque_nm != torque || p.branch != branch) continue;
        const bool ok = p.point.status == Status::kSuccess && !p.point.rms_dte.empty();
        const double y = ok ? 1e6 * p.point.rms_dte.front() : std::nan("");
        s.x.push_back(p.point.mesh_frequency_hz);
        s.y.push_back(y);
        if (ok && branch == "up") panel.markers.push_back({s.x.back(), y, "", kUp});
        if (ok && branch != "up" && branch != "down") {
          panel.markers.push_back({s.x.back(), y, "", kOther});
        }
      }
      if (!s.x.empty()) panel.series.push_back(s);
    }
    spec.panels.push_back(panel);
  }
  if (spec.panels.empty()) spec.panels.emplace_back();
  return RenderSvg(spec);
}

}  // namespace geardyn::app
