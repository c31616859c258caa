// Micro-benchmark of the per-mesh stiffness kernel K_mesh = Gᵀ K2 G (spec 01 §3), evaluated once
// per θ-sample by every LTV analysis. Compared with the mesh Jacobian (built once per model) and
// with the same product in dynamic-size Eigen, the allocation-paying alternative.
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/mesh_stiffness_benchmark
#include <benchmark/benchmark.h>

#include <cmath>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "geardyn/models/mesh/stiffness_core.hpp"

namespace geardyn {
namespace {

// A helical external pair, right-hand pinion, arbitrary placement.
MeshFrame MakeFrame() {
  MeshPlacement p;
  p.pinion_base_radius = 0.042;
  p.gear_base_radius = 0.071;
  p.operating_pressure_angle = DegToRad(23.1);
  p.base_helix_angle = DegToRad(18.7);
  p.pinion_hand = HelixHand::kRight;
  p.pinion_center = Vector3(0.13, -0.21, 0.07);
  const double C =
      (p.pinion_base_radius + p.gear_base_radius) / std::cos(p.operating_pressure_angle);
  p.gear_center = p.pinion_center + C * Vector3(std::cos(2.31), std::sin(2.31), 0.0);
  return CalcMeshFrame(p);
}

void BM_CalcMeshStiffness(benchmark::State& state) {
  const Matrix2x12 G = CalcMeshJacobian(MakeFrame());
  Matrix2 K2 = CalcStiffnessCore(3.7e8, 0.003, 0.28, 0.012);
  for (auto _ : state) {
    benchmark::DoNotOptimize(K2.data());  // K2(θ) changes every sample
    const Matrix12 K = CalcMeshStiffness(G, K2);
    benchmark::DoNotOptimize(K.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_CalcMeshStiffness);

void BM_CalcMeshStiffnessWithCore(benchmark::State& state) {
  const Matrix2x12 G = CalcMeshJacobian(MakeFrame());
  double K = 3.7e8;
  for (auto _ : state) {
    benchmark::DoNotOptimize(K);
    const Matrix12 K_mesh = CalcMeshStiffness(G, CalcStiffnessCore(K, 0.003, 0.28, 0.012));
    benchmark::DoNotOptimize(K_mesh.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_CalcMeshStiffnessWithCore);

void BM_DynamicSizeBaseline(benchmark::State& state) {
  const MatrixX G = CalcMeshJacobian(MakeFrame());
  MatrixX K2 = CalcStiffnessCore(3.7e8, 0.003, 0.28, 0.012);
  for (auto _ : state) {
    benchmark::DoNotOptimize(K2.data());
    const MatrixX K = G.transpose() * K2 * G;  // allocates temporaries and the result
    benchmark::DoNotOptimize(K.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_DynamicSizeBaseline);

void BM_CalcMeshJacobian(benchmark::State& state) {
  const MeshFrame frame = MakeFrame();
  for (auto _ : state) {
    const Matrix2x12 G = CalcMeshJacobian(frame);
    benchmark::DoNotOptimize(G.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_CalcMeshJacobian);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
