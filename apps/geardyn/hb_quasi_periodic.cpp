// `geardyn hb` on a scene with several mesh frequencies (hb_quasi_periodic.hpp).
#include "geardyn/hb_quasi_periodic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "geardyn/analyses/nonlinear_quasi_periodic_hb.hpp"
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

// One point of either model: the torus result, and for the nonlinear model the contact.
struct QpPoint {
  QuasiPeriodicHbResult torus;
  std::vector<NonlinearQuasiPeriodicMeshContact> contact;  // empty for the linear model
  int newton_iterations = 0;
  std::string initial_guess;
};

// Solves one point at total order H: the linear model, or the nonlinear one from the previous
// frequency's solution at the same H (`guesses`, updated).
QpPoint SolveAtOrder(const SystemModel& model, double f_m, int H, bool nonlinear,
                     std::map<int, MatrixXc>* guesses) {
  QpPoint point;
  if (!nonlinear) {
    QuasiPeriodicHbOptions options;
    options.total_order = H;
    point.torus = SolveQuasiPeriodicHb(model, f_m, options);
    return point;
  }
  NonlinearQuasiPeriodicHbOptions options;
  options.torus.total_order = H;
  const auto it = guesses->find(H);
  NonlinearQuasiPeriodicHbResult r = SolveNonlinearQuasiPeriodicHb(
      model, f_m, options, it == guesses->end() ? nullptr : &it->second);
  if (r.torus.summary.ok()) (*guesses)[H] = r.coordinate_harmonics;
  point.torus = std::move(r.torus);
  point.contact = std::move(r.contact);
  point.newton_iterations = r.newton_iterations;
  point.initial_guess = r.initial_guess;
  return point;
}

double EstimateBytes(const SystemModel& model, int H, bool nonlinear) {
  if (!nonlinear) {
    QuasiPeriodicHbOptions options;
    options.total_order = H;
    return EstimateQuasiPeriodicHbBytes(model, options);
  }
  NonlinearQuasiPeriodicHbOptions options;
  options.torus.total_order = H;
  return EstimateNonlinearQuasiPeriodicHbBytes(model, options);
}

// One point: a fixed H, or H = 8, 16, … (from first_order/2 … when tooth errors need more)
// until the RMS settles to `tolerance`.
QpPoint SolvePoint(const SystemModel& model, double f_m, int harmonics, double tolerance,
                   int first_order, bool nonlinear, std::map<int, MatrixXc>* guesses) {
  if (harmonics > 0) return SolveAtOrder(model, f_m, harmonics, nonlinear, guesses);
  int order = first_order;
  QpPoint previous = SolveAtOrder(model, f_m, order, nonlinear, guesses);
  double last_change = 0.0;
  while (true) {
    const int next = 2 * order;
    const double bytes =
        next > kMaxQuasiPeriodicOrder ? 0.0 : EstimateBytes(model, next, nonlinear);
    if (next > kMaxQuasiPeriodicOrder || bytes > kSearchBudgetBytes) {
      Summary& summary = previous.torus.summary;
      if (!summary.ok()) return previous;
      summary.status = Status::kToleranceNotMet;
      std::ostringstream why;
      why << "quasi-periodic harmonic balance: the RMS DTE changed by " << last_change
          << " from H = " << order / 2 << " to " << order << ", above the tolerance " << tolerance
          << ", and the search stops before H = " << next << " (about " << bytes / 1e9 << " GB"
          << (nonlinear ? " for the dense Newton matrix" : " of factors")
          << "); give --harmonics for a higher order, or a looser --tolerance";
      summary.message = why.str();
      summary.error_estimate = last_change;
      return previous;
    }
    order = next;
    QpPoint current = SolveAtOrder(model, f_m, order, nonlinear, guesses);
    if (!current.torus.summary.ok() || !previous.torus.summary.ok()) return current;
    last_change = RmsChange(current.torus, previous.torus);
    current.torus.summary.error_estimate = last_change;
    if (last_change <= tolerance) return current;
    previous = std::move(current);
  }
}

