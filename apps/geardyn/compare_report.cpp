#include "geardyn/compare_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "geardyn/analyses/floquet_verdict.hpp"
#include "geardyn/csv_cell.hpp"
#include "geardyn/region_plot.hpp"
#include "geardyn/stability_chart_runner.hpp"
#include "geardyn/svg_plot.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMicro = 1e6;  // m → µm

json Finite(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json FiniteArray(const std::vector<double>& v) {
  json a = json::array();
  for (const double x : v) a.push_back(Finite(x));
  return a;
}

std::string Num(double v, const char* format = "%.6g") {
  if (!std::isfinite(v)) return "—";
  char b[48];
  std::snprintf(b, sizeof(b), format, v);
  return b;
}

std::string Pct(double v) { return std::isfinite(v) ? Num(100.0 * v, "%+.3g%%") : "—"; }

std::string Pad(const std::string& s, std::size_t width) {
  // Width in characters (UTF-8 continuation bytes do not count).
  std::size_t chars = 0;
  for (const unsigned char c : s) chars += (c & 0xC0) != 0x80;
  return chars >= width ? s + " " : s + std::string(width - chars, ' ');
}

const LevelComparison* ComparisonOf(const CompareResult& r, const std::string& level) {
  for (const LevelComparison& c : r.comparisons) {
    if (c.level == level) return &c;
  }
  return nullptr;
}

std::string Verdict(const LevelComparison* c, CompareAnalysis a) {
  if (c == nullptr) return "—";
  const auto it = c->verdict.find(a);
  return it == c->verdict.end() ? "—" : it->second;
}

std::string Reference(const CompareResult& r, CompareAnalysis a) {
  const auto it = r.reference.find(a);
  return it == r.reference.end() ? "" : it->second;
}

// The summary numbers of one level (NaN where not available).
struct LevelNumbers {
  double modes_max = kNaN;  // max |Δf/f| over matched modes
  double modes_in_plane = kNaN, modes_out_of_plane = kNaN;
  int absent = -1;
  double floquet = kNaN;  // max|λ| − reference's
  double dte_max = kNaN, dte_rms = kNaN, peak_shift = kNaN;
};

LevelNumbers NumbersOf(const LevelComparison* c) {
  LevelNumbers n;
  if (c == nullptr) return n;
  if (c->modes) {
    n.modes_max = c->modes->max_abs_relative_difference;
    n.absent = static_cast<int>(c->modes->matches.size()) - c->modes->num_matched;
    n.modes_in_plane = c->modes_max_in_plane;
    n.modes_out_of_plane = c->modes_max_out_of_plane;
  }
  if (c->floquet_difference) n.floquet = *c->floquet_difference;
  if (c->dte) {
    n.dte_max = c->dte->max_abs;
    n.dte_rms = c->dte->rms;
    if (c->dte->reference_peak_hz > 0.0) {
      n.peak_shift = (c->dte->peak_hz - c->dte->reference_peak_hz) / c->dte->reference_peak_hz;
    }
  }
  return n;
}

json ModesJson(const ModalResult& m, double time_s) {
  json labels = json::array();
  for (const ModeType t : m.labels) labels.push_back(ToString(t));
  return {{"frequencies_hz",
           FiniteArray(std::vector<double>(m.frequencies_hz.data(),
                                           m.frequencies_hz.data() + m.frequencies_hz.size()))},
          {"labels", labels},
          {"num_rigid_body_modes", m.num_rigid_body_modes},
          {"status", StatusName(m.summary.status)},
          {"message", m.summary.message},
          {"wall_time_s", time_s}};
}

json ComparisonJson(const LevelComparison& c, const LevelRun& run, const CompareResult& r) {
  json out;
  json verdict = json::object();
  for (const auto& [a, v] : c.verdict) {
    verdict[a == CompareAnalysis::kHb ? "dte" : ToString(a)] = v;
  }
  out["verdict"] = verdict;
  out["notes"] = c.notes;
  if (c.modes) {
    json modes = json::array(), absent = json::array(), extra = json::array();
    const LevelRun* ref = nullptr;
    for (const LevelRun& x : r.runs) {
      if (x.level == Reference(r, CompareAnalysis::kModes)) ref = &x;
    }
    for (const ModeMatch& m : c.modes->matches) {
      json row = {{"reference_mode", m.reference + 1},
                  {"reference_hz", m.reference_hz},
                  {"mode", m.other >= 0 ? json(m.other + 1) : json(nullptr)},
                  {"hz", Finite(m.other_hz)},
                  {"relative_difference", Finite(m.relative_difference)},
                  {"mac", Finite(m.mac)}};
      if (ref && ref->modes && m.reference < static_cast<int>(ref->modes->labels.size())) {
        row["type"] = ToString(ref->modes->labels[m.reference]);
      }
      modes.push_back(row);
      if (m.other < 0) absent.push_back(m.reference + 1);
    }
    for (const int j : c.modes->extra) {
      if (run.modes && j < run.modes->frequencies_hz.size()) {
        extra.push_back({{"mode", j + 1}, {"hz", run.modes->frequencies_hz(j)}});
      }
    }
    out["modes"] = modes;
    out["absent"] = absent;
    out["extra"] = extra;
    out["max_abs_relative_difference"] = Finite(c.modes->max_abs_relative_difference);
  }
  out["floquet_difference"] = c.floquet_difference ? Finite(*c.floquet_difference) : json(nullptr);
  if (c.dte) {
    const DteDifference& d = *c.dte;
    json ranges = json::array();
    for (const auto& [lo, hi] : d.disagree_ranges) ranges.push_back({lo, hi});
    out["dte"] = {{"max_abs", Finite(d.max_abs)},
                  {"max_at_hz", d.max_at_hz},
                  {"max_where", d.max_where},
                  {"rms", Finite(d.rms)},
                  {"peak_hz", d.peak_hz},
                  {"reference_peak_hz", d.reference_peak_hz},
                  {"peak_ratio", Finite(d.peak_ratio)},
                  {"missing", d.missing},
                  {"disagree_ranges_hz", ranges},
                  {"difference_up", FiniteArray(d.up)},
                  {"difference_down", FiniteArray(d.down)}};
  }
  return out;
}

}  // namespace

