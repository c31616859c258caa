// ComputeHbStability: the Floquet verdict of every linear-HB point (hb_stability.hpp), a
// separate pass over the frequencies with ComputeFloquet.
#include "geardyn/analyses/hb_stability.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace geardyn {
namespace {

std::string Hz(double f) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", f);
  return text;
}

// Runs of consecutive kUnstable points, in the given order.
std::vector<HbUnstableRange> UnstableRanges(const std::vector<HbPointStability>& points) {
  std::vector<HbUnstableRange> ranges;
  bool in_run = false;
  for (const HbPointStability& p : points) {
    if (p.verdict != FloquetVerdict::kUnstable) {
      in_run = false;
      continue;
    }
    if (!in_run) ranges.push_back({p.mesh_frequency_hz, p.mesh_frequency_hz, 0, 0.0});
    in_run = true;
    HbUnstableRange& r = ranges.back();
    r.hi_hz = p.mesh_frequency_hz;
    ++r.points;
    // An unstable verdict has a max|λ| > 1 (possibly +inf); never NaN (FloquetVerdict rules).
    r.max_abs_multiplier = std::max(r.max_abs_multiplier, p.max_abs_multiplier);
  }
  return ranges;
}

// The Floquet analysis at f_m (options.mesh_frequency_hz replaced, no monodromy kept).
FloquetResult FloquetAt(const SystemModel& model, double mesh_frequency_hz,
                        const FloquetOptions& options) {
  FloquetOptions at = options;
  at.mesh_frequency_hz = mesh_frequency_hz;
  at.keep_monodromy = false;
  return ComputeFloquet(model, at);
}

HbPointStability ToPointStability(double mesh_frequency_hz, const FloquetResult& r) {
  HbPointStability out;
  out.mesh_frequency_hz = mesh_frequency_hz;
  out.verdict = r.verdict;
  out.max_abs_multiplier = r.max_abs_multiplier;
  out.error_estimate = r.summary.error_estimate;
  out.marginal = r.marginal;
  out.method_used = r.method_used;
  out.status = r.summary.status;
  out.message = r.summary.message;
  out.wall_time_s = r.summary.wall_time_s;
  return out;
}

}  // namespace

HbPointStability ComputeHbPointStability(const SystemModel& model, double mesh_frequency_hz,
                                         const FloquetOptions& options) {
  return ToPointStability(mesh_frequency_hz, FloquetAt(model, mesh_frequency_hz, options));
}

HbStabilitySweep ComputeHbStability(const SystemModel& model,
                                    const std::vector<double>& mesh_frequencies_hz,
                                    const FloquetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  HbStabilitySweep sweep;
  std::vector<std::string> floquet_warnings;
  int undetermined = 0;
  const HbPointStability* first_undetermined = nullptr;
  sweep.points.reserve(mesh_frequencies_hz.size());
  for (const double f : mesh_frequencies_hz) {
    const FloquetResult r = FloquetAt(model, f, options);
    for (const std::string& w : r.summary.warnings) {
      if (std::find(floquet_warnings.begin(), floquet_warnings.end(), w) ==
          floquet_warnings.end()) {
        floquet_warnings.push_back(w);
      }
    }
    sweep.points.push_back(ToPointStability(f, r));
  }
  for (const HbPointStability& p : sweep.points) {
    if (p.verdict != FloquetVerdict::kUndetermined) continue;
    if (undetermined++ == 0) first_undetermined = &p;
  }
  sweep.unstable_ranges = UnstableRanges(sweep.points);
  for (const HbUnstableRange& r : sweep.unstable_ranges) {
    const std::string where = r.points == 1 ? "f_m = " + Hz(r.lo_hz) + " Hz"
                                            : "f_m = " + Hz(r.lo_hz) + " … " + Hz(r.hi_hz) +
                                                  " Hz (" + std::to_string(r.points) + " points)";
    sweep.summary.warnings.push_back(
        "parametrically unstable at " + where + ", max|λ| up to " +
        FormatMaxAbsMultiplier(r.max_abs_multiplier) +
        ": the periodic solution there is not a response the system settles to (Floquet "
        "multipliers of M q'' + C q' + K(θ) q = 0 outside the unit circle)");
  }
  for (const std::string& w : floquet_warnings) sweep.summary.warnings.push_back("Floquet: " + w);
  if (undetermined > 0) {
    sweep.summary.status = Status::kNumericalIssue;
    sweep.summary.message =
        "Floquet verdict undetermined at " + std::to_string(undetermined) + " of " +
        std::to_string(sweep.points.size()) +
        " mesh frequencies (first f_m = " + Hz(first_undetermined->mesh_frequency_hz) +
        " Hz: status " + StatusName(first_undetermined->status) +
        (first_undetermined->message.empty() ? "" : ", " + first_undetermined->message) +
        "); the stability of those periodic solutions is unknown";
  }
  sweep.summary.counters["floquet_points"] = static_cast<long>(sweep.points.size());
  sweep.summary.counters["unstable_points"] = 0;
  for (const HbUnstableRange& r : sweep.unstable_ranges) {
    sweep.summary.counters["unstable_points"] += r.points;
  }
  sweep.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sweep;
}

}  // namespace geardyn
