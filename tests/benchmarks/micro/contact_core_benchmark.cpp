// Micro-benchmark of the tooth-contact mesh core (contact_mesh_core.hpp): one CalcForces on the
// Kahraman–Blankenship rig (two 50-tooth spur gears, Kim's law, μ = 0.06) at a loaded state
// (1 µm along the line of action, two-pair zone), as a time integrator calls it per stage / Newton
// iteration. Arguments: teeth type (0 rigid, 1 revolute = Kim's type A, 2 bushing = type B),
// face slices, Jacobians (0/1), biarcs per flank (0: the exact involute; N: profile = "biarc").
//
// Run: build with -DCMAKE_BUILD_TYPE=Release -DGEARDYN_BUILD_BENCHMARKS=ON, then
//   ./tests/benchmarks/contact_core_benchmark
#include <benchmark/benchmark.h>

#include <cmath>

#include "geardyn/models/contact/contact_mesh_core.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

void BM_ContactCoreCalcForces(benchmark::State& state) {
  const GearPairGeometry pair = CalcGearPairGeometry(test::KimRigPair());
  const MeshFrame frame = CalcMeshFrame(pair, Vector3::Zero(), 0.0, 1);
  ContactMeshDef def;
  def.teeth = static_cast<ToothBodyType>(state.range(0));
  def.bending_stiffness = 11.5e3;
  def.bending_damping = 2e-4;
  def.friction_coefficient = 0.06;
  def.face_slices = static_cast<int>(state.range(1));
  if (state.range(3) > 0) {
    def.profile = ContactProfile::kBiarc;
    def.arcs = static_cast<int>(state.range(3));
  }
  const ContactMeshCore core(pair, frame, def);
  auto ws = core.MakeWorkspace();
  NonlinearMeshCoreOutput out = core.MakeOutput();
  VectorX x = VectorX::Zero(core.num_coordinates());
  VectorX v = VectorX::Constant(core.num_coordinates(), 1e-3);
  x(5) = 1e-6 / pair.pinion.base_radius;
  const bool jac = state.range(2) != 0;
  double theta = 2.0;
  for (auto _ : state) {
    core.CalcForces(*ws, theta, 2 * 3.141592653589793 * 2000.0, x, v, jac, &out);
    benchmark::DoNotOptimize(out.force.data());
    theta = theta == 2.0 ? 2.0 + 1e-9 : 2.0;  // a new θ each call
  }
  state.counters["coords"] = core.num_coordinates();
  state.counters["contacts"] = out.num_contacts;
}
BENCHMARK(BM_ContactCoreCalcForces)
    ->ArgsProduct({{0, 1, 2}, {1, 5}, {0, 1}, {0}})
    ->ArgsProduct({{0, 1}, {1}, {1}, {4, 32}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