json MakeCompareReport(const CompareResult& r) {
  json report;
  report["scene"] = r.scene;
  report["mesh"] = r.mesh;
  report["operating_mesh_frequency_hz"] = r.operating_mesh_frequency_hz;
  json analyses = json::array();
  for (const CompareAnalysis a : r.settings.analyses) analyses.push_back(ToString(a));
  report["settings"] = {{"analyses", analyses},
                        {"reference", r.settings.reference},
                        {"modes", r.settings.num_modes},
                        {"mac_threshold", r.settings.mac_threshold},
                        {"frequency_tolerance", r.settings.frequency_tolerance},
                        {"dte_tolerance", r.settings.dte_tolerance},
                        {"nonlinear_harmonics", r.settings.nonlinear_harmonics}};
  report["references"] = {{"modes", Reference(r, CompareAnalysis::kModes)},
                          {"floquet", Reference(r, CompareAnalysis::kFloquet)},
                          {"dte", Reference(r, CompareAnalysis::kHb)}};
  report["frequencies_hz"] = r.frequencies_hz;
  report["dte_quantity"] =
      r.dimensionless ? "x of the oscillator (dimensionless; the *_m fields hold x)"
                      : "loaded transmission error delta_eta = g q along the tooth normal (RMS "
                        "of the alternating part, peak-to-peak) [m]";
  json levels = json::array();
  for (const LevelRun& run : r.runs) {
    json l;
    l["level"] = run.level;
    const CompareLevelInfo* info = FindCompareLevel(run.level);
    l["description"] = info ? info->description : "";
    l["num_dofs"] = run.num_dofs;
    json skipped = json::object();
    for (const auto& [a, why] : run.skipped) skipped[ToString(a)] = why;
    l["skipped"] = skipped;
    l["warnings"] = run.warnings;
    if (run.modes) l["modes"] = ModesJson(*run.modes, run.modes_time_s);
    if (run.floquet) {
      const FloquetResult& f = *run.floquet;
      l["floquet"] = {{"max_abs_multiplier", Finite(f.max_abs_multiplier)},
                      {"verdict", ToString(f.verdict)},
                      {"method", ToString(f.method_used)},
                      {"status", StatusName(f.summary.status)},
                      {"message", f.summary.message},
                      {"wall_time_s", run.floquet_time_s}};
    }
    if (run.dte) {
      const LevelDte& d = *run.dte;
      l["dte"] = {{"source", d.source},
                  {"status", StatusName(d.summary.status)},
                  {"message", d.summary.message},
                  {"wall_time_s", d.wall_time_s},
                  {"multivalued", d.multivalued},
                  {"rms_up_m", FiniteArray(d.rms_up)},
                  {"rms_down_m", FiniteArray(d.rms_down)},
                  {"peak_to_peak_up_m", FiniteArray(d.peak_to_peak_up)},
                  {"peak_to_peak_down_m", FiniteArray(d.peak_to_peak_down)},
                  {"jumps_hz", FiniteArray(d.jumps_hz)}};
      if (!d.curve_hz.empty()) {
        l["dte"]["curve"] = {{"hz", FiniteArray(d.curve_hz)},
                             {"rms_m", FiniteArray(d.curve_rms)},
                             {"stable", d.curve_stable},
                             {"segment", d.curve_segment}};
      }
    }
    if (run.chart) {
      const StabilityChartResult& c = *run.chart;
      long unstable = 0, undetermined = 0;
      for (std::size_t k = 0; k < c.stable.size(); ++k) {
        undetermined += !c.ok[k];
        unstable += c.ok[k] && !c.stable[k];
      }
      l["chart"] = {{"grid_points", static_cast<long>(c.stable.size())},
                    {"unstable_points", unstable},
                    {"undetermined_points", undetermined},
                    {"transition_curves", static_cast<long>(c.curves.size())},
                    {"status", StatusName(c.summary.status)},
                    {"wall_time_s", run.chart_time_s}};
    } else if (!run.chart_skipped.empty()) {
      l["chart"] = {{"skipped", run.chart_skipped}};
    }
    if (const LevelComparison* c = ComparisonOf(r, run.level)) {
      l["comparison"] = ComparisonJson(*c, run, r);
      l["comparison"]["chart_agreement"] = Finite(c->chart_agreement);
      l["comparison"]["chart_points"] = c->chart_points;
    }
    levels.push_back(l);
  }
  report["levels"] = levels;
  report["warnings"] = r.warnings;
  report["notes"] = r.notes;
  report["status"] = r.ok ? "success" : "numerical_issue";
  report["wall_time_s"] = r.wall_time_s;
  return report;
}

