// `geardyn hb` on a scene with several mesh frequencies (hb_quasi_periodic.hpp).
#include "geardyn/hb_quasi_periodic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geardyn/analyses/quasi_periodic_hb.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/hb_report.hpp"
#include "geardyn/interrupt.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

constexpr int kFirstOrder = 8;  // the tolerance search's first total order (after H/2 = 4)
// Without --tolerance: 2 % on the RMS DTE from H/2 to H (the change measures the error of H/2;
// H's own is far smaller: on the two-stage example 1.2 % from H = 4 to 8, then 0.06 % from 8 to
// 12, docs/benchmarks.md). The periodic path's 1e-4 would push a gearbox with ISO stiffness of
// ~10³ harmonics per mesh to H = 32 and beyond, minutes to hours per point.
constexpr double kDefaultTolerance = 2e-2;
// The search stops (tolerance_not_met, with the order reached) before an order whose factors
// would need more than this, even under the memory limit: H = 16 on the 48-DOF two-stage train
// is ~1 GB and a minute per point; --harmonics goes beyond it on request.
constexpr double kSearchBudgetBytes = 5e8;
constexpr int kReportedLines = 8;  // DTE lines per mesh and point in the JSON
constexpr int kTextLines = 5;      // ... and in the text of a one-frequency run

// The HbResult the periodic path's CSV, plot and report read (DTE, mesh force; no elements).
HbResult ToHbResult(const QuasiPeriodicHbResult& qp) {
  HbResult r;
  r.summary = qp.summary;
  r.mesh_frequency_hz = qp.mesh_frequency_hz;
  r.harmonics = qp.total_order;
  r.highest_harmonic = qp.total_order;
  r.reciprocal_condition = qp.reciprocal_condition;
  r.time_samples = qp.samples_per_base;
  for (const QuasiPeriodicMeshOutput& m : qp.meshes) {
    HbMeshOutput out;
    out.name = m.name;
    out.mean_dte = m.mean_dte;
    out.rms_dte = m.rms_dte;
    out.peak_to_peak_dte = m.peak_to_peak_dte;
    out.mean_force = m.mean_force;
    out.rms_force = m.rms_force;
    out.peak_to_peak_force = m.peak_to_peak_force;
    // dte_amplitudes(h): the mesh's own mesh order h (κ = h·P_b e_b of its base).
    out.dte_amplitudes = VectorX::Zero(kCsvHarmonics + 1);
    out.dte_amplitudes(0) = std::abs(m.mean_dte);
    const std::int64_t P = qp.bases[static_cast<std::size_t>(m.base)].period_meshes;
    for (const QuasiPeriodicLine& line : m.lines) {
      bool own_axis = true;
      for (std::size_t b = 0; b < line.order.size(); ++b) {
        if (static_cast<int>(b) != m.base && line.order[b] != 0) own_axis = false;
      }
      const int k = line.order[static_cast<std::size_t>(m.base)];
      if (!own_axis || k <= 0 || k % P != 0 || k / P > kCsvHarmonics) continue;
      out.dte_amplitudes(k / P) = line.amplitude;
    }
    r.meshes.push_back(std::move(out));
  }
  return r;
}

// The largest relative change of the RMS DTE between two solutions (relative to the largest).
double RmsChange(const QuasiPeriodicHbResult& a, const QuasiPeriodicHbResult& b) {
  double scale = 0.0, change = 0.0;
  for (std::size_t k = 0; k < a.meshes.size(); ++k) {
    scale = std::max(scale, b.meshes[k].rms_dte);
    change = std::max(change, std::abs(a.meshes[k].rms_dte - b.meshes[k].rms_dte));
  }
  return scale > 0.0 ? change / scale : 0.0;
}

