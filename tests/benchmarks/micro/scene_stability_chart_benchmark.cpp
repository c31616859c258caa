// The README's stability chart (issue 13: "80 × 24 points, 9.4 s; target under 1 s"):
// ComputeSceneStabilityChart (apps/geardyn/stability_chart_runner.hpp) on builtin:helical-pair
// with K(θ) = 4e8 + a cos θ N/m, speed 5 000 … 40 000 rpm × a = 0 … 1.2e8 N/m, i.e.
//   geardyn stability-chart builtin:helical-pair
//     --set 'mesh.pinion-wheel.parameters={form="fourier", stiffness=[4e8, 0, 0]}'
//     --x operating_point.speed_rpm=5000:40000:80
//     --y mesh.pinion-wheel.parameters.stiffness.1=0:1.2e8:24
// Arguments: x points, y points, threads (0 = all cores), settings (0: the defaults before issue
// 13, Floquet tolerance 1e-10 and bisection to 1e-5 of the span; 2: the first issue-13 defaults,
// 1e-6 with the 1e-10 verdict refinement and bisection to 1e-3; 1: the current defaults, as 2
// with the measured-order Magnus step control for the 1e-6 screening run and the prepared rows
// (PreparedFloquet); 3: as 1 without the prepared rows, every point a ComputeFloquet).
#include <benchmark/benchmark.h>

#include "geardyn/stability_chart_runner.hpp"

namespace geardyn {
namespace {

void BM_ReadmeChart(benchmark::State& state) {
  app::SceneChartSettings s;
  s.scene = "builtin:helical-pair";
  s.overrides = {"mesh.pinion-wheel.parameters={form=\"fourier\", stiffness=[4e8, 0, 0]}"};
  s.x = {app::kSpeedPath, 5000.0, 40000.0, static_cast<int>(state.range(0))};
  s.y = {"mesh.pinion-wheel.parameters.stiffness.1", 0.0, 1.2e8, static_cast<int>(state.range(1))};
  s.chart.num_threads = static_cast<int>(state.range(2));
  const long settings = state.range(3);
  s.floquet.tolerance = settings != 0 ? 1e-6 : 1e-10;
  s.chart.boundary_tolerance = settings != 0 ? 1e-3 : 1e-5;
  s.measured_order = settings == 1 || settings == 3;
  s.prepare_rows = settings == 1;
  long evaluations = 0, regions = 0, unstable = 0;
  for (auto _ : state) {
    const app::SceneChart run = app::ComputeSceneStabilityChart(s);
    evaluations = run.chart.summary.counters.at("evaluations");
    regions = static_cast<long>(run.chart.regions.size());
    unstable = 0;
    for (std::size_t i = 0; i < run.chart.stable.size(); ++i) {
      unstable += run.chart.ok[i] && !run.chart.stable[i];
    }
    benchmark::DoNotOptimize(run.chart.max_abs_multiplier.data());
  }
  state.counters["evaluations"] = static_cast<double>(evaluations);
  state.counters["regions"] = static_cast<double>(regions);
  state.counters["unstable_points"] = static_cast<double>(unstable);
}

BENCHMARK(BM_ReadmeChart)
    ->Args({80, 24, 0, 1})
    ->Args({80, 24, 1, 1})
    ->Args({80, 24, 0, 3})
    ->Args({80, 24, 1, 3})
    ->Args({80, 24, 0, 2})
    ->Args({80, 24, 1, 2})
    ->Args({80, 24, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