std::string FormatCompareText(const CompareResult& r) {
  std::ostringstream s;
  s << "compare: " << r.scene << ", mesh " << r.mesh
    << ", operating f_m = " << Num(r.operating_mesh_frequency_hz) << " Hz\n";
  const std::string ref_modes = Reference(r, CompareAnalysis::kModes);
  const std::string ref_floquet = Reference(r, CompareAnalysis::kFloquet);
  const std::string ref_dte = Reference(r, CompareAnalysis::kHb);
  s << "references: modes " << (r.reference.count(CompareAnalysis::kModes) ? ref_modes : "—")
    << ", floquet " << (r.reference.count(CompareAnalysis::kFloquet) ? ref_floquet : "—")
    << ", DTE " << (r.reference.count(CompareAnalysis::kHb) ? ref_dte : "—") << "\n\n";

  // Level table: verdicts, errors and wall times (what a simplification costs and saves).
  s << Pad("level", 19) << Pad("DOFs", 6) << Pad("modes", 13) << Pad("max|Δf/f|", 11)
    << Pad("floquet", 13) << Pad("max|λ|", 10) << Pad("DTE", 13) << Pad("max|ΔRMS|", 11)
    << Pad("DTE by", 14) << "time modes/floquet/DTE [s]\n";
  for (const LevelRun& run : r.runs) {
    const LevelComparison* c = ComparisonOf(r, run.level);
    const LevelNumbers n = NumbersOf(c);
    s << Pad(run.level, 19) << Pad(std::to_string(run.num_dofs), 6)
      << Pad(Verdict(c, CompareAnalysis::kModes), 13) << Pad(Pct(n.modes_max), 11)
      << Pad(Verdict(c, CompareAnalysis::kFloquet), 13)
      << Pad(run.floquet ? FormatMaxAbsMultiplier(run.floquet->max_abs_multiplier) : "—", 10)
      << Pad(Verdict(c, CompareAnalysis::kHb), 13) << Pad(Pct(n.dte_max), 11)
      << Pad(run.dte ? run.dte->source : "—", 14)
      << (run.modes ? Num(run.modes_time_s, "%.3g") : "—") << "/"
      << (run.floquet ? Num(run.floquet_time_s, "%.3g") : "—") << "/"
      << (run.dte ? Num(run.dte->wall_time_s, "%.3g") : "—") << "\n";
  }

  // Mode table.
  const LevelRun* ref = nullptr;
  for (const LevelRun& x : r.runs) {
    if (x.level == ref_modes) ref = &x;
  }
  if (ref && ref->modes) {
    s << "\nmodes matched by MAC (≥ " << Num(r.settings.mac_threshold, "%.2g")
      << ") to the reference " << ref_modes << ": Δf/f and MAC per level\n";
    s << Pad("#", 4) << Pad("type", 15) << Pad("f_ref [Hz]", 12);
    std::vector<const LevelComparison*> columns;
    for (const LevelRun& run : r.runs) {
      const LevelComparison* c = ComparisonOf(r, run.level);
      if (c && c->modes && run.level != ref_modes) {
        columns.push_back(c);
        s << Pad(run.level, 19);
      }
    }
    s << "\n";
    const int rows = static_cast<int>(
        std::min<Eigen::Index>(r.settings.num_modes, ref->modes->frequencies_hz.size()));
    for (int k = 0; k < rows; ++k) {
      s << Pad(std::to_string(k + 1), 4)
        << Pad(k < static_cast<int>(ref->modes->labels.size()) ? ToString(ref->modes->labels[k])
                                                               : "",
               15)
        << Pad(Num(ref->modes->frequencies_hz(k), "%.5g"), 12);
      for (const LevelComparison* c : columns) {
        const ModeMatch& m = c->modes->matches[k];
        s << Pad(m.other < 0 ? "absent (" + Num(m.mac, "%.2f") + ")"
                             : Pct(m.relative_difference) + " " + Num(m.mac, "%.3f"),
                 19);
      }
      s << "\n";
    }
  }

  s << "\nverdicts:\n";
  for (const LevelComparison& c : r.comparisons) {
    s << "* " << c.level;
    const bool is_reference = std::all_of(c.verdict.begin(), c.verdict.end(), [](const auto& v) {
      return v.second == "reference" || v.second == "skipped";
    });
    s << (is_reference && !c.verdict.empty() ? " (reference)" : "") << "\n";
    for (const std::string& note : c.notes) s << "    " << note << "\n";
  }
  for (const LevelRun& run : r.runs) {
    for (const std::string& w : run.warnings) s << "warning: " << run.level << ": " << w << "\n";
  }
  for (const std::string& n : r.notes) s << "note: " << n << "\n";
  for (const std::string& w : r.warnings) s << "warning: " << w << "\n";
  s << "status: " << (r.ok ? "success" : "numerical issue (see the verdicts)") << ", "
    << Num(r.wall_time_s, "%.3g") << " s\n";
  return s.str();
}