// One point: a fixed H, or H = 8, 16, … until the RMS settles to `tolerance`.
QuasiPeriodicHbResult SolvePoint(const SystemModel& model, double f_m, int harmonics,
                                 double tolerance) {
  QuasiPeriodicHbOptions options;
  if (harmonics > 0) {
    options.total_order = harmonics;
    return SolveQuasiPeriodicHb(model, f_m, options);
  }
  options.total_order = kFirstOrder / 2;
  QuasiPeriodicHbResult previous = SolveQuasiPeriodicHb(model, f_m, options);
  double last_change = 0.0;
  while (true) {
    QuasiPeriodicHbOptions next = options;
    next.total_order = 2 * options.total_order;
    if (next.total_order > kMaxQuasiPeriodicOrder ||
        EstimateQuasiPeriodicHbBytes(model, next) > kSearchBudgetBytes) {
      previous.summary.status = Status::kToleranceNotMet;
      std::ostringstream why;
      why << "quasi-periodic harmonic balance: the RMS DTE changed by " << last_change
          << " from H = " << options.total_order / 2 << " to " << options.total_order
          << ", above the tolerance " << tolerance
          << ", and the search stops before H = " << next.total_order << " (about "
          << EstimateQuasiPeriodicHbBytes(model, next) / 1e9
          << " GB of factors); give --harmonics for a higher order, or a looser --tolerance";
      previous.summary.message = why.str();
      previous.summary.error_estimate = last_change;
      return previous;
    }
    options = next;
    QuasiPeriodicHbResult current = SolveQuasiPeriodicHb(model, f_m, options);
    if (!current.summary.ok() || !previous.summary.ok()) return current;
    last_change = RmsChange(current, previous);
    current.summary.error_estimate = last_change;
    if (last_change <= tolerance) return current;
    previous = std::move(current);
  }
}

std::string OrderText(const std::vector<int>& order) {
  std::string s = "(";
  for (std::size_t b = 0; b < order.size(); ++b) s += (b ? ", " : "") + std::to_string(order[b]);
  return s + ")";
}

}  // namespace

