// Micro-benchmark of assembly and eigen analysis on geared-shaft systems (issue 4): two parallel
// steel shafts of Timoshenko elements (D = 60 mm, span 0.5 m) joined by the helical mesh of
// builtin:helical-pair (z 25/61, β 15°, B–S LTV core with its mean for the modes), each gear on
// its shaft's middle node, each shaft on two grounded rolling bearings at its ends (radial
// 5e8 N/m, axial 3e8 N/m on one of them; torsion free: one rigid-body mode of the train).
// Sizes (nodes per shaft a + b, DOFs = 6 (a + b)): 1 + 1 = 12 (the two gears on their bearings),
// 8 + 9 = 102, 83 + 84 = 1 002, 416 + 417 = 4 998.
//
// Benchmarks:
// * BM_MakeSystemModel — scene → SystemModel of builtin:helical-pair (12 DOFs; mesh core from
//   the contact lines and ISO 6336-1, Fourier form, plus SystemBuilder::Build).
// * BM_Build/<dofs> — SystemBuilder::Build() of the geared shafts (validation, sparse M/K0/C0,
//   block partition, facts); the builder is filled outside the timed loop.
// * BM_AssembleMeanStiffness/<dofs> — K̄ into an existing workspace (dense below 200 DOFs, the
//   model's storage hint; sparse above).
// * BM_Modes/dense/<dofs>, BM_Modes/arpack/<dofs> — ComputeModes with m = min(20, n/2) lowest
//   modes (ARPACK needs m < n − 1) and energy fractions, forced path. The dense path at 4 998 DOFs
//   runs once (one iteration, minutes: O(n³) with vectors); run the others with
//   --benchmark_filter='BM_(MakeSystemModel|Build|Assemble|Modes/arpack|Modes/dense/(12|102|1002)$)'
//   and that one alone with --benchmark_filter=BM_Modes/dense/4998.
// Counters: dofs, modes, nnz (K̄ nonzeros), ops (ARPACK operator applications), f1_hz (first
// non-zero frequency) and rel_diff (max relative difference of the returned eigenvalues between
// ARPACK and dense, computed once outside the timed loop, up to 1 002 DOFs).
//
// Run: cmake -S . -B build-modes-rel -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON
//      cmake --build build-modes-rel --target geared_shafts_benchmark
//      ./build-modes-rel/tests/benchmarks/geared_shafts_benchmark
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/elements/shaft_beam.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/system_builder.hpp"
#include "geardyn/system/workspace.hpp"
#include "modes_benchmark_body.hpp"