std::string FormatCompareLevelsCsv(const CompareResult& r) {
  std::ostringstream s;
  s.precision(10);
  s << "level,num_dofs,modes_verdict,modes_max_abs_rel_diff,modes_absent,floquet_verdict,"
       "max_abs_multiplier,floquet_difference,dte_verdict,dte_source,dte_max_abs_diff,"
       "dte_max_at_hz,dte_rms_diff,dte_peak_shift,modes_time_s,floquet_time_s,dte_time_s\n";
  for (const LevelRun& run : r.runs) {
    const LevelComparison* c = ComparisonOf(r, run.level);
    const LevelNumbers n = NumbersOf(c);
    const auto csv = [](double v) { return CsvNumber(v, "%.10g"); };
    s << run.level << "," << run.num_dofs << "," << Verdict(c, CompareAnalysis::kModes) << ","
      << csv(n.modes_max) << "," << (n.absent >= 0 ? std::to_string(n.absent) : "") << ","
      << Verdict(c, CompareAnalysis::kFloquet) << ","
      << (run.floquet ? csv(run.floquet->max_abs_multiplier) : "") << "," << csv(n.floquet) << ","
      << Verdict(c, CompareAnalysis::kHb) << "," << (run.dte ? run.dte->source : "") << ","
      << csv(n.dte_max) << "," << (c && c->dte ? csv(c->dte->max_at_hz) : "") << ","
      << csv(n.dte_rms) << "," << csv(n.peak_shift) << ","
      << (run.modes ? csv(run.modes_time_s) : "") << ","
      << (run.floquet ? csv(run.floquet_time_s) : "") << ","
      << (run.dte ? csv(run.dte->wall_time_s) : "") << "\n";
  }
  return s.str();
}