HbRun RunQuasiPeriodicHb(const HbRunSettings& opts, const Scene& scene, const SceneSystem& built,
                         const std::vector<double>& frequencies, const std::string& out_dir,
                         const ProgressLine& progress) {
  const HbSettings& settings = opts.settings;
  GEARDYN_THROW_UNLESS(settings.harmonics == 0 || !opts.tolerance_given,
                       "--tolerance: chooses the total order (H = 8, 16, ... until the RMS DTE "
                       "changes by at most the tolerance) and is not used with a fixed "
                       "--harmonics "
                           << settings.harmonics << "; give one of them");
  GEARDYN_THROW_UNLESS(settings.harmonics >= 0 && settings.harmonics <= kMaxQuasiPeriodicOrder,
                       "--harmonics: the total order of the quasi-periodic harmonic balance must "
                       "be in [1, "
                           << kMaxQuasiPeriodicOrder << "], got " << settings.harmonics);
  GEARDYN_THROW_UNLESS(std::isfinite(settings.tolerance) && settings.tolerance > 0.0,
                       "--tolerance: must be > 0, got " << settings.tolerance);
  const SystemModel& model = built.model;
  QuasiPeriodicHbOptions probe;
  if (settings.harmonics > 0) {
    probe.total_order = settings.harmonics;
    // Refused here, before any point, with the estimate (exit code 2).
    const double bytes = EstimateQuasiPeriodicHbBytes(model, probe);
    GEARDYN_THROW_UNLESS(
        bytes <= probe.memory_limit_bytes,
        "--harmonics: a total order of "
            << settings.harmonics << " on the " << FindQuasiPeriodicBases(model, 1.0, probe).size()
            << " mesh frequencies of this scene would need about " << bytes / 1e9 << " GB (limit "
            << probe.memory_limit_bytes / 1e9 << " GB); lower --harmonics");
  }
  std::vector<QuasiPeriodicHbResult> results;
  HbSweepResult sweep;
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    if (Interrupted()) {
      sweep.summary.status = Status::kInterrupted;
      sweep.summary.message = "interrupted";
      break;
    }
    results.push_back(SolvePoint(model, frequencies[i], settings.harmonics,
                                 opts.tolerance_given ? settings.tolerance : kDefaultTolerance));
    const QuasiPeriodicHbResult& r = results.back();
    sweep.points.push_back(ToHbResult(r));
    sweep.summary.wall_time_s += r.summary.wall_time_s;
    sweep.summary.error_estimate = std::max(sweep.summary.error_estimate, r.summary.error_estimate);
    if (!r.summary.ok() && sweep.summary.ok()) {
      sweep.summary.status = r.summary.status;
      sweep.summary.message = r.summary.message;
    }
    for (const std::string& w : r.summary.warnings) {
      if (std::find(sweep.summary.warnings.begin(), sweep.summary.warnings.end(), w) ==
          sweep.summary.warnings.end()) {
        sweep.summary.warnings.push_back(w);
      }
    }
    if (settings.progress && progress &&
        (i + 1 == frequencies.size() ||
         (i + 1) % std::max<std::size_t>(1, frequencies.size() / 20) == 0)) {
      progress("geardyn hb: " + std::to_string(i + 1) + "/" + std::to_string(frequencies.size()) +
               " mesh frequencies (quasi-periodic)\n");
    }
  }
  const std::string note =
      "no Floquet verdicts: the meshes run at several frequencies (the points are not verified "
      "stable); `geardyn floquet` forms the monodromy over their common period when the ratios "
      "are rational, at a cost of that many mesh cycles per frequency";
  sweep.summary.warnings.push_back(note);

  nlohmann::json report = MakeHbReport(scene.source, settings, sweep, built.warnings, nullptr);
  report["mode"] = "linear, quasi-periodic";
  report["stability_note"] = note;
  json bases = json::array();
  if (!results.empty()) {
    for (const QuasiPeriodicBase& b : results.front().bases) {
      json names = json::array();
      for (int k : b.meshes) names.push_back(model.meshes()[static_cast<std::size_t>(k)].name);
      bases.push_back({{"phase_ratio", b.phase_ratio},
                       {"period_meshes", b.period_meshes},
                       {"frequency_hz", b.frequency_hz},
                       {"meshes", names}});
    }
  }
  report["quasi_periodic"] = {{"bases", bases},
                              {"truncation", "total order |k|_1 <= H (harmonics column)"}};
  for (std::size_t i = 0; i < results.size(); ++i) {
    json& p = report["points"][i];
    p["method"] = "quasi_periodic";
    p["unknowns"] = results[i].summary.counters.count("unknowns")
                        ? results[i].summary.counters.at("unknowns")
                        : 0;
    for (std::size_t k = 0; k < results[i].meshes.size(); ++k) {
      const QuasiPeriodicMeshOutput& m = results[i].meshes[k];
      json lines = json::array();
      for (std::size_t l = 0; l < m.lines.size() && l < kReportedLines; ++l) {
        lines.push_back({{"order", m.lines[l].order},
                         {"frequency_hz", m.lines[l].frequency_hz},
                         {"amplitude_m", m.lines[l].amplitude}});
      }
      p["meshes"][k]["base"] = m.base;
      p["meshes"][k]["lines"] = lines;
      // The periodic path's harmonics of one mesh frequency do not exist here: own orders only.
      p["meshes"][k]["dte_amplitudes_note"] = "amplitudes of the mesh's own mesh orders";
    }
  }

  std::ostringstream text;
  text << FormatHbText(report);
  text << "quasi-periodic: " << bases.size() << " mesh frequencies (bases)";
  if (!results.empty()) {
    text << " at f_mesh = " << results.front().mesh_frequency_hz << " Hz of the first:";
    for (std::size_t b = 0; b < bases.size(); ++b) {
      std::string names;
      for (const auto& n : bases[b]["meshes"])
        names += (names.empty() ? "" : ", ") + n.get<std::string>();
      char line[160];
      std::snprintf(line, sizeof(line), "\n  base %zu: ratio %.6g, %.6g Hz (%s)", b,
                    bases[b]["phase_ratio"].get<double>(), bases[b]["frequency_hz"].get<double>(),
                    names.c_str());
      text << line;
    }
  }
  text << "\n";
  if (results.size() == 1 && results.front().summary.ok()) {
    text << "largest DTE lines (order per base, frequency, amplitude):\n";
    for (const QuasiPeriodicMeshOutput& m : results.front().meshes) {
      text << "  " << m.name << ":";
      for (std::size_t l = 0; l < m.lines.size() && l < kTextLines; ++l) {
        char line[96];
        std::snprintf(line, sizeof(line), " %s %.1f Hz %.4g um;",
                      OrderText(m.lines[l].order).c_str(), m.lines[l].frequency_hz,
                      1e6 * m.lines[l].amplitude);
        text << line;
      }
      text << "\n";
    }
  }
  if (!out_dir.empty()) {
    WriteOutputFile(out_dir, "hb.json", report.dump(2) + "\n");
    WriteOutputFile(out_dir, "hb.csv", FormatHbCsv(sweep, nullptr));
    WriteOutputFile(out_dir, "hb_rms_dte.svg",
                    RenderHbPlot(sweep,
                                 "RMS DTE (quasi-periodic linear harmonic balance, no stability "
                                 "verdict): " +
                                     scene.source,
                                 nullptr));
  }
  HbRun run;
  run.report = std::move(report);
  run.text = text.str();
  run.exit_code = sweep.summary.ok()                             ? int{kExitOk}
                  : sweep.summary.status == Status::kInterrupted ? int{kExitInterrupted}
                                                                 : int{kExitNumericalIssue};
  return run;
}

}  // namespace geardyn::app
