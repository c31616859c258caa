// The C++ side of the Python overhead benchmark (tests/benchmarks/python/overhead.py): the
// commands' analyses (apps/geardyn/analysis_runs.hpp) on a scene loaded once, exactly the calls
// the Python package makes. overhead.py times the same cases through `geardyn.modes` / `.hb`.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "geardyn/analysis_runs.hpp"
#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn::app {
namespace {

// The cases of overhead.py, by name: scene, overrides.
const Scene& Rig() {
  static const Scene scene = LoadScene("builtin:kahraman-blankenship-rig");
  return scene;
}
const Scene& RigSlices() {
  static const Scene scene =
      LoadScene("builtin:kahraman-blankenship-rig",
                {"mesh.pinion-wheel.model=slices", "mesh.pinion-wheel.center_distance=0.1502",
                 "mesh.pinion-wheel.damping_ratio=0.05"});
  return scene;
}

void BM_ModesHelicalPair(benchmark::State& state) {
  const Scene scene = LoadScene("builtin:helical-pair");
  for (auto _ : state) benchmark::DoNotOptimize(RunModesAnalysis(scene, ModesSettings{}));
}
BENCHMARK(BM_ModesHelicalPair)->Unit(benchmark::kMillisecond);

void BM_ModesGearedShaftsAllShapesDamped(benchmark::State& state) {
  const Scene scene = LoadScene("builtin:geared-shafts");
  ModesSettings settings;
  settings.num_modes = 1000;
  settings.shapes = true;
  settings.damped = true;
  for (auto _ : state) benchmark::DoNotOptimize(RunModesAnalysis(scene, settings));
}
BENCHMARK(BM_ModesGearedShaftsAllShapesDamped)->Unit(benchmark::kMillisecond);

void BM_HbLinearRig40(benchmark::State& state) {
  HbRunSettings settings;
  settings.settings.mesh_frequency = "700.0:3500.0:40";
  for (auto _ : state) benchmark::DoNotOptimize(RunHbAnalysis(Rig(), settings));
}
BENCHMARK(BM_HbLinearRig40)->Unit(benchmark::kMillisecond);

void BM_HbNonlinearRig(benchmark::State& state) {
  HbRunSettings settings;
  settings.settings.mesh_frequency = "1500.0:4000.0:120";
  for (auto _ : state) benchmark::DoNotOptimize(RunHbAnalysis(RigSlices(), settings));
}
BENCHMARK(BM_HbNonlinearRig)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geardyn::app

BENCHMARK_MAIN();
