// Micro-benchmark of the slice mesh core (spec 01 §4.4; geardyn/system/mesh_core.hpp): the
// force pair and tangent EvalSliceForce at N = 10, 40, 160 slices, as a nonlinear HB (AFT) or
// time-stepping analysis calls it once per time sample and state. Variants:
//  * EvalSliceForce — a new θ every call (the table k_s(θ) is interpolated, then the slice loop);
//  * EvalSliceForceSameTheta — repeated θ (Newton iterations at one time sample: cached values);
//  * CalcSliceForce — slice values precomputed (AFT: k_s(θ_t) do not depend on the state);
//  * EvalStiffnessCore — the linear B–S core of the same pair (piecewise/Fourier/table), for scale.
// Helical pair (m_n 2.5 mm, z 23/61, β 18°, B 30 mm), tooth-like k(r), partial contact (a tilt
// δ_ζ unloads about a third of the slices) and a finite backlash.
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/slice_core_benchmark
#include <benchmark/benchmark.h>

#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "geardyn/models/mesh/mesh_cores.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn {
namespace {

MeshCoreSource HelicalSource() {
  GearPairSpec s;
  s.normal_module = 2.5e-3;
  s.normal_pressure_angle = DegToRad(20.0);
  s.helix_angle = DegToRad(18.0);
  s.pinion_hand = HelixHand::kRight;
  s.pinion.teeth = 23;
  s.gear.teeth = 61;
  s.pinion.face_width = 0.030;
  s.gear.face_width = 0.030;
  const GearPairGeometry g = CalcGearPairGeometry(s);
  const double len = g.line_of_action_length;
  MeshCoreSource source =
      MakeMeshCoreSource(g, StiffnessProfile::PiecewiseLinear({0.0, 0.3 * len, 0.7 * len, len},
                                                              {0.6e10, 1.4e10, 1.4e10, 0.7e10}));
  source.backlash = 80e-6;
  return source;
}

const MeshCoreSource& Source() {
  static const MeshCoreSource source = HelicalSource();
  return source;
}

// δ_η = 4 µm, δ_ζ tilting so that a = δ_η − σ δ_ζ < 0 on roughly the upper third of σ.
constexpr double kDeltaEta = 4e-6;
constexpr double kDeltaZeta = 4e-6 / 0.006;

void BM_EvalSliceForce(benchmark::State& state) {
  const SliceMeshCore core = MakeSliceMeshCore(Source(), static_cast<int>(state.range(0)));
  SliceMeshWorkspace ws(core);
  double theta = 0.0;
  for (auto _ : state) {
    theta += 0.0123;  // a new time sample every call
    const SliceForce f = EvalSliceForce(core, ws, theta, kDeltaEta, kDeltaZeta);
    benchmark::DoNotOptimize(f);
  }
  state.counters["slices"] = static_cast<double>(core.num_slices());
}
BENCHMARK(BM_EvalSliceForce)->Arg(10)->Arg(40)->Arg(160);

void BM_EvalSliceForceSameTheta(benchmark::State& state) {
  const SliceMeshCore core = MakeSliceMeshCore(Source(), static_cast<int>(state.range(0)));
  SliceMeshWorkspace ws(core);
  double d_eta = kDeltaEta;
  for (auto _ : state) {
    benchmark::DoNotOptimize(d_eta);  // a Newton iterate at a fixed θ
    const SliceForce f = EvalSliceForce(core, ws, 1.0, d_eta, kDeltaZeta);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_EvalSliceForceSameTheta)->Arg(10)->Arg(40)->Arg(160);

void BM_CalcSliceForce(benchmark::State& state) {
  const SliceMeshCore core = MakeSliceMeshCore(Source(), static_cast<int>(state.range(0)));
  SliceMeshWorkspace ws(core);
  EvalSliceValues(core, ws, 1.0);
  double d_eta = kDeltaEta;
  for (auto _ : state) {
    benchmark::DoNotOptimize(d_eta);
    const SliceForce f = CalcSliceForce(core, ws.stiffness, ws.separation, d_eta, kDeltaZeta);
    benchmark::DoNotOptimize(f);
  }
}
BENCHMARK(BM_CalcSliceForce)->Arg(10)->Arg(40)->Arg(160);

// The linear B–S core of the same pair: 0 = exact Fourier to 1e-4 (kAuto), 1 = 256-sample table.
void BM_EvalStiffnessCore(benchmark::State& state) {
  MeshCoefficientOptions options;
  if (state.range(0) == 1) options.form = MeshCoefficientForm::kTable;
  const LinearMeshCore core =
      MakeLinearMeshCore(Source(), MeshModelLevel::kBlankenshipSingh, options);
  double theta = 0.0;
  for (auto _ : state) {
    theta += 0.0123;
    const Matrix2 K2 = EvalStiffnessCore(core, theta);
    benchmark::DoNotOptimize(K2.data());
  }
  state.SetLabel(state.range(0) == 1 ? "table_256" : "fourier_rel_tol_1e-4");
}
BENCHMARK(BM_EvalStiffnessCore)->Arg(0)->Arg(1);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