// Appends per-mesh contact columns to the CSV of FormatHbCsv (one row per point, in order).
std::string AppendContactColumns(const std::string& csv, const SystemModel& model,
                                 const std::vector<QpPoint>& points) {
  std::istringstream in(csv);
  std::ostringstream out;
  std::string line;
  std::size_t row = 0;
  while (std::getline(in, line)) {
    out << line;
    if (row == 0) {
      for (const SystemMesh& m : model.meshes()) {
        out << "," << m.name << ":contact_loss_fraction," << m.name << ":min_force_n," << m.name
            << ":max_force_n";
      }
    } else if (row - 1 < points.size()) {
      const QpPoint& p = points[row - 1];
      for (std::size_t k = 0; k < static_cast<std::size_t>(model.num_meshes()); ++k) {
        if (k < p.contact.size() && p.torus.summary.ok()) {
          char cells[96];
          std::snprintf(cells, sizeof(cells), ",%.6g,%.6g,%.6g", p.contact[k].contact_loss_fraction,
                        p.contact[k].min_force, p.contact[k].max_force);
          out << cells;
        } else {
          out << ",,,";
        }
      }
    }
    out << "\n";
    ++row;
  }
  return out.str();
}

std::string OrderText(const std::vector<int>& order) {
  std::string s = "(";
  for (std::size_t b = 0; b < order.size(); ++b) s += (b ? ", " : "") + std::to_string(order[b]);
  return s + ")";
}

}  // namespace

