// Work-precision of the contact profile (issue 14, spec 03: "exact involute vs biarc contact"),
// at the core level: the Kahraman–Blankenship rig's pair (two 50-tooth spur gears, m = 3 mm),
// rigid teeth, Kim's law, 100 N·m. For each profile (exact involute; Kim's biarcs with
// N = 2 … 32 per flank) the loaded static transmission error at 64 phases of a mesh cycle (Newton
// on the pinion moment, to 1e-9 of the load: the round-off floor is ≈ 1e-11) and the cost of one
// ContactMeshCore::CalcForces with Jacobians at those states (what an implicit integrator calls per
// iteration). Error = RMS over the cycle of STE − STE_exact [m] (the exact involute is the
// converged reference: both models approximate it); knob = N (0: exact). Output: CSV `method, knob,
// wall_time_s, error, evaluations` (wp_common.hpp), wall time per evaluation; then, as comments,
// the largest error and the flank deviations.
#include <cmath>
#include <cstdio>
#include <vector>

#include "geardyn/models/contact/biarc_profile.hpp"
#include "geardyn/models/contact/contact_mesh_core.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "support/contact_pairs.hpp"
#include "wp_common.hpp"

namespace {

using namespace geardyn;

constexpr int kPhases = 64;
constexpr double kTorque = 100.0;  // N·m on the pinion

GearPairGeometry RigPair() { return CalcGearPairGeometry(test::KimRigPair()); }

double Phase(int i) { return -std::acos(-1.0) + 2.0 * std::acos(-1.0) * (i + 0.5) / kPhases; }

// Pinion rotation x(5) carrying the torque at phase θ (rigid teeth: one unknown), by Newton.
struct StaticPoint {
  VectorX x;
  double ste = 0.0;  // r_b1 x(5) [m]
  bool converged = false;
};
StaticPoint SolveStatic(const ContactMeshCore& core, NonlinearMeshCoreWorkspace& ws, double theta) {
  NonlinearMeshCoreOutput out = core.MakeOutput();
  const double rb1 = core.kinematics().pinion().base_radius;
  StaticPoint p;
  p.x = VectorX::Zero(core.num_coordinates());
  const VectorX v = VectorX::Zero(core.num_coordinates());
  p.x(5) = 1e-6 / rb1;
  for (int it = 0; it < 60; ++it) {
    core.CalcForces(ws, theta, 0.0, p.x, v, true, &out);
    const double residual = -out.force(5) - kTorque;
    if (std::abs(residual) < 1e-9 * kTorque) {
      p.converged = true;
      break;
    }
    p.x(5) -= residual / out.stiffness(5, 5);
  }
  p.ste = rb1 * p.x(5);
  return p;
}

}  // namespace

int main() {
  const GearPairGeometry pair = RigPair();
  const MeshFrame frame = CalcMeshFrame(pair, Vector3::Zero(), 0.0, 1);
  ContactMeshDef def;  // Kim's law (Eq. 12), rigid teeth, one face slice
  std::vector<double> reference(kPhases);
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  for (const int n : {0, 2, 4, 8, 16, 32}) {
    def.profile = n == 0 ? ContactProfile::kInvolute : ContactProfile::kBiarc;
    def.arcs = n == 0 ? 4 : n;
    const ContactMeshCore core(pair, frame, def);
    auto ws = core.MakeWorkspace();
    std::vector<VectorX> states;
    double sum2 = 0.0, worst = 0.0;
    bool all_converged = true;
    for (int i = 0; i < kPhases; ++i) {
      const StaticPoint p = SolveStatic(core, *ws, Phase(i));
      all_converged = all_converged && p.converged;
      if (n == 0) reference[i] = p.ste;
      const double e = p.ste - reference[i];
      sum2 += e * e;
      worst = std::max(worst, std::abs(e));
      states.push_back(p.x);
    }
    NonlinearMeshCoreOutput out = core.MakeOutput();
    const VectorX v = VectorX::Constant(core.num_coordinates(), 1e-3);
    const double time = wp::TimeIt([&] {
      for (int i = 0; i < kPhases; ++i) {
        core.CalcForces(*ws, Phase(i), 2.0 * std::acos(-1.0) * 2000.0, states[i], v, true, &out);
      }
    });
    wp::Row(n == 0 ? "exact" : "biarc", n, time / kPhases, std::sqrt(sum2 / kPhases), kPhases);
    const double dev = n == 0 ? 0.0
                              : BiarcFlank(core.kinematics().pinion(), -1, n).max_deviation() +
                                    BiarcFlank(core.kinematics().gear(), -1, n).max_deviation();
    std::printf("# N=%d: max |STE error| %.3e m, flank deviations (sum) %.3e m%s\n", n, worst, dev,
                all_converged ? "" : ", NEWTON NOT CONVERGED at some phase");
  }
  std::printf("# reference mean STE (exact involute) %.6e m\n", [&] {
    double s = 0.0;
    for (const double r : reference) s += r;
    return s / kPhases;
  }());
  return 0;
}
