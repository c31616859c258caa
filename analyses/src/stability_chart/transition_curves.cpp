// Step 2 of ComputeStabilityChart: bisection of the grid edges where the verdict changes and
// the joining of the crossings into polylines (marching squares; stability_chart.hpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "stability_chart/chart_internal.hpp"

namespace geardyn::internal {
namespace {

// One grid edge to bisect: from the stable end to the unstable end along one axis.
struct EdgeJob {
  int edge = 0;           // edge id (horizontal first, then vertical)
  bool along_x = true;    // the varying coordinate
  int ix = 0, iy = 0;     // grid index of the fixed coordinate (the other is −1 while bisecting)
  double stable = 0.0;    // varying coordinate at the stable end
  double unstable = 0.0;  // varying coordinate at the unstable end
};

struct Crossing {
  double x = 0.0, y = 0.0;
  double error = 0.0;  // half the final bracket / axis span
  long evaluations = 0;
};

// max|λ| − 1 − tolerance at a grid point: its sign is the verdict.
double Growth(const StabilityChartResult& c, int i, double threshold) {
  const double tol = std::max(threshold, c.error_estimate[i]);
  return c.max_abs_multiplier[i] - 1.0 - tol;
}

int MaxBisections(const ChartAxis& axis, double tolerance) {
  const double step = (axis.hi - axis.lo) / (axis.num_points - 1);
  return 2 + static_cast<int>(std::ceil(std::log2(step / (tolerance * (axis.hi - axis.lo)))));
}

Crossing Bisect(const EdgeJob& job, const ChartEvaluator& evaluate, const StabilityChartResult& c,
                const StabilityChartOptions& options) {
  const ChartAxis& axis = job.along_x ? c.x_axis : c.y_axis;
  const double width = options.boundary_tolerance * (axis.hi - axis.lo);
  double a = job.stable, b = job.unstable;
  Crossing out;
  while (std::abs(b - a) > width) {
    const double mid = 0.5 * (a + b);
    if (mid == a || mid == b) break;  // bracket at the resolution of doubles
    const ChartPoint p = job.along_x ? ChartPoint{mid, c.y_axis.Value(job.iy), -1, job.iy}
                                     : ChartPoint{c.x_axis.Value(job.ix), mid, job.ix, -1};
    const ChartPointResult r = evaluate(p);
    ++out.evaluations;
    if (!r.ok || !std::isfinite(r.max_abs_multiplier) || !std::isfinite(r.error_estimate)) {
      break;  // an undetermined point: keep the bracket so far (its half-width is the error)
    }
    (IsUnstable(r, options.instability_threshold) ? b : a) = mid;
  }
  const double at = 0.5 * (a + b);
  out.error = 0.5 * std::abs(b - a) / (axis.hi - axis.lo);
  out.x = job.along_x ? at : c.x_axis.Value(job.ix);
  out.y = job.along_x ? c.y_axis.Value(job.iy) : at;
  return out;
}

}  // namespace

void TraceTransitionCurves(std::vector<ChartEvaluator>& evaluators,
                           const StabilityChartOptions& options, StabilityChartResult* chart) {
  StabilityChartResult& c = *chart;
  const int nx = c.x_axis.num_points, ny = c.y_axis.num_points;
  const int num_h = (nx - 1) * ny;
  const int num_edges = num_h + nx * (ny - 1);
  const auto h_edge = [nx](int ix, int iy) { return iy * (nx - 1) + ix; };
  const auto v_edge = [nx, num_h](int ix, int iy) { return num_h + iy * nx + ix; };

  // Edges with a verdict change between two successful points, in edge-id order.
  std::vector<EdgeJob> jobs;
  const auto add_job = [&](int edge, bool along_x, int i0, int i1, int ix, int iy, double v0,
                           double v1) {
    if (!c.ok[i0] || !c.ok[i1] || c.stable[i0] == c.stable[i1]) return;
    jobs.push_back({edge, along_x, ix, iy, c.stable[i0] ? v0 : v1, c.stable[i0] ? v1 : v0});
  };
  for (int iy = 0; iy < ny; ++iy) {
    for (int ix = 0; ix + 1 < nx; ++ix) {
      add_job(h_edge(ix, iy), true, c.index(ix, iy), c.index(ix + 1, iy), ix, iy,
              c.x_axis.Value(ix), c.x_axis.Value(ix + 1));
    }
  }
  for (int iy = 0; iy + 1 < ny; ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      add_job(v_edge(ix, iy), false, c.index(ix, iy), c.index(ix, iy + 1), ix, iy,
              c.y_axis.Value(iy), c.y_axis.Value(iy + 1));
    }
  }

