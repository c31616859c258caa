/// @file
/// @brief Internals of ComputeStabilityChart: the parallel loop, the transition curves and the
/// region labels (stability_chart.hpp has the algorithm).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "geardyn/analyses/stability_chart.hpp"

namespace geardyn::internal {

/// @brief Runs body(i, thread) for i = 0 … n−1 on `num_threads` OpenMP threads (dynamic
/// schedule) and reports progress from the calling thread. An exception thrown by body is
/// rethrown after the loop (the one of the lowest i); the other iterations still run.
void ParallelFor(long n, int num_threads, const std::function<void(long i, int thread)>& body,
                 const ChartProgressCallback& progress, const char* phase);

/// @brief Threads to use for options.num_threads (0 = omp_get_max_threads()), clamped to the
/// hardware threads (omp_get_num_procs()) and to `work` items; `note` (may be null) says so when
/// a positive request is reduced.
int ResolveThreadCount(int requested, long work, std::string* note);

/// True when the point is unstable: max|λ| > 1 + max(threshold, error_estimate).
inline bool IsUnstable(const ChartPointResult& r, double threshold) {
  const double tol = r.error_estimate > threshold ? r.error_estimate : threshold;
  return r.max_abs_multiplier > 1.0 + tol;
}

/// @brief Bisects the grid edges with a verdict change and joins the crossings into curves
/// (step 2 of the algorithm). Adds the counters "evaluations" and "curve_points" and sets
/// summary.error_estimate.
void TraceTransitionCurves(std::vector<ChartEvaluator>& evaluators,
                           const StabilityChartOptions& options, StabilityChartResult* chart);

/// @brief Finds the unstable regions and labels them (step 3 of the algorithm).
void FindRegions(const StabilityChartOptions& options, StabilityChartResult* chart);

}  // namespace geardyn::internal
