// Micro-benchmark of the generalized symmetric eigen solvers
// (geardyn/numerics/symmetric_eigen.hpp): the dense solver (all n modes: Cholesky of M +
// tridiagonal QR, O(n³)) against ARPACK shift-invert Lanczos for the lowest 20 modes (sparse LDLᵀ
// of K − σM + a few dozen solves, O(n) for banded systems), with mode shapes in both cases, at 12,
// 100, 1 000 and 5 000 DOF (ARPACK also at 20 000). The dense solver runs only once at 5 000 DOF:
// it takes one to two minutes at -O3 (n³ scaling), which is the point of the ARPACK path.
//
// System: a seeded random "beam-like" banded pencil — springs k·U(0.5, 1.5) between every pair of
// DOFs at distance 1..3 (half-bandwidth 3, 7 non-zeros per row like a 2-DOF-per-node beam), no
// ground (one rigid-body mode, K singular), masses m·U(0.5, 2) plus a consistent coupling between
// neighbours (tridiagonal SPD M). A second-order (chain-like) operator is used rather than a
// fourth-order beam: a 2 500-node Euler–Bernoulli beam has λ_1/λ_max ~ 1e-13, where the dense
// reference itself has no correct digit left in the lowest modes.
//
// At 12 DOF ARPACK computes min(20, n/2) = 6 modes (it needs num_modes < ncv ≤ n).
// Counters: op = applications of (K − σM)⁻¹M, restarts = ARPACK iterations, rel_diff = max relative
// difference of the lowest nonzero eigenvalues ARPACK vs dense (sizes ≤ 1 000; computed outside the
// timed loop).
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/eigen_solvers_benchmark
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/numerics/symmetric_eigen.hpp"
#include "support/pencils.hpp"

namespace geardyn {
namespace {

// The same seeded random banded pencil as the eigen tests (half-bandwidth 3, one rigid mode).
test::Pencil MakeBandedPencil(int n) {
  return test::MakeRandomBanded(n, /*bandwidth=*/3, 0x65617231U + static_cast<unsigned>(n));
}

int NumModes(int n) { return std::min(20, n / 2); }

void BM_DenseAllModes(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const test::Pencil p = MakeBandedPencil(n);
  const MatrixX K(p.K), M(p.M);
  for (auto _ : state) {
    GeneralizedEigenResult r = SolveGeneralizedEigenDense(K, M);
    benchmark::DoNotOptimize(r.eigenvalues.data());
    benchmark::DoNotOptimize(r.vectors.data());
    if (!r.summary.ok()) state.SkipWithError(r.summary.message.c_str());
  }
  state.counters["dofs"] = n;
}
BENCHMARK(BM_DenseAllModes)->Arg(12)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
// One timed run at 5 000 DOF (one to two minutes at -O3); skip it with
// --benchmark_filter=-BM_DenseAllModes/5000.
BENCHMARK(BM_DenseAllModes)->Arg(5000)->Iterations(1)->Unit(benchmark::kMillisecond);

void BM_ArpackLowestModes(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const int modes = NumModes(n);
  const test::Pencil p = MakeBandedPencil(n);
  GeneralizedEigenResult last;
  for (auto _ : state) {
    last = SolveGeneralizedEigenArpack(p.K, p.M, modes);
    benchmark::DoNotOptimize(last.eigenvalues.data());
    benchmark::DoNotOptimize(last.vectors.data());
    if (!last.summary.ok()) state.SkipWithError(last.summary.message.c_str());
  }
  state.counters["dofs"] = n;
  state.counters["modes"] = modes;
  state.counters["op"] = static_cast<double>(last.summary.counters["operator_applications"]);
  state.counters["restarts"] = static_cast<double>(last.summary.counters["iterations"]);
  if (n <= 1000) {
    GeneralizedEigenOptions options;
    options.compute_vectors = false;
    const GeneralizedEigenResult dense =
        SolveGeneralizedEigenDense(MatrixX(p.K), MatrixX(p.M), options);
    double worst = 0.0;
    for (int j = 0; j < modes; ++j) {
      const double reference = dense.eigenvalues(j);
      if (reference == 0.0) continue;  // the rigid mode: exactly 0 in both (checked in the tests)
      worst = std::max(worst, std::abs(last.eigenvalues(j) - reference) / reference);
    }
    state.counters["rel_diff"] = worst;
  }
}
BENCHMARK(BM_ArpackLowestModes)
    ->Arg(12)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(5000)
    ->Arg(20000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
