// Micro-benchmark of the dense modal path when a few modes with vectors are wanted
// (ComputeModes, method kDense, shapes on): all n eigenpairs (num_modes = 0: Cholesky of M,
// tridiagonal QR with accumulated vectors, SolveGeneralizedEigenDense — what the dense path did
// for any num_modes before) against only the lowest 20 (num_modes = 20: Householder
// tridiagonalization and LAPACK dstemr for the index range, SolveGeneralizedEigenDenseSubset),
// with ARPACK's lowest 20 for reference. ComputeModes includes the assembly, the residual check,
// the energy classification and, since the scene has modal damping, the dense damping
// classification (an O(n³) commutation test); BM_DenseSolver times the two eigen solvers alone on
// the same mean stiffness K̄ and mass M. Scene: builtin:geared-shafts (two shafts of 8 Timoshenko
// elements, 108 DOFs) and the same with 50 elements per shaft (612 DOFs:
// --set shaft.input.sections.0.elements=50 --set shaft.output.sections.0.elements=50).
// Counters: dofs, modes (returned), max_rel_diff = max relative difference of the 20 lowest
// frequencies few vs all (computed once, outside the timed loop).
//
// Run: build with -DGEARDYN_BUILD_BENCHMARKS=ON (Release, or RelWithDebInfo at -O2), then
//   ./tests/benchmarks/dense_few_modes_benchmark
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/numerics/symmetric_eigen_subset.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn {
namespace {

constexpr int kFewModes = 20;

SystemModel GearedShafts(int elements_per_shaft) {
  const std::string e = std::to_string(elements_per_shaft);
  return MakeSystemModel(
      LoadScene("builtin:geared-shafts",
                {"shaft.input.sections.0.elements=" + e, "shaft.output.sections.0.elements=" + e}));
}

ModalOptions Options(ModalMethod method, int num_modes) {
  ModalOptions o;
  o.method = method;
  o.num_modes = num_modes;
  o.compute_shapes = true;
  return o;
}

void BM_DenseModes(benchmark::State& state, ModalMethod method, int num_modes) {
  const SystemModel model = GearedShafts(static_cast<int>(state.range(0)));
  ModalResult r;
  for (auto _ : state) {
    r = ComputeModes(model, Options(method, num_modes));
    benchmark::DoNotOptimize(r.eigenvalues.data());
  }
  if (!r.summary.ok() || r.method_used != method) {
    state.SkipWithError(("not ok or wrong method: " + r.summary.BriefReport()).c_str());
    return;
  }
  state.counters["dofs"] = model.num_dofs();
  state.counters["modes"] = static_cast<double>(r.eigenvalues.size());
  const ModalResult all = ComputeModes(model, Options(ModalMethod::kDense, 0));
  double worst = 0.0;
  for (int k = 0; k < kFewModes; ++k) {
    if (all.frequencies_hz(k) > 0.0) {
      worst = std::max(worst, std::abs(r.frequencies_hz(k) / all.frequencies_hz(k) - 1.0));
    }
  }
  state.counters["max_rel_diff"] = worst;
}

// The eigen solvers alone: all n pairs (SolveGeneralizedEigenDense) or the lowest 20
// (SolveGeneralizedEigenDenseSubset), vectors in both.
void BM_DenseSolver(benchmark::State& state, bool few) {
  const SystemModel model = GearedShafts(static_cast<int>(state.range(0)));
  SystemWorkspace ws(model, StorageKind::kSparse);
  const MatrixX K(AssembleMeanStiffnessSparse(model, ws)), M(model.mass());
  GeneralizedEigenResult r;
  for (auto _ : state) {
    r = few ? SolveGeneralizedEigenDenseSubset(K, M, kFewModes) : SolveGeneralizedEigenDense(K, M);
    benchmark::DoNotOptimize(r.eigenvalues.data());
  }
  if (!r.summary.ok()) state.SkipWithError(r.summary.message.c_str());
  state.counters["dofs"] = model.num_dofs();
  state.counters["modes"] = static_cast<double>(r.eigenvalues.size());
}

BENCHMARK_CAPTURE(BM_DenseSolver, all, false)->Arg(8)->Arg(50)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DenseSolver, few, true)->Arg(8)->Arg(50)->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_DenseModes, dense_all, ModalMethod::kDense, 0)
    ->Arg(8)
    ->Arg(50)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DenseModes, dense_few, ModalMethod::kDense, kFewModes)
    ->Arg(8)
    ->Arg(50)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DenseModes, arpack_few, ModalMethod::kArpack, kFewModes)
    ->Arg(8)
    ->Arg(50)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