std::string FormatCompareModesCsv(const CompareResult& r) {
  std::ostringstream s;
  s << "level,reference_mode,reference_hz,mode,hz,relative_difference,mac\n";
  for (const LevelComparison& c : r.comparisons) {
    if (!c.modes) continue;
    for (const ModeMatch& m : c.modes->matches) {
      s << c.level << "," << m.reference + 1 << "," << Num(m.reference_hz, "%.10g") << ","
        << (m.other >= 0 ? std::to_string(m.other + 1) : "") << ","
        << CsvNumber(m.other_hz, "%.10g") << "," << CsvNumber(m.relative_difference, "%.6g") << ","
        << Num(m.mac, "%.6f") << "\n";
    }
  }
  return s.str();
}

std::string FormatCompareDteCsv(const CompareResult& r) {
  std::ostringstream s;
  s << "mesh_frequency_hz";
  std::vector<const LevelRun*> runs;
  for (const LevelRun& run : r.runs) {
    if (!run.dte) continue;
    runs.push_back(&run);
    for (const char* col :
         {"rms_up_m", "rms_down_m", "p2p_up_m", "p2p_down_m", "diff_up", "diff_down"}) {
      s << "," << run.level << "_" << col;
    }
  }
  s << "\n";
  const auto csv = [](double v) { return CsvNumber(v, "%.10g"); };
  for (std::size_t k = 0; k < r.frequencies_hz.size(); ++k) {
    s << Num(r.frequencies_hz[k], "%.10g");
    for (const LevelRun* run : runs) {
      const LevelDte& d = *run->dte;
      const LevelComparison* c = ComparisonOf(r, run->level);
      s << "," << csv(d.rms_up[k]) << "," << csv(d.rms_down[k]) << "," << csv(d.peak_to_peak_up[k])
        << "," << csv(d.peak_to_peak_down[k]) << "," << (c && c->dte ? csv(c->dte->up[k]) : "")
        << "," << (c && c->dte ? csv(c->dte->down[k]) : "");
    }
    s << "\n";
  }
  return s.str();
}