HbRun RunQuasiPeriodicHb(const HbRunSettings& opts, const Scene& scene, const SceneSystem& built,
                         const std::vector<double>& frequencies, const std::string& out_dir,
                         const ProgressLine& progress, bool nonlinear) {
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
    const double bytes = EstimateBytes(model, settings.harmonics, nonlinear);
    GEARDYN_THROW_UNLESS(bytes <= probe.memory_limit_bytes,
                         "--harmonics: a total order of "
                             << settings.harmonics << " on the "
                             << FindQuasiPeriodicBases(model, 1.0, probe).size()
                             << " mesh frequencies of this scene would need about " << bytes / 1e9
                             << " GB (limit " << probe.memory_limit_bytes / 1e9 << " GB"
                             << (nonlinear ? ", the nonlinear model's dense Newton matrix" : "")
                             << "); lower --harmonics");
  }
  // Tooth errors repeating every P mesh cycles put the mesh frequency at order P of its base.
  std::int64_t longest = 1;
  std::string longest_mesh;
  for (const QuasiPeriodicBase& b : FindQuasiPeriodicBases(model, 1.0, probe)) {
    if (b.period_meshes <= longest) continue;
    longest = b.period_meshes;
    for (int k : b.meshes) {
      const SystemMesh& mesh = model.meshes()[static_cast<std::size_t>(k)];
      if (PeriodMeshes(mesh.core) > 1) longest_mesh = mesh.name;
    }
  }
  if (longest > 1) {
    const std::string why =
        "--harmonics: the tooth errors of mesh '" + longest_mesh + "' repeat every " +
        std::to_string(longest) + " mesh cycles, so the total order counts harmonics of f_mesh/" +
        std::to_string(longest) + " on its base and the mesh frequency is order " +
        std::to_string(longest);
    const std::string remedy =
        "leave the tooth errors out of the multi-stage harmonic balance (`geardyn simulate` "
        "takes them)";
    GEARDYN_THROW_UNLESS(
        longest <= kMaxQuasiPeriodicOrder,
        why << ", above the largest total order " << kMaxQuasiPeriodicOrder << "; " << remedy);
    GEARDYN_THROW_UNLESS(settings.harmonics == 0 || settings.harmonics >= longest,
                         why << ": H = " << settings.harmonics << " would leave it out; give "
                             << "--harmonics " << longest << " or more, or " << remedy);
  }
  const int first_order = static_cast<int>(std::max<std::int64_t>(kFirstOrder / 2, longest));
  if (settings.harmonics == 0 && longest > 1) {
    const double bytes = EstimateBytes(model, first_order, nonlinear);
    GEARDYN_THROW_UNLESS(bytes <= kSearchBudgetBytes,
                         "--harmonics: the tooth errors of mesh '"
                             << longest_mesh << "' repeat every " << longest
                             << " mesh cycles, so the quasi-periodic harmonic balance needs a "
                                "total order of at least "
                             << longest << " (the mesh frequency's order on its base), about "
                             << bytes / 1e9
                             << " GB on this scene; leave the tooth errors out of the multi-stage "
                                "harmonic balance (`geardyn simulate` takes them), or give "
                                "--harmonics "
                             << longest << " to try");
  }
  std::vector<QpPoint> points;
  std::map<int, MatrixXc> guesses;  // the nonlinear solution per H at the previous frequency
  HbSweepResult sweep;
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    if (Interrupted()) {
      sweep.summary.status = Status::kInterrupted;
      sweep.summary.message = "interrupted";
      break;
    }
    points.push_back(SolvePoint(model, frequencies[i], settings.harmonics,
                                opts.tolerance_given ? settings.tolerance : kDefaultTolerance,
                                first_order, nonlinear, &guesses));
    const QuasiPeriodicHbResult& r = points.back().torus;
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
      nonlinear
          ? "no stability verdicts: a quasi-periodic response has no period, so the nonlinear "
            "points have no Floquet multipliers (they are not verified stable); `geardyn "
            "floquet` gives the parametric stability of the linear model (over the common "
            "period, or by rational approximants of incommensurate ratios)"
          : "no Floquet verdicts: the meshes run at several frequencies (the points are not "
            "verified stable); `geardyn floquet` gives the parametric stability over their "
            "common period, or by rational approximants of incommensurate ratios, at a cost of "
            "that many mesh cycles per frequency";
  sweep.summary.warnings.push_back(note);

  HbSettings shown = settings;  // the report's tolerance is the one the search used
  if (!opts.tolerance_given) shown.tolerance = kDefaultTolerance;
  nlohmann::json report = MakeHbReport(scene.source, shown, sweep, built.warnings, nullptr);
  report["mode"] = nonlinear ? "nonlinear, quasi-periodic" : "linear, quasi-periodic";
  report["stability_note"] = note;
  json bases = json::array();
  if (!points.empty()) {
    for (const QuasiPeriodicBase& b : points.front().torus.bases) {
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
  for (std::size_t i = 0; i < points.size(); ++i) {
    const QuasiPeriodicHbResult& result = points[i].torus;
    json& p = report["points"][i];
    p["method"] = nonlinear ? "quasi_periodic_nonlinear" : "quasi_periodic";
    p["unknowns"] =
        result.summary.counters.count("unknowns") ? result.summary.counters.at("unknowns") : 0;
    if (nonlinear) {
      p["newton_iterations"] = points[i].newton_iterations;
      p["initial_guess"] = points[i].initial_guess;
    }
    for (std::size_t k = 0; k < result.meshes.size(); ++k) {
      const QuasiPeriodicMeshOutput& m = result.meshes[k];
      if (k < points[i].contact.size()) {
        const NonlinearQuasiPeriodicMeshContact& c = points[i].contact[k];
        p["meshes"][k]["contact_loss_fraction"] = c.contact_loss_fraction;
        p["meshes"][k]["back_contact"] = c.back_contact;
        p["meshes"][k]["min_force_n"] = c.min_force;
        p["meshes"][k]["max_force_n"] = c.max_force;
      }
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
  if (!points.empty()) {
    text << " at f_mesh = " << points.front().torus.mesh_frequency_hz << " Hz of the first:";
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
  if (points.size() == 1 && points.front().torus.summary.ok()) {
    const QpPoint& point = points.front();
    if (nonlinear) {
      text << "contact (fraction of the torus without drive-flank contact, force range):\n";
      for (std::size_t k = 0; k < point.contact.size(); ++k) {
        char line[200];
        std::snprintf(line, sizeof(line), "  %s: loss %.4f, F_eta %.6g .. %.6g N%s\n",
                      point.torus.meshes[k].name.c_str(), point.contact[k].contact_loss_fraction,
                      point.contact[k].min_force, point.contact[k].max_force,
                      point.contact[k].back_contact ? ", back flank hit" : "");
        text << line;
      }
    }
    text << "largest DTE lines (order per base, frequency, amplitude):\n";
    for (const QuasiPeriodicMeshOutput& m : point.torus.meshes) {
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
    // The nonlinear model writes nhb.* as the periodic nonlinear path does.
    const std::string stem = nonlinear ? "nhb" : "hb";
    WriteOutputFile(out_dir, stem + ".json", report.dump(2) + "\n");
    const std::string csv = FormatHbCsv(sweep, nullptr);
    WriteOutputFile(out_dir, stem + ".csv",
                    nonlinear ? AppendContactColumns(csv, model, points) : csv);
    WriteOutputFile(out_dir, stem + "_rms_dte.svg",
                    RenderHbPlot(sweep,
                                 std::string("RMS DTE (quasi-periodic ") +
                                     (nonlinear ? "nonlinear" : "linear") +
                                     " harmonic balance, no stability verdict): " + scene.source,
                                 nullptr));
  }
  HbRun run;
  run.nonlinear = nonlinear;
  run.report = std::move(report);
  run.text = text.str();
  run.exit_code = sweep.summary.ok()                             ? int{kExitOk}
                  : sweep.summary.status == Status::kInterrupted ? int{kExitInterrupted}
                                                                 : int{kExitNumericalIssue};
  return run;
}

}  // namespace geardyn::app
