// Micro-benchmark of one time-domain evaluation (analyses/src/time_domain/td_system.hpp) of the
// Kahraman–Blankenship rig with model = "contact" (Kim's law, 100 N·m): what a time integrator
// pays per stage (explicit: EvalForces + the mass solve M⁻¹f) or per Newton iteration (implicit:
// EvalForces with the sparse tangents as generalized-α asks for them, the iteration matrix
// assembled from the triplets and factored by SparseLU). At the static equilibrium θ₀ = 2 rad
// (two pairs in contact), small velocities.
// Arguments: tooth type (0 rigid, 1 revolute = Kim's type A, 2 bushing = type B); teeth per gear
// (20, 50, 100: the module scaled to keep the 150 mm centre distance); mode (0 explicit,
// 1 implicit with the dense tangent and LU as before, 2 implicit sparse, 3 explicit with the
// dense products and LDLT solve of before emulated: the sparse evaluation plus K0x, C0v, vᵀC0v
// as dense n × n products and the dense LDLT solve, i.e. the old cost within a few sparse
// products).
//
// Run: build with -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/td_evaluation_benchmark
#include <benchmark/benchmark.h>

#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "../../../analyses/src/time_domain/td_system.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {
namespace {

SystemModel Rig(int type, int teeth) {
  const char* names[3] = {"rigid", "revolute", "bushing"};
  const double module = 0.150 / teeth;  // centre distance 150 mm
  std::vector<std::string> set = {
      "mesh.pinion-wheel.model=\"contact\"",
      std::string("mesh.pinion-wheel.contact.teeth=\"") + names[type] + "\""};
  if (type > 0) {  // Kim Table 3 in SI
    set.push_back("mesh.pinion-wheel.contact.bending_stiffness=11.5e3");
    set.push_back("mesh.pinion-wheel.contact.bending_damping=2e-4");
  }
  for (const char* g : {"pinion", "wheel"}) {
    const std::string p = std::string("gear.") + g + ".";
    set.push_back(p + "teeth=" + std::to_string(teeth));
    set.push_back(p + "normal_module=" + std::to_string(module));
    set.push_back(p + "tip_diameter=" + std::to_string(module * (teeth + 2)));
  }
  SceneSystemOptions so;
  so.analysis = "td_evaluation_benchmark";
  so.allow_contact_meshes = true;
  return MakeSystemModel(LoadScene("builtin:kahraman-blankenship-rig", set), so);
}

void BM_TdEvaluation(benchmark::State& state) {
  const int type = static_cast<int>(state.range(0));
  const int teeth = static_cast<int>(state.range(1));
  const int mode = static_cast<int>(state.range(2));
  SystemModel model;
  try {
    model = Rig(type, teeth);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const internal::TdSystem sys(model);
  internal::TdWorkspace ws(sys);
  const double theta = 2.0, rate = 2.0 * 3.141592653589793 * 2000.0;
  const internal::TdStatic st = internal::SolveStatic(sys, ws, theta);
  if (!st.ok) {
    state.SkipWithError(st.message.c_str());
    return;
  }
  const VectorX v = VectorX::Constant(sys.n, 1e-4);
  VectorX acc(sys.n);
  ws.sparse_tangents = mode == 2;
  std::vector<Eigen::Triplet<double>> trip;
  SparseMatrix jac(sys.n, sys.n);
  Eigen::SparseLU<SparseMatrix> lu;
  const double ck = 1e-12, cc = 1e-6;  // β h², γ h of a 1 µs step (orders only)
  for (auto _ : state) {
    internal::EvalForces(sys, ws, theta, rate, st.x, v, mode == 1 || mode == 2);
    if (mode == 0) {
      sys.mass_solver->Solve(ws.force, &acc);
    } else if (mode == 3) {
      const VectorX f = sys.load0 - sys.stiffness0 * st.x - sys.damping0 * v;
      benchmark::DoNotOptimize(f.data());
      benchmark::DoNotOptimize(v.dot(sys.damping0 * v));
      acc = sys.mass_ldlt->solve(ws.force);
    } else if (mode == 1) {
      const MatrixX j = sys.mass + ck * ws.tangent_k + cc * ws.tangent_c;
      acc = Eigen::PartialPivLU<MatrixX>(j).solve(ws.force);
    } else {
      trip.clear();
      internal::AppendTriplets(sys.mass_sparse, 1.0, &trip);
      for (const auto& e : ws.tangent_k_triplets)
        trip.emplace_back(e.row(), e.col(), ck * e.value());
      for (const auto& e : ws.tangent_c_triplets)
        trip.emplace_back(e.row(), e.col(), cc * e.value());
      jac.setFromTriplets(trip.begin(), trip.end());
      lu.compute(jac);
      acc = lu.solve(ws.force);
    }
    benchmark::DoNotOptimize(acc.data());
  }
  state.counters["coords"] = sys.n;
  state.counters["contacts"] = ws.contacts[0];
}
BENCHMARK(BM_TdEvaluation)
    ->ArgsProduct({{0, 1, 2}, {20, 50, 100}, {0}})
    ->ArgsProduct({{0, 1, 2}, {50}, {3}})
    ->ArgsProduct({{1, 2}, {50}, {1, 2}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