std::string RenderCompareDtePlot(const CompareResult& r) {
  PlotSpec spec;
  spec.title = "DTE of the model levels: " + r.scene + " (reference " +
               Reference(r, CompareAnalysis::kHb) + ")";
  spec.x_label = "mesh frequency [Hz]";
  PlotPanel rms, diff;
  rms.y_label = r.dimensionless ? "RMS x [-]" : "RMS DTE [µm]";
  const double unit = r.dimensionless ? 1.0 : kMicro;
  diff.y_label = "Δ RMS [% of the reference's peak]";
  std::size_t index = 0;
  for (const LevelRun& run : r.runs) {
    if (!run.dte) continue;
    const LevelDte& d = *run.dte;
    const std::string colour = PlotColour(index++);
    const auto scaled = [](const std::vector<double>& v, double f) {
      std::vector<double> out;
      for (const double x : v) out.push_back(x * f);
      return out;
    };
    rms.series.push_back({run.level + " (" + d.source + (d.multivalued ? ", up" : "") + ")",
                          r.frequencies_hz, scaled(d.rms_up, unit), false, colour});
    if (d.multivalued) {
      rms.series.push_back(
          {run.level + " (down)", r.frequencies_hz, scaled(d.rms_down, unit), true, colour});
    }
    const LevelComparison* c = ComparisonOf(r, run.level);
    if (c && c->dte && run.level != Reference(r, CompareAnalysis::kHb)) {
      diff.series.push_back(
          {run.level, r.frequencies_hz, scaled(c->dte->up, 100.0), false, colour});
      bool split = false;  // the down-branch difference differs from the up-branch one
      for (std::size_t k = 0; k < c->dte->up.size(); ++k) {
        const double a = c->dte->up[k], b = c->dte->down[k];
        split = split || (std::isfinite(a) != std::isfinite(b)) ||
                (std::isfinite(a) && std::abs(a - b) > 1e-9);
      }
      if (split) {
        diff.series.push_back({"", r.frequencies_hz, scaled(c->dte->down, 100.0), true, colour});
      }
    }
  }
  spec.panels.push_back(rms);
  if (!diff.series.empty()) spec.panels.push_back(diff);
  return RenderSvg(spec);
}

std::string RenderCompareChartPlot(const CompareResult& r) {
  const LevelRun* ref = nullptr;
  const std::string ref_name = Reference(r, CompareAnalysis::kFloquet);
  for (const LevelRun& run : r.runs) {
    if (run.chart && (ref == nullptr || run.level == ref_name)) ref = &run;
    if (ref && ref->level == ref_name) break;
  }
  if (ref == nullptr) return "";
  const StabilityChartResult& c = *ref->chart;
  RegionPlotSpec spec = MakeRegionPlotGrid(
      c, "Stability charts of the model levels: " + r.scene + " (regions: " + ref->level + ")");
  std::size_t index = 0;
  for (const LevelRun& run : r.runs) {
    const std::string colour = PlotColour(index++);
    if (!run.chart) continue;
    if (run.chart->curves.empty()) {
      spec.curves.push_back({{}, {}, false, colour, run.level + " (no transition curve)"});
    }
    for (const TransitionCurve& t : run.chart->curves) {
      spec.curves.push_back({t.x, t.y, t.closed, colour, run.level});
    }
  }
  return RenderRegionSvg(spec);
}

std::string FormatCompareChartCsv(const CompareResult& r) {
  std::ostringstream s;
  s << "level,x,y,max_abs_multiplier,stable\n";
  for (const LevelRun& run : r.runs) {
    if (!run.chart) continue;
    const StabilityChartResult& c = *run.chart;
    for (int iy = 0; iy < c.y_axis.num_points; ++iy) {
      for (int ix = 0; ix < c.x_axis.num_points; ++ix) {
        const std::size_t k = static_cast<std::size_t>(iy) * c.x_axis.num_points + ix;
        s << run.level << "," << Num(c.x_axis.Value(ix), "%.10g") << ","
          << Num(c.y_axis.Value(iy), "%.10g") << "," << CsvNumber(c.max_abs_multiplier[k], "%.10g")
          << "," << CsvVerdict(c.ok[k], c.stable[k]) << "\n";
      }
    }
  }
  return s.str();
}

