// Micro-benchmark of ComputeModes (geardyn/analyses/modal.hpp), dense vs ARPACK through the
// analysis entry point (assembly of K̄ and M from the model, the eigen solve, the residual check
// and the energy classification of the returned modes), on a free-free Timoshenko shaft of
// N elements along Z (steel, D = 0.2 m, L = 1 m; 6·(N + 1) DOFs, six rigid-body modes, bending
// modes in pairs): N = 1, 16, 166, 833 → 12, 102, 1 002, 5 004 DOFs.
//
// Both paths return the same number of modes, m = min(20, n/2) (ARPACK needs m < n − 1), with
// energy fractions (hence vectors); the dense path computes all n and keeps m. The dense path
// runs once at 5 004 DOFs (tens of seconds: O(n³)).
// Counters: modes = returned modes, rel_diff = max relative difference of the returned nonzero
// eigenvalues between the two paths (computed once, outside the timed loop), ops = applications
// of (K̄ − σM)⁻¹M (ARPACK).
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/modal_benchmark
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/elements/shaft_beam.hpp"
#include "geardyn/system/system_builder.hpp"
#include "modes_benchmark_body.hpp"

namespace geardyn {
namespace {

SystemModel MakeShaft(int num_elements) {
  const double length = 1.0, h = length / num_elements;
  SystemBuilder b;
  std::vector<BodyIndex> nodes;
  for (int i = 0; i <= num_elements; ++i) {
    nodes.push_back(b.AddBody("n" + std::to_string(i), Matrix6::Zero(), Vector3(0.0, 0.0, i * h)));
  }
  ShaftBeam beam;
  beam.section.outer_diameter = 0.2;
  beam.material = ShaftMaterial::FromPoissonRatio(2.1e11, 0.3, 7850.0);
  beam.node_b = Vector3(0.0, 0.0, h);
  const MatrixX K = CalcShaftBeamStiffness(beam), M = CalcShaftBeamMass(beam);
  for (int i = 0; i < num_elements; ++i) {
    b.AddElement("shaft" + std::to_string(i), ElementKind::kShaft, {nodes[i], nodes[i + 1]}, K,
                 MatrixX(), M);
  }
  return b.Build();
}

void BM_ComputeModes(benchmark::State& state, ModalMethod method) {
  bench::RunModesBenchmark(state, MakeShaft(static_cast<int>(state.range(0))), method);
}

void DenseSizes(benchmark::internal::Benchmark* b) {
  for (const int elements : {1, 16, 166}) b->Arg(elements);
}

BENCHMARK_CAPTURE(BM_ComputeModes, dense, ModalMethod::kDense)
    ->Apply(DenseSizes)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ComputeModes, dense, ModalMethod::kDense)
    ->Arg(833)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ComputeModes, arpack, ModalMethod::kArpack)
    ->Apply(DenseSizes)
    ->Arg(833)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
