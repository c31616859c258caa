// ComputeStabilityChart: options, axes, the parallel grid and the driver of the three steps
// (stability_chart.hpp).
#include "geardyn/analyses/stability_chart.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <sstream>

#include "geardyn/common/errors.hpp"
#include "stability_chart/chart_internal.hpp"

namespace geardyn {

double ChartAxis::Value(int i) const {
  if (i <= 0) return lo;
  if (i >= num_points - 1) return hi;
  return lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(num_points - 1);
}

bool ChartAxis::IsValid(const std::string& what, std::string* why) const {
  std::ostringstream s;
  if (num_points < 2) {
    s << what << ": the number of points must be at least 2, got " << num_points;
  } else if (num_points > kMaxChartAxisPoints) {
    s << what << ": the number of points must be at most " << kMaxChartAxisPoints << ", got "
      << num_points << " (each point of an axis is a row or column of Floquet solves)";
  } else if (!std::isfinite(lo) || !std::isfinite(hi)) {
    s << what << ": the bounds must be finite, got " << lo << ":" << hi;
  } else if (!(lo < hi)) {
    s << what << ": the lower bound must be below the upper bound, got " << lo << ":" << hi;
  } else {
    return true;
  }
  if (why) *why = s.str();
  return false;
}

bool IsValidChartGrid(const ChartAxis& x, const ChartAxis& y, std::string* why) {
  const long long n = static_cast<long long>(x.num_points) * y.num_points;
  if (n <= kMaxChartGridPoints) return true;
  // Per point: max|λ|, error, f_m (3 doubles), ok, stable (2 bytes), region (int).
  constexpr double kBytesPerPoint = 3 * sizeof(double) + 2 + sizeof(int);
  std::ostringstream s;
  s << "grid: " << x.num_points << " × " << y.num_points << " = " << n
    << " points exceed the limit " << kMaxChartGridPoints << ": that is " << n
    << " Floquet solves (plus the transition-curve bisections) and "
    << static_cast<double>(n) * kBytesPerPoint / 1e9 << " GB of per-point results";
  if (why) *why = s.str();
  return false;
}

bool StabilityChartOptions::IsValid(std::string* why) const {
  std::ostringstream s;
  if (num_threads < 0) {
    s << "num_threads must be >= 0 (0 = all cores), got " << num_threads;
  } else if (!(instability_threshold >= 0.0 && instability_threshold < 1.0)) {
    s << "instability_threshold must be in [0, 1), got " << instability_threshold;
  } else if (!(boundary_tolerance > 0.0 && boundary_tolerance < 1.0)) {
    s << "boundary_tolerance must be in (0, 1), got " << boundary_tolerance;
  } else if (first_mode_index < 0) {
    s << "first_mode_index must be >= 0, got " << first_mode_index;
  } else if (max_resonance_order < 1) {
    s << "max_resonance_order must be >= 1, got " << max_resonance_order;
  } else {
    for (const std::vector<double>& row : natural_frequencies_hz) {
      for (double f : row) {
        if (!std::isfinite(f) || f < 0.0) {
          s << "natural_frequencies_hz must be finite and >= 0, got " << f;
          if (why) *why = s.str();
          return false;
        }
      }
    }
    return true;
  }
  if (why) *why = s.str();
  return false;
}

const char* ToString(ResonanceKind kind) {
  switch (kind) {
    case ResonanceKind::kPrincipal:
      return "principal";
    case ResonanceKind::kSumCombination:
      return "sum_combination";
    case ResonanceKind::kDifferenceCombination:
      return "difference_combination";
  }
  return "unknown";
}

namespace internal {

int ResolveThreadCount(int requested, long work, std::string* note) {
  // More threads than hardware threads or than work items only cost memory (one evaluator, i.e.
  // one model, per thread) and, past a few 10⁴, make the OpenMP runtime fail.
  const int hardware = std::max(1, omp_get_num_procs());
  const long cap = std::max(1L, std::min<long>(hardware, work));
  const int wanted = requested > 0 ? requested : std::max(1, omp_get_max_threads());
  const int used = static_cast<int>(std::min<long>(wanted, cap));
  if (requested > used && note != nullptr) {
    *note = "num_threads: " + std::to_string(requested) + " requested, " + std::to_string(used) +
            " used (" + std::to_string(hardware) + " hardware threads, " + std::to_string(work) +
            " grid points)";
  }
  return used;
}

void ParallelFor(long n, int num_threads, const std::function<void(long i, int thread)>& body,
                 const ChartProgressCallback& progress, const char* phase) {
  std::atomic<long> done{0};
  long first_error_index = n;
  std::exception_ptr first_error;
  const long step = std::max(1L, n / 100);
  long next_report = step;
#pragma omp parallel for schedule(dynamic, 1) num_threads(num_threads)
  for (long i = 0; i < n; ++i) {
    try {
      body(i, omp_get_thread_num());
    } catch (...) {
#pragma omp critical(geardyn_chart_error)
      {
        if (i < first_error_index) {
          first_error_index = i;
          first_error = std::current_exception();
        }
      }
    }
    const long d = ++done;
    // Thread 0 is the calling thread: the callback never runs on a worker.
    if (progress && omp_get_thread_num() == 0 && d >= next_report) {
      next_report = d + step;
      progress(ChartProgress{phase, d, n});
    }
  }
  if (progress) progress(ChartProgress{phase, n, n});
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace internal

StabilityChartResult ComputeStabilityChart(const ChartAxis& x, const ChartAxis& y,
                                           const ChartEvaluatorFactory& make_evaluator,
                                           const StabilityChartOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  if (!x.IsValid("x axis", &why) || !y.IsValid("y axis", &why) || !IsValidChartGrid(x, y, &why) ||
      !options.IsValid(&why)) {
    throw InvalidInput("ComputeStabilityChart: " + why);
  }
  if (!make_evaluator) throw InvalidInput("ComputeStabilityChart: make_evaluator is empty");
  const std::size_t rows = options.natural_frequencies_hz.size();
  if (rows != 0 && rows != 1 && rows != static_cast<std::size_t>(y.num_points)) {
    throw InvalidInput("ComputeStabilityChart: natural_frequencies_hz must have 0, 1 or " +
                       std::to_string(y.num_points) + " (y.num_points) lists, got " +
                       std::to_string(rows));
  }

  const long grid_points = static_cast<long>(x.num_points) * y.num_points;
  std::string thread_note;
  const int threads = internal::ResolveThreadCount(options.num_threads, grid_points, &thread_note);
  std::vector<ChartEvaluator> evaluators;
  evaluators.reserve(threads);
  for (int t = 0; t < threads; ++t) evaluators.push_back(make_evaluator());

  StabilityChartResult chart;
  if (!thread_note.empty()) chart.summary.warnings.push_back(thread_note);
  chart.x_axis = x;
  chart.y_axis = y;
  const long n = static_cast<long>(x.num_points) * y.num_points;
  chart.max_abs_multiplier.assign(n, 0.0);
  chart.error_estimate.assign(n, 0.0);
  chart.mesh_frequency_hz.assign(n, 0.0);
  chart.ok.assign(n, 0);
  chart.stable.assign(n, 0);
  chart.region.assign(n, -1);

  // Step 1: the grid. A cancelled point is skipped: undetermined, counted apart.
  std::vector<char> computed(n, 0);
  internal::ParallelFor(
      n, threads,
      [&](long i, int thread) {
        if (options.cancel != nullptr && options.cancel->load()) return;
        computed[i] = 1;
        const int ix = static_cast<int>(i % x.num_points);
        const int iy = static_cast<int>(i / x.num_points);
        const ChartPointResult r = evaluators[thread](ChartPoint{x.Value(ix), y.Value(iy), ix, iy});
        // Undetermined: the evaluator says so, or max|λ| or its estimate is not finite (a NaN
        // estimate would otherwise drop out of IsUnstable's comparison and read as stable).
        const bool ok =
            r.ok && std::isfinite(r.max_abs_multiplier) && std::isfinite(r.error_estimate);
        chart.max_abs_multiplier[i] = r.max_abs_multiplier;
        chart.error_estimate[i] = r.error_estimate;
        chart.mesh_frequency_hz[i] = r.mesh_frequency_hz;
        chart.ok[i] = ok ? 1 : 0;
        chart.stable[i] = ok && !internal::IsUnstable(r, options.instability_threshold) ? 1 : 0;
      },
      options.progress, "grid");

  long failed = 0;
  for (long i = 0; i < n; ++i) failed += chart.ok[i] ? 0 : 1;
  chart.summary.counters["grid_points"] = n;
  chart.summary.counters["evaluations"] = n;
  chart.summary.counters["undetermined_points"] = failed;
  chart.summary.counters["threads"] = threads;
  const long done = std::count(computed.begin(), computed.end(), char{1});
  if (done < n) {
    chart.summary.status = Status::kInterrupted;
    chart.summary.message = "interrupted: " + std::to_string(done) + " of " + std::to_string(n) +
                            " grid points computed, the others are undetermined; no transition "
                            "curves traced";
  } else if (failed > 0) {
    chart.summary.status = Status::kNumericalIssue;
    chart.summary.message = std::to_string(failed) + " of " + std::to_string(n) +
                            " grid points are undetermined (evaluation failed or its verdict is "
                            "undetermined; left out of the regions and curves)";
  }

  // Step 2: transition curves; step 3: regions and labels.
  if (options.trace_curves && done == n) {
    internal::TraceTransitionCurves(evaluators, options, &chart);
  }
  internal::FindRegions(options, &chart);
  chart.summary.counters["regions"] = static_cast<long>(chart.regions.size());

  chart.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return chart;
}

}  // namespace geardyn