// ---------------------------------------------------------------------------- --vary

std::string FormatCompareVaryCsv(const std::string& key, const std::vector<CompareVaryPoint>& v) {
  std::ostringstream s;
  s << "value,key,level,modes_max_abs_rel_diff,modes_in_plane,modes_out_of_plane,modes_absent,"
       "floquet_difference,dte_max_abs_diff,dte_rms_diff,dte_peak_shift,modes_verdict,"
       "floquet_verdict,dte_verdict\n";
  const auto csv = [](double x) { return CsvNumber(x, "%.10g"); };
  for (const CompareVaryPoint& p : v) {
    for (const LevelComparison& c : p.result.comparisons) {
      const LevelNumbers n = NumbersOf(&c);
      s << Num(p.value, "%.10g") << "," << key << "," << c.level << "," << csv(n.modes_max) << ","
        << csv(n.modes_in_plane) << "," << csv(n.modes_out_of_plane) << ","
        << (n.absent >= 0 ? std::to_string(n.absent) : "") << "," << csv(n.floquet) << ","
        << csv(n.dte_max) << "," << csv(n.dte_rms) << "," << csv(n.peak_shift) << ","
        << Verdict(&c, CompareAnalysis::kModes) << "," << Verdict(&c, CompareAnalysis::kFloquet)
        << "," << Verdict(&c, CompareAnalysis::kHb) << "\n";
    }
  }
  return s.str();
}

json MakeCompareVaryReport(const std::string& key, const std::vector<CompareVaryPoint>& v) {
  json points = json::array();
  bool ok = true;
  for (const CompareVaryPoint& p : v) {
    json levels = json::array();
    for (const LevelComparison& c : p.result.comparisons) {
      const LevelNumbers n = NumbersOf(&c);
      json verdict = json::object();
      for (const auto& [a, x] : c.verdict)
        verdict[a == CompareAnalysis::kHb ? "dte" : ToString(a)] = x;
      levels.push_back(
          {{"level", c.level},
           {"modes_max_abs_relative_difference", Finite(n.modes_max)},
           {"modes_in_plane_max_abs_relative_difference", Finite(n.modes_in_plane)},
           {"modes_out_of_plane_max_abs_relative_difference", Finite(n.modes_out_of_plane)},
           {"modes_absent", n.absent},
           {"floquet_difference", Finite(n.floquet)},
           {"dte_max_abs_difference", Finite(n.dte_max)},
           {"dte_rms_difference", Finite(n.dte_rms)},
           {"dte_peak_shift", Finite(n.peak_shift)},
           {"verdict", verdict},
           {"notes", c.notes}});
    }
    ok = ok && p.result.ok;
    points.push_back({{"value", p.value},
                      {"references",
                       {{"modes", Reference(p.result, CompareAnalysis::kModes)},
                        {"floquet", Reference(p.result, CompareAnalysis::kFloquet)},
                        {"dte", Reference(p.result, CompareAnalysis::kHb)}}},
                      {"status", p.result.ok ? "success" : "numerical_issue"},
                      {"wall_time_s", p.result.wall_time_s},
                      {"levels", levels}});
  }
  return {{"vary", key},
          {"scene", v.empty() ? "" : v.front().result.scene},
          {"points", points},
          {"status", ok ? "success" : "numerical_issue"}};
}

