// The verdicts of `geardyn compare` (compare_runner.hpp): each level against the reference of
// every analysis — modes by MAC, Floquet verdicts, DTE differences, chart agreement — as
// three-valued verdicts with one-line notes.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "geardyn/analyses/floquet_verdict.hpp"
#include "geardyn/compare_internal.hpp"

namespace geardyn::app::compare_internal {

ModalResult FirstModes(const ModalResult& r, int count) {
  count = std::min<int>(count, static_cast<int>(r.frequencies_hz.size()));
  ModalResult out;
  out.frequencies_hz = r.frequencies_hz.head(count);
  out.eigenvalues = r.eigenvalues.head(count);
  out.shapes = r.shapes.leftCols(count);
  out.num_rigid_body_modes = std::min(r.num_rigid_body_modes, count);
  if (static_cast<int>(r.labels.size()) >= count) {
    out.labels.assign(r.labels.begin(), r.labels.begin() + count);
  }
  for (const std::vector<int>& g : r.multiplicity_groups) {
    std::vector<int> kept;
    for (const int k : g) {
      if (k < count) kept.push_back(k);
    }
    if (!kept.empty()) out.multiplicity_groups.push_back(kept);
  }
  return out;
}

std::string Percent(double x) {
  char s[32];
  std::snprintf(s, sizeof(s), "%+.3g %%", 100.0 * x);
  return s;
}

std::string Hz(double f) {
  char s[32];
  std::snprintf(s, sizeof(s), "%.4g Hz", f);
  return s;
}

bool FloquetDetermined(const FloquetResult& r) {
  return r.verdict != FloquetVerdict::kUndetermined && std::isfinite(r.max_abs_multiplier);
}

std::string ModeName(const ModalResult& r, int k) {
  std::string name = "mode " + std::to_string(k + 1);
  if (k < static_cast<int>(r.labels.size()))
    name += std::string(" (") + ToString(r.labels[k]) + ")";
  return name + " " + Hz(r.frequencies_hz(k));
}

const LevelRun* FindRun(const CompareResult& result, const std::string& level) {
  for (const LevelRun& r : result.runs) {
    if (r.level == level) return &r;
  }
  return nullptr;
}

std::string SkipReason(const LevelRun& run, CompareAnalysis a) {
  const auto it = run.skipped.find(a);
  return it != run.skipped.end() ? it->second : std::string("not run");
}

void CompareModes(const LevelRun& run, const LevelRun* ref, const CompareSettings& settings,
                  LevelComparison* c) {
  std::string& v = c->verdict[CompareAnalysis::kModes];
  if (!run.modes) {
    v = "skipped";
    c->notes.push_back("modes: skipped (" + SkipReason(run, CompareAnalysis::kModes) + ")");
    return;
  }
  if (ref == nullptr || !ref->modes) {
    v = "undetermined";
    c->notes.push_back("modes: undetermined (no reference level ran the modes)");
    return;
  }
  if (!run.modes->summary.ok() || !ref->modes->summary.ok()) {
    v = "undetermined";
    c->notes.push_back(
        std::string("modes: undetermined (") +
        (run.modes->summary.ok() ? "the reference's" : "its") +
        " modal analysis did not succeed: " +
        (run.modes->summary.ok() ? ref->modes->summary.message : run.modes->summary.message) + ")");
    return;
  }
  const ModalResult reference = FirstModes(*ref->modes, settings.num_modes);
  ModeMatchingOptions options;
  options.mac_threshold = settings.mac_threshold;
  c->modes = MatchModesByMac(reference, *run.modes, ref->mass, options);
  c->modes_max_in_plane = c->modes_max_out_of_plane = 0.0;
  for (const ModeMatch& m : c->modes->matches) {
    if (m.other < 0 || !std::isfinite(m.relative_difference) ||
        m.reference >= static_cast<int>(reference.labels.size())) {
      continue;
    }
    const ModeType type = reference.labels[m.reference];
    double& worst = type == ModeType::kAxial || type == ModeType::kRocking
                        ? c->modes_max_out_of_plane
                        : c->modes_max_in_plane;
    worst = std::max(worst, std::abs(m.relative_difference));
  }
  if (run.level == ref->level) {
    v = "reference";
    return;
  }
  int outside = 0, absent = 0;
  std::vector<std::string> lines;
  for (const ModeMatch& m : c->modes->matches) {
    if (m.other < 0) {
      ++absent;
      lines.push_back("  " + ModeName(reference, m.reference) + ": absent (best MAC " +
                      std::to_string(m.mac).substr(0, 4) + ")");
    } else if (!(std::abs(m.relative_difference) <= settings.frequency_tolerance)) {
      ++outside;
      lines.push_back("  " + ModeName(reference, m.reference) + ": " +
                      (std::isfinite(m.relative_difference) ? Percent(m.relative_difference)
                                                            : std::string("rigid vs not")) +
                      " (" + Hz(m.other_hz) + ", MAC " + std::to_string(m.mac).substr(0, 4) + ")");
    }
  }
  const int matched = c->modes->num_matched;
  const int total = static_cast<int>(c->modes->matches.size());
  if (outside == 0 && absent == 0) {
    v = "agrees";
    c->notes.push_back("modes: agrees — all " + std::to_string(total) + " modes matched (MAC ≥ " +
                       std::to_string(settings.mac_threshold).substr(0, 4) + "), max |Δf/f| " +
                       Percent(c->modes->max_abs_relative_difference).substr(1) + " ≤ " +
                       Percent(settings.frequency_tolerance).substr(1));
  } else {
    v = "differs";
    c->notes.push_back("modes: differs — " + std::to_string(matched) + "/" + std::to_string(total) +
                       " matched, " + std::to_string(outside) + " beyond ±" +
                       Percent(settings.frequency_tolerance).substr(1) + ", " +
                       std::to_string(absent) + " absent:");
    for (std::string& l : lines) c->notes.push_back(std::move(l));
  }
}

void CompareFloquet(const LevelRun& run, const LevelRun* ref, LevelComparison* c) {
  std::string& v = c->verdict[CompareAnalysis::kFloquet];
  if (!run.floquet) {
    v = "skipped";
    c->notes.push_back("floquet: skipped (" + SkipReason(run, CompareAnalysis::kFloquet) + ")");
    return;
  }
  const FloquetResult& f = *run.floquet;
  if (ref == nullptr || !ref->floquet || !FloquetDetermined(f) ||
      !FloquetDetermined(*ref->floquet)) {
    v = "undetermined";
    c->notes.push_back(std::string("floquet: undetermined (") +
                       (FloquetDetermined(f) ? "the reference's" : "its") + " verdict is " +
                       "undetermined: " +
                       (FloquetDetermined(f) && ref && ref->floquet ? ref->floquet->summary.message
                                                                    : f.summary.message) +
                       ")");
    return;
  }
  c->floquet_difference = f.max_abs_multiplier - ref->floquet->max_abs_multiplier;
  if (run.level == ref->level) {
    v = "reference";
    return;
  }
  const bool same = f.verdict == ref->floquet->verdict;
  v = same ? "agrees" : "differs";
  c->notes.push_back(std::string("floquet: ") + (same ? "agrees — " : "differs — ") +
                     ToString(f.verdict) + ", max|λ| " +
                     FormatMaxAbsMultiplier(f.max_abs_multiplier) + " vs the reference's " +
                     ToString(ref->floquet->verdict) + ", " +
                     FormatMaxAbsMultiplier(ref->floquet->max_abs_multiplier));
}

void CompareDte(const LevelRun& run, const LevelRun* ref, const CompareResult& result,
                const CompareSettings& settings, LevelComparison* c) {
  std::string& v = c->verdict[CompareAnalysis::kHb];
  if (!run.dte) {
    v = "skipped";
    c->notes.push_back("DTE: skipped (" +
                       SkipReason(run, run.skipped.count(CompareAnalysis::kHb)
                                           ? CompareAnalysis::kHb
                                           : CompareAnalysis::kSimulate) +
                       ")");
    return;
  }
  if (ref == nullptr || !ref->dte || !run.dte->summary.ok() || !ref->dte->summary.ok()) {
    v = "undetermined";
    const bool mine = !run.dte->summary.ok();
    c->notes.push_back(mine ? "DTE: undetermined (its " + run.dte->source +
                                  " did not succeed: " + run.dte->summary.message + ")"
                            : "DTE: undetermined (the reference " +
                                  (ref ? ref->level : std::string("level")) +
                                  " did not succeed: see its verdict)");
    return;
  }
  c->dte = CalcDteDifference(*run.dte, *ref->dte, result.frequencies_hz, settings.dte_tolerance);
  if (run.level == ref->level) {
    v = "reference";
    return;
  }
  const DteDifference& d = *c->dte;
  if (!std::isfinite(d.max_abs)) {
    v = "undetermined";
    c->notes.push_back("DTE: undetermined (no mesh frequency where both have a stable solution)");
    return;
  }
  std::string peak;
  if (d.reference_peak_hz > 0.0) {
    peak = "; peak " + Hz(d.peak_hz) + " vs " + Hz(d.reference_peak_hz) + " (" +
           Percent((d.peak_hz - d.reference_peak_hz) / d.reference_peak_hz) + "), height ×" +
           std::to_string(d.peak_ratio).substr(0, 5);
  }
  if (d.max_abs <= settings.dte_tolerance && d.missing == 0) {
    v = "agrees";
    c->notes.push_back("DTE: agrees — max |Δ RMS| " + Percent(d.max_abs).substr(1) +
                       " of the reference's peak ≤ " + Percent(settings.dte_tolerance).substr(1) +
                       peak);
    return;
  }
  v = "differs";
  std::string ranges;
  for (const auto& [lo, hi] : d.disagree_ranges) {
    ranges += (ranges.empty() ? "" : ", ") + (lo == hi ? Hz(lo) : Hz(lo) + "–" + Hz(hi));
  }
  c->notes.push_back("DTE: differs — max |Δ RMS| " + Percent(d.max_abs).substr(1) +
                     " of the reference's peak at " + Hz(d.max_at_hz) + " (" + d.max_where +
                     "), RMS " + Percent(d.rms).substr(1) + peak);
  if (!ranges.empty())
    c->notes.push_back("  beyond ±" + Percent(settings.dte_tolerance).substr(1) + " at " + ranges);
  if (d.missing > 0) {
    c->notes.push_back("  " + std::to_string(d.missing) +
                       " branch point(s) with a stable solution on one side only (a jump or a "
                       "range without a steady state)");
  }
}

LevelComparison CompareToReferences(const LevelRun& run, const CompareResult& result,
                                    const CompareSettings& settings) {
  LevelComparison c;
  c.level = run.level;
  const auto ref = [&](CompareAnalysis a) -> const LevelRun* {
    const auto it = result.reference.find(a);
    return it == result.reference.end() || it->second.empty() ? nullptr
                                                              : FindRun(result, it->second);
  };
  if (result.reference.count(CompareAnalysis::kModes)) {
    CompareModes(run, ref(CompareAnalysis::kModes), settings, &c);
  }
  if (result.reference.count(CompareAnalysis::kFloquet)) {
    CompareFloquet(run, ref(CompareAnalysis::kFloquet), &c);
  }
  if (result.reference.count(CompareAnalysis::kHb)) {
    CompareDte(run, ref(CompareAnalysis::kHb), result, settings, &c);
  }
  // Charts: the share of grid points with the reference's verdict.
  const LevelRun* chart_ref = nullptr;
  for (const LevelRun& r : result.runs) {
    if (r.chart && r.chart->summary.ok()) {
      chart_ref = &r;
      break;
    }
  }
  if (const auto it = result.reference.find(CompareAnalysis::kFloquet);
      it != result.reference.end() && !it->second.empty()) {
    const LevelRun* floquet_ref = FindRun(result, it->second);
    if (floquet_ref && floquet_ref->chart) chart_ref = floquet_ref;
  }
  if (chart_ref && run.chart && chart_ref->chart &&
      run.chart->stable.size() == chart_ref->chart->stable.size()) {
    int same = 0, compared = 0;
    for (std::size_t k = 0; k < run.chart->stable.size(); ++k) {
      if (!run.chart->ok[k] || !chart_ref->chart->ok[k]) continue;
      ++compared;
      same += run.chart->stable[k] == chart_ref->chart->stable[k];
    }
    c.chart_points = compared;
    if (compared > 0) {
      c.chart_agreement = static_cast<double>(same) / compared;
      if (run.level != chart_ref->level) {
        c.notes.push_back("chart: the reference's verdict at " +
                          Percent(c.chart_agreement).substr(1) + " of " + std::to_string(compared) +
                          " grid points");
      }
    }
  } else if (!run.chart_skipped.empty()) {
    c.notes.push_back("chart: skipped (" + run.chart_skipped + ")");
  }
  return c;
}

}  // namespace geardyn::app::compare_internal
