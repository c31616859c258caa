// Cost of the quasi-periodic linear harmonic balance vs total order H (issue 18): the two-stage
// wind-turbine gearbox (examples/multi-stage/wind-turbine-two-stage.toml, 48 DOF, 7 meshes, two
// mesh frequencies in the ratio 7/40) at its operating point, one SolveQuasiPeriodicHb per
// iteration (expansion, assembly, SparseLU, outputs). Counters: unknowns, LU nonzeros.
// BM_NonlinearQuasiPeriodicHb: the same train with slice meshes (model = "slices" on every
// mesh), one SolveNonlinearQuasiPeriodicHb per iteration from the linear guess (condensation per
// κ, torus AFT, dense Newton). Counters: real unknowns, grid points, Newton iterations.
#include <benchmark/benchmark.h>

#include <string>

#include "geardyn/analyses/nonlinear_quasi_periodic_hb.hpp"
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
// Total orders H = 2 … 10.
void TotalOrders(benchmark::internal::Benchmark* b) {
  for (int H : {2, 4, 6, 8, 10}) b->Arg(H);
  b->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_QuasiPeriodicHb)->Apply(TotalOrders);

void BM_NonlinearQuasiPeriodicHb(benchmark::State& state) {
  const Scene scene = LoadScene(
      std::string(GEARDYN_SOURCE_DIR) + "/examples/multi-stage/wind-turbine-two-stage.toml",
      {"mesh.sun-planet.model=\"slices\"", "mesh.planet-ring.model=\"slices\"",
       "mesh.hs-pinion-hs-wheel.model=\"slices\""});
  const SystemModel model = BuildSceneSystem(scene).model;
  NonlinearQuasiPeriodicHbOptions options;
  options.torus.total_order = static_cast<int>(state.range(0));
  NonlinearQuasiPeriodicHbResult r;
  for (auto _ : state) {
    r = SolveNonlinearQuasiPeriodicHb(model, scene.NominalMeshFrequencyHz(), options);
    benchmark::DoNotOptimize(r.torus.harmonics.data());
  }
  state.counters["unknowns"] = static_cast<double>(r.torus.summary.counters["unknowns"]);
  state.counters["grid_points"] = static_cast<double>(r.torus.summary.counters["grid_points"]);
  state.counters["newton"] = r.newton_iterations;
  state.counters["rms_dte_um_hs"] = 1e6 * r.torus.meshes.front().rms_dte;
  state.counters["estimate_GB"] = EstimateNonlinearQuasiPeriodicHbBytes(model, options) / 1e9;
}
BENCHMARK(BM_NonlinearQuasiPeriodicHb)->Apply(TotalOrders);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
