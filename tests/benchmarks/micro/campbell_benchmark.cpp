// Cost of the Campbell diagram per speed (issue 18): RunCampbellAnalysis (the whole command: the
// scene build once, the speed terms, one state-space eigen solve of 2m per speed with vectors,
// MAC tracking, labels) on the built-in scenes, for 11 and 41 speeds; the difference of the two
// gives the cost per speed, the counter `s_per_speed` the average.
#include <benchmark/benchmark.h>

#include <string>

#include "geardyn/analysis_runs.hpp"
#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn::app {
namespace {

void BM_Campbell(benchmark::State& state, const std::string& scene_name) {
  const Scene scene = LoadScene(scene_name);
  CampbellSettings settings;
  const int n = static_cast<int>(state.range(0));
  settings.speed = "0:20000:" + std::to_string(n);
  int modes = 0;
  for (auto _ : state) {
    const CampbellRun run = RunCampbellAnalysis(scene, settings);
    modes = static_cast<int>(run.result.tracks.size());
    benchmark::DoNotOptimize(run.report);
  }
  state.counters["modes"] = modes;
  // Seconds per speed (the scene build included, shared over the n speeds).
  state.counters["s_per_speed"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK_CAPTURE(BM_Campbell, lin_parker, std::string("builtin:planetary-lin-parker"))
    ->Arg(11)->Arg(41)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Campbell, wind_turbine, std::string("builtin:planetary-wind-turbine"))
    ->Arg(11)->Arg(41)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Campbell, helical_pair, std::string("builtin:helical-pair"))
    ->Arg(11)->Arg(41)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Campbell, geared_shafts, std::string("builtin:geared-shafts"))
    ->Arg(11)->Arg(41)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geardyn::app

BENCHMARK_MAIN();