std::string FormatCompareVaryText(const std::string& key, const std::vector<CompareVaryPoint>& v) {
  std::ostringstream s;
  s << "compare over " << key << (v.empty() ? "" : ": " + v.front().result.scene) << "\n";
  s << Pad(key.substr(key.rfind('.') == std::string::npos ? 0 : key.rfind('.') + 1), 18)
    << Pad("level", 19) << Pad("max|Δf/f|", 11) << Pad("in plane", 10) << Pad("axial/rock", 11)
    << Pad("absent", 8) << Pad("Δmax|λ|", 11) << Pad("DTE max|Δ|", 12) << Pad("DTE RMS Δ", 11)
    << "peak shift\n";
  for (const CompareVaryPoint& p : v) {
    for (const LevelComparison& c : p.result.comparisons) {
      const LevelNumbers n = NumbersOf(&c);
      s << Pad(Num(p.value, "%.6g"), 18) << Pad(c.level, 19) << Pad(Pct(n.modes_max), 11)
        << Pad(Pct(n.modes_in_plane), 10) << Pad(Pct(n.modes_out_of_plane), 11)
        << Pad(n.absent >= 0 ? std::to_string(n.absent) : "—", 8)
        << Pad(Num(n.floquet, "%+.2e"), 11) << Pad(Pct(n.dte_max), 12) << Pad(Pct(n.dte_rms), 11)
        << Pct(n.peak_shift) << "\n";
    }
    if (!p.result.ok) s << "  (a run did not succeed at this value: see compare_vary.json)\n";
  }
  return s.str();
}

std::string RenderCompareVaryPlot(const std::string& key, const std::vector<CompareVaryPoint>& v) {
  PlotSpec spec;
  spec.title = "Model-level errors against the reference: " +
               (v.empty() ? std::string() : v.front().result.scene);
  spec.x_label = key;
  PlotPanel modes, out_of_plane, dte, absent;
  modes.y_label = "max |Δf/f|, rotational/translational modes [%]";
  out_of_plane.y_label = "max |Δf/f|, axial/rocking modes [%]";
  dte.y_label = "DTE max |Δ RMS| [% of ref. peak]";
  absent.y_label = "absent modes [-]";
  std::vector<std::string> levels;
  for (const CompareVaryPoint& p : v) {
    for (const LevelComparison& c : p.result.comparisons) {
      if (std::find(levels.begin(), levels.end(), c.level) == levels.end()) {
        levels.push_back(c.level);
      }
    }
  }
  for (std::size_t i = 0; i < levels.size(); ++i) {
    PlotSeries m{levels[i], {}, {}, false, PlotColour(i)};
    PlotSeries o{levels[i], {}, {}, false, PlotColour(i)};
    PlotSeries d{levels[i], {}, {}, false, PlotColour(i)}, a = d;
    bool any_reference = true;
    for (const CompareVaryPoint& p : v) {
      const LevelNumbers n = NumbersOf(ComparisonOf(p.result, levels[i]));
      m.x.push_back(p.value);
      m.y.push_back(100.0 * n.modes_in_plane);
      o.x.push_back(p.value);
      o.y.push_back(100.0 * n.modes_out_of_plane);
      d.x.push_back(p.value);
      d.y.push_back(100.0 * n.dte_max);
      a.x.push_back(p.value);
      a.y.push_back(n.absent >= 0 ? n.absent : kNaN);
      const LevelComparison* c = ComparisonOf(p.result, levels[i]);
      any_reference = any_reference && c != nullptr &&
                      std::all_of(c->verdict.begin(), c->verdict.end(), [](const auto& x) {
                        return x.second == "reference" || x.second == "skipped";
                      });
    }
    if (any_reference) continue;  // the reference's own zero line says nothing
    // A mark on every computed value (the lines only join them).
    for (const auto& [panel, series] :
         {std::pair<PlotPanel*, const PlotSeries*>{&modes, &m}, {&out_of_plane, &o}, {&dte, &d}}) {
      for (std::size_t k = 0; k < series->x.size(); ++k) {
        panel->markers.push_back({series->x[k], series->y[k], "", series->colour});
      }
    }
    modes.series.push_back(m);
    out_of_plane.series.push_back(o);
    dte.series.push_back(d);
    absent.series.push_back(a);
  }
  spec.panels = {modes, out_of_plane, dte, absent};
  return RenderSvg(spec);
}

}  // namespace geardyn::app