  std::vector<Crossing> crossings(jobs.size());
  const long max_steps = std::max(MaxBisections(c.x_axis, options.boundary_tolerance),
                                  MaxBisections(c.y_axis, options.boundary_tolerance));
  ChartProgressCallback progress;
  if (options.progress) {  // report evaluations (upper bound), not edges
    progress = [&options, max_steps](const ChartProgress& p) {
      options.progress(ChartProgress{p.phase, p.done * max_steps, p.total * max_steps});
    };
  }
  ParallelFor(
      static_cast<long>(jobs.size()), static_cast<int>(evaluators.size()),
      [&](long j, int thread) { crossings[j] = Bisect(jobs[j], evaluators[thread], c, options); },
      progress, "boundaries");

  long evaluations = 0;
  double worst = 0.0;
  std::vector<int> crossing_of_edge(num_edges, -1);
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    crossing_of_edge[jobs[j].edge] = static_cast<int>(j);
    evaluations += crossings[j].evaluations;
    worst = std::max(worst, crossings[j].error);
  }
  c.summary.counters["evaluations"] += evaluations;
  c.summary.counters["curve_points"] = static_cast<long>(jobs.size());
  c.summary.error_estimate = worst;

  // Marching squares: one or two segments per cell, between crossings on its edges.
  std::vector<std::array<int, 2>> neighbours(jobs.size(), {-1, -1});
  const auto link = [&neighbours](int a, int b) {
    for (int k = 0; k < 2; ++k) {
      if (neighbours[a][k] < 0) {
        neighbours[a][k] = b;
        break;
      }
    }
    for (int k = 0; k < 2; ++k) {
      if (neighbours[b][k] < 0) {
        neighbours[b][k] = a;
        break;
      }
    }
  };
  for (int cy = 0; cy + 1 < ny; ++cy) {
    for (int cx = 0; cx + 1 < nx; ++cx) {
      // Edges e0 bottom (c0–c1), e1 right (c1–c2), e2 top (c2–c3), e3 left (c3–c0).
      const std::array<int, 4> e = {
          crossing_of_edge[h_edge(cx, cy)], crossing_of_edge[v_edge(cx + 1, cy)],
          crossing_of_edge[h_edge(cx, cy + 1)], crossing_of_edge[v_edge(cx, cy)]};
      std::array<int, 4> found{};
      int count = 0;
      for (int k = 0; k < 4; ++k) {
        if (e[k] >= 0) found[count++] = e[k];
      }
      if (count == 2) {
        link(found[0], found[1]);
      } else if (count == 4) {  // saddle: decide by the mean growth of the corners
        const int c0 = c.index(cx, cy);
        const double centre =
            0.25 * (Growth(c, c0, options.instability_threshold) +
                    Growth(c, c.index(cx + 1, cy), options.instability_threshold) +
                    Growth(c, c.index(cx + 1, cy + 1), options.instability_threshold) +
                    Growth(c, c.index(cx, cy + 1), options.instability_threshold));
        const bool centre_stable = !(centre > 0.0);
        if (centre_stable == static_cast<bool>(c.stable[c0])) {  // c0, c2 joined: cut c1, c3
          link(e[0], e[1]);
          link(e[2], e[3]);
        } else {  // c1, c3 joined: cut c0, c2
          link(e[3], e[0]);
          link(e[1], e[2]);
        }
      }
    }
  }

  // Chain: open curves from their ends first, then the closed loops.
  std::vector<char> visited(jobs.size(), 0);
  const auto walk = [&](int start) {
    TransitionCurve curve;
    int previous = -1, at = start;
    while (at >= 0 && !visited[at]) {
      visited[at] = 1;
      curve.x.push_back(crossings[at].x);
      curve.y.push_back(crossings[at].y);
      const int next = neighbours[at][0] != previous ? neighbours[at][0] : neighbours[at][1];
      previous = at;
      at = next;
    }
    curve.closed = at == start && curve.x.size() > 2;
    c.curves.push_back(std::move(curve));
  };
  const auto degree = [&neighbours](int j) {
    return (neighbours[j][0] >= 0 ? 1 : 0) + (neighbours[j][1] >= 0 ? 1 : 0);
  };
  for (int j = 0; j < static_cast<int>(jobs.size()); ++j) {
    if (!visited[j] && degree(j) <= 1) walk(j);
  }
  for (int j = 0; j < static_cast<int>(jobs.size()); ++j) {
    if (!visited[j]) walk(j);
  }
}

}  // namespace geardyn::internal
