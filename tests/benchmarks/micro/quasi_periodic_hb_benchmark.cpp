// Cost of the quasi-periodic linear harmonic balance vs total order H (issue 18): the two-stage
// wind-turbine gearbox (examples/multi-stage/wind-turbine-two-stage.toml, 48 DOF, 7 meshes, two
// mesh frequencies in the ratio 7/40) at its operating point, one SolveQuasiPeriodicHb per
// iteration (expansion, assembly, SparseLU, outputs). Counters: unknowns, LU nonzeros.
#include <benchmark/benchmark.h>

#include <string>

#include "geardyn/analyses/quasi_periodic_hb.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {
namespace {

void BM_QuasiPeriodicHb(benchmark::State& state) {
  const Scene scene = LoadScene(std::string(GEARDYN_SOURCE_DIR) +
                                "/examples/multi-stage/wind-turbine-two-stage.toml");
  const SystemModel model = BuildSceneSystem(scene).model;
  QuasiPeriodicHbOptions options;
  options.total_order = static_cast<int>(state.range(0));
  QuasiPeriodicHbResult r;
  for (auto _ : state) {
    r = SolveQuasiPeriodicHb(model, scene.NominalMeshFrequencyHz(), options);
    benchmark::DoNotOptimize(r.harmonics.data());
  }
  state.counters["unknowns"] = static_cast<double>(r.summary.counters["unknowns"]);
  state.counters["lu_nonzeros"] = static_cast<double>(r.summary.counters["lu_nonzeros"]);
  state.counters["estimate_GB"] = EstimateQuasiPeriodicHbBytes(model, options) / 1e9;
}
BENCHMARK(BM_QuasiPeriodicHb)
    ->Arg(2)
    ->Arg(4)
    ->Arg(6)
    ->Arg(8)
    ->Arg(10)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
