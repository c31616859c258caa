// Benchmark of the gear-system nonlinear harmonic balance (issue 13): the Kahraman–Blankenship
// rig with a 10-slice mesh (centre distance 150.2 mm: contact loss, back flank never reached),
// mesh damping ratio 0.05, 100 N·m, traced over 700–3500 Hz with monodromy stability of every
// point, exactly as `geardyn hb builtin:kahraman-blankenship-rig --mesh-frequency 700:3500:200
// --set mesh.pinion-wheel.model=slices --set mesh.pinion-wheel.center_distance=0.1502 --set
// mesh.pinion-wheel.damping_ratio=0.05` runs it (H = 24). Paired paths:
//  * Exact — as the CLI runs it now: kAuto (the slice law's projected form integrated exactly,
//    exact piecewise monodromy; nonlinear_hb.hpp "Exact integration of projected laws"; the
//    pole–residue condensation built once) and |ΔΩ| ≤ range/200 per step (max_omega_step);
//  * ExactDirectCondensation — the same with NhbCondensation::kDirect (an LU of every D_k at
//    every new Ω, as before issue 13's second round): what the pole–residue form saves;
//  * Before — as the CLI ran it before issue 13: forced kSampled (AFT, 16 samples per harmonic,
//    Magnus-4 monodromy on max(64, 4H) uniform steps) and scaled arclength step ≤ 1/200;
//  * SampledCapped — kSampled with the new step rule (what the step rule alone gives).
// Counters: points, folds, jumps and the up/down jump frequencies (accuracy of the curve).
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/nhb_rig_sweep_benchmark
#include <benchmark/benchmark.h>

#include <algorithm>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {
namespace {

const SystemModel& Rig() {
  static const SystemModel model =
      BuildSceneSystem(
          LoadScene("builtin:kahraman-blankenship-rig", {"mesh.pinion-wheel.model=\"slices\"",
                                                         "mesh.pinion-wheel.center_distance=0.1502",
                                                         "mesh.pinion-wheel.damping_ratio=0.05"}))
          .model;
  return model;
}

void Sweep(benchmark::State& state, NhbForceIntegration integration, bool omega_cap,
           NhbCondensation condensation = NhbCondensation::kAuto) {
  SystemNhbOptions o;
  o.hb.harmonics = 24;
  o.hb.force_integration = integration;
  o.hb.condensation = condensation;
  o.start_hz = 700.0;
  o.end_hz = 3500.0;
  if (omega_cap) {
    o.continuation.max_omega_step = 2.0 * std::numbers::pi * (o.end_hz - o.start_hz) / 200;
  } else {
    o.continuation.max_step = 1.0 / 200;  // the CLI's old rule for 200 frequencies
  }
  o.continuation.initial_step = std::min(o.continuation.initial_step, 1.0 / 200);
  SystemNhbCurve c;
  for (auto _ : state) {
    c = TraceSystemNonlinearHb(Rig(), o);
    benchmark::DoNotOptimize(c);
  }
  state.counters["points"] = static_cast<double>(c.points.size());
  state.counters["folds"] = static_cast<double>(c.fold_frequencies_hz.size());
  state.counters["ok"] = c.summary.ok() ? 1.0 : 0.0;
  int unstable = 0;
  for (const SystemNhbPoint& p : c.points) unstable += p.point.stable == FloquetVerdict::kUnstable;
  state.counters["unstable"] = unstable;
  int index = 0;
  for (const SystemNhbJump& j : c.jumps) {
    state.counters[(j.up_sweep ? "up" : "down") + std::to_string(index++) + "_hz"] =
        j.mesh_frequency_hz;
  }
}

void BM_RigSweepExact(benchmark::State& state) { Sweep(state, NhbForceIntegration::kAuto, true); }
void BM_RigSweepExactDirectCondensation(benchmark::State& state) {
  Sweep(state, NhbForceIntegration::kAuto, true, NhbCondensation::kDirect);
}
void BM_RigSweepBefore(benchmark::State& state) {
  Sweep(state, NhbForceIntegration::kSampled, false);
}
void BM_RigSweepSampledCapped(benchmark::State& state) {
  Sweep(state, NhbForceIntegration::kSampled, true);
}

BENCHMARK(BM_RigSweepExact)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_RigSweepExactDirectCondensation)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_RigSweepBefore)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_RigSweepSampledCapped)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
