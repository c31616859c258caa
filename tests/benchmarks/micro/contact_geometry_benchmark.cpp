// Micro-benchmark of the contact simulator's geometry kernels (spec 03; geardyn/models/contact/):
//  * InvoluteContact — one flank–flank evaluation (closed form, with derivatives);
//  * TipCornerContact — one tip-corner–flank evaluation (closed form);
//  * BiarcContact/N — the same contact with Kim's biarc flanks (N biarcs per flank, all arcs);
//  * BiarcContactNear/N — the same with the O(1) lookup from the exact kernel's rolls, the
//    exact kernel included (as the contact core calls it);
//  * Presearch — the candidate tooth pairs of the rig (50/50 teeth) at one phase;
//  * EvalToothPair — one pair in one slice through the mesh kinematics (poses, kernel, chain rule
//    to the 12 body coordinates, θ and the tooth DOFs), spur (rig) and helical (21/37, β 20°)
//    rigid, and spur with deflected teeth;
//  * RigSlice — pre-search plus both flanks of every candidate pair: one slice of the rig.
// Kahraman–Blankenship rig as in Kim et al. (2015): m 3 mm, z 50/50, α 20°, r_a 78 mm.
//
// Run: build with -DGEARDYN_BUILD_BENCHMARKS=ON (Release), then
//   ./tests/benchmarks/contact_geometry_benchmark
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <numbers>

#include "geardyn/models/contact/biarc_profile.hpp"
#include "geardyn/models/contact/contact_presearch.hpp"
#include "geardyn/models/contact/involute_contact.hpp"
#include "geardyn/models/contact/mesh_kinematics.hpp"
#include "geardyn/models/contact/tip_corner_contact.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

struct FlankPair {
  InvoluteFlankPose a, b;
};

// The rig's flanks touching at mid path on the ε = −1 tangent.
FlankPair RigFlanks(const test::ContactPairSetup& s) {
  const double r1 = s.pinion.base_radius, r2 = s.gear.base_radius, c = 0.150;
  const double alpha = std::acos((r1 + r2) / c), length = std::sqrt(c * c - (r1 + r2) * (r1 + r2));
  const double rho1 = 0.5 * length, rho2 = length - rho1 + 5e-6;
  FlankPair f{MakeFlankPose(s.pinion, Vector2::Zero(), 0.0, -1),
              MakeFlankPose(s.gear, Vector2(c, 0.0), 0.0, -1)};
  f.a.base_angle = -alpha + rho1 / r1;
  f.b.base_angle = -alpha + std::numbers::pi + rho2 / r2;
  return f;
}

void BM_InvoluteContact(benchmark::State& state) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  FlankPair f = RigFlanks(s);
  for (auto _ : state) {
    f.a.base_angle += 1e-12;
    benchmark::DoNotOptimize(CalcInvoluteContact(f.a, f.b));
  }
}
BENCHMARK(BM_InvoluteContact);

void BM_TipCornerContact(benchmark::State& state) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  FlankPair f = RigFlanks(s);
  for (auto _ : state) {
    f.a.base_angle += 1e-12;
    benchmark::DoNotOptimize(CalcTipCornerContact(f.a, 0.2e-3, f.b));
  }
}
BENCHMARK(BM_TipCornerContact);

void BM_BiarcContact(benchmark::State& state) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  FlankPair f = RigFlanks(s);
  const int n = static_cast<int>(state.range(0));
  const BiarcFlank a(s.pinion, -1, n), b(s.gear, -1, n);
  for (auto _ : state) {
    f.a.base_angle += 1e-12;
    benchmark::DoNotOptimize(CalcBiarcContact(a, f.a, b, f.b));
  }
  state.counters["max_dev_m"] = a.max_deviation();
}
BENCHMARK(BM_BiarcContact)->Arg(4)->Arg(8)->Arg(16);

void BM_BiarcContactNear(benchmark::State& state) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  FlankPair f = RigFlanks(s);
  const int n = static_cast<int>(state.range(0));
  const BiarcFlank a(s.pinion, -1, n), b(s.gear, -1, n);
  for (auto _ : state) {
    f.a.base_angle += 1e-12;
    const FlankContact t = CalcInvoluteContact(f.a, f.b);
    benchmark::DoNotOptimize(CalcBiarcContactNear(a, f.a, t.roll1, b, f.b, t.roll2));
  }
}
BENCHMARK(BM_BiarcContactNear)->Arg(4)->Arg(8)->Arg(16)->Arg(32);

void BM_Presearch(benchmark::State& state) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 1);
  const auto [p1, p2] = kin.SlicePoses(Vector12::Zero(), 1.3, 0);
  std::array<ToothPairCandidate, 64> buf;
  for (auto _ : state)
    benchmark::DoNotOptimize(FindCandidatePairs(s.pinion, p1.layout, s.gear, p2.layout, 0.01, buf));
}
BENCHMARK(BM_Presearch);

// Arg: 0 spur rigid teeth, 1 helical rigid teeth, 2 spur deflected teeth (type A/B state).
void BM_EvalToothPair(benchmark::State& state) {
  const bool helical = state.range(0) == 1;
  ToothPairState teeth;
  teeth.pinion = {1e-5, 1e-7, -1e-7};
  const ToothPairState* deflected = state.range(0) == 2 ? &teeth : nullptr;
  const auto s = test::MakeContactPair(helical ? test::HelicalPair() : test::KimRigPair());
  const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 1);
  Vector12 q = Vector12::Constant(1e-6);
  double theta = 0.3;
  for (auto _ : state) {
    theta += 1e-9;
    benchmark::DoNotOptimize(
        kin.EvalToothPair(q, theta, 0, 0, 0, FlankSide::kDrive, nullptr, 0.0, deflected));
  }
}
BENCHMARK(BM_EvalToothPair)->Arg(0)->Arg(1)->Arg(2);

void BM_RigSlice(benchmark::State& state) {
  const auto s = test::MakeContactPair(test::KimRigPair(150.2));
  const ContactMeshKinematics kin(s.pair, s.frame, s.pinion, s.gear, 1);
  Vector12 q = Vector12::Constant(1e-6);
  double theta = 0.3;
  std::array<ToothPairCandidate, 64> buf;
  int evaluations = 0;
  for (auto _ : state) {
    theta += 1e-3;
    const auto [p1, p2] = kin.SlicePoses(q, theta, 0);
    const int n = FindCandidatePairs(s.pinion, p1.layout, s.gear, p2.layout, 0.01, buf);
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
      for (FlankSide side : {FlankSide::kDrive, FlankSide::kCoast}) {
        sum += kin.EvalToothPair(q, theta, 0, buf[k].tooth1, buf[k].tooth2, side).penetration;
        ++evaluations;
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["pairs_per_slice"] =
      benchmark::Counter(evaluations, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_RigSlice);

}  // namespace
}  // namespace geardyn

BENCHMARK_MAIN();