namespace geardyn {
namespace {

constexpr double kSpan = 0.5;  // shaft length [m]

// Nodes per shaft (a, b) for a benchmark argument (the DOF count).
std::pair<int, int> NodesFor(int dofs) {
  switch (dofs) {
    case 12:
      return {1, 1};
    case 102:
      return {8, 9};
    case 1002:
      return {83, 84};
    default:
      return {416, 417};  // 4998
  }
}

const SceneSystem& HelicalPair() {
  static const SceneSystem built = BuildSceneSystem(LoadScene("builtin:helical-pair"));
  return built;
}

// Adds one shaft of `nodes` nodes along Z through `centre` (gear on the middle node, whose mass
// block is `gear_mass`), with grounded bearings at both ends; returns the gear node.
BodyIndex AddShaft(SystemBuilder& b, const std::string& name, int nodes, const Vector3& centre,
                   const Matrix6& gear_mass) {
  const int gear = nodes / 2;
  const double h = nodes > 1 ? kSpan / (nodes - 1) : 0.0;
  std::vector<BodyIndex> ids;
  for (int i = 0; i < nodes; ++i) {
    const Matrix6 mass = i == gear ? gear_mass : Matrix6::Zero();
    ids.push_back(
        b.AddBody(name + std::to_string(i), mass, centre + Vector3(0.0, 0.0, (i - gear) * h)));
  }
  if (nodes > 1) {
    ShaftBeam beam;
    beam.section.outer_diameter = 0.06;
    beam.material = ShaftMaterial::FromPoissonRatio(2.1e11, 0.3, 7850.0);
    beam.node_b = Vector3(0.0, 0.0, h);
    const MatrixX K = CalcShaftBeamStiffness(beam), M = CalcShaftBeamMass(beam);
    for (int i = 0; i + 1 < nodes; ++i) {
      b.AddElement(name + "-shaft" + std::to_string(i), ElementKind::kShaft, {ids[i], ids[i + 1]},
                   K, MatrixX(), M);
    }
  }
  // Bearings: radial 5e8 N/m at both ends (+ tilt stiffness 1e5 N·m/rad so that a one-node
  // shaft is held too), axial 3e8 N/m at the first; torsion free.
  Vector6 k_locating, k_floating;
  k_locating << 5e8, 5e8, 3e8, 1e5, 1e5, 0.0;
  k_floating << 5e8, 5e8, 0.0, 1e5, 1e5, 0.0;
  b.AddElement(name + "-bearing-a", ElementKind::kBearing, {ids.front()},
               MatrixX(k_locating.asDiagonal()));
  b.AddElement(name + "-bearing-b", ElementKind::kBearing, {ids.back()},
               MatrixX(k_floating.asDiagonal()));
  return ids[static_cast<std::size_t>(gear)];
}

SystemBuilder GearedShaftsBuilder(int dofs) {
  const SceneSystem& pair = HelicalPair();
  const MatrixX M = pair.model.DenseMass();
  const SystemMesh& mesh = pair.model.meshes()[0];
  const auto [a, b] = NodesFor(dofs);
  SystemBuilder builder;
  const BodyIndex pinion = AddShaft(builder, "p", a, pair.centres[0], Matrix6(M.block<6, 6>(0, 0)));
  const BodyIndex wheel = AddShaft(builder, "w", b, pair.centres[1], Matrix6(M.block<6, 6>(6, 6)));
  // The gears sit at the same centres as in the scene, so its G applies unchanged.
  builder.AddMesh("mesh", pinion, wheel, mesh.G, mesh.core);
  return builder;
}

SystemModel GearedShafts(int dofs) { return GearedShaftsBuilder(dofs).Build(); }

void BM_MakeSystemModel(benchmark::State& state) {
  const Scene scene = LoadScene("builtin:helical-pair");
  for (auto _ : state) {
    SystemModel model = MakeSystemModel(scene);
    benchmark::DoNotOptimize(model.num_dofs());
  }
  state.counters["dofs"] = 12;
}

void BM_Build(benchmark::State& state) {
  const SystemBuilder builder = GearedShaftsBuilder(static_cast<int>(state.range(0)));
  int n = 0;
  for (auto _ : state) {
    SystemModel model = builder.Build();
    n = model.num_dofs();
    benchmark::DoNotOptimize(n);
  }
  state.counters["dofs"] = n;
}

void BM_AssembleMeanStiffness(benchmark::State& state) {
  const SystemModel model = GearedShafts(static_cast<int>(state.range(0)));
  SystemWorkspace ws(model);
  const bool dense = ws.storage == StorageKind::kDense;
  for (auto _ : state) {
    if (dense) {
      benchmark::DoNotOptimize(AssembleMeanStiffness(model, ws).data());
    } else {
      benchmark::DoNotOptimize(AssembleMeanStiffnessSparse(model, ws).valuePtr());
    }
  }
  state.counters["dofs"] = model.num_dofs();
  state.counters["nnz"] = dense ? static_cast<double>(model.num_dofs()) * model.num_dofs()
                                : static_cast<double>(ws.stiffness_sparse.nonZeros());
  state.SetLabel(dense ? "dense" : "sparse");
}

void BM_Modes(benchmark::State& state, ModalMethod method) {
  bench::RunModesBenchmark(state, GearedShafts(static_cast<int>(state.range(0))), method, true);
}

void AllSizes(benchmark::internal::Benchmark* b) {
  for (const int dofs : {12, 102, 1002, 4998}) b->Arg(dofs);
}

BENCHMARK(BM_MakeSystemModel)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Build)->Apply(AllSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_AssembleMeanStiffness)->Apply(AllSizes)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Modes, dense, ModalMethod::kDense)
    ->Arg(12)
    ->Arg(102)
    ->Arg(1002)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Modes, arpack, ModalMethod::kArpack)
    ->Apply(AllSizes)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Modes, dense, ModalMethod::kDense)
    ->Arg(4998)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
