/// @file
/// @brief `simulate`'s engine on the Kahraman–Blankenship rig against the frequency-domain
/// analyses of the same scene (a different method on the same equation):
/// * the LTV mesh (model = blankenship_singh, ζ_m = 0.05): steady-state DTE RMS and mean equal
///   the linear harmonic balance's (converged in H);
/// * the slice mesh with contact loss (kb_rig_fixture.hpp): steady state at a contact-loss and
///   a full-contact frequency equals the nonlinear HB orbit; stepped up and down sweeps jump
///   where the nonlinear HB's folds are (within 2 %), finding both branches;
/// * the energy balance of every integrated period below 1e-4 of its work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "analyses/system_nhb/kb_rig_fixture.hpp"
#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "support/sweep_jumps.hpp"

namespace geardyn {
namespace {

SystemModel KbRigLtvModel(double torque = 100.0) {
  const std::string t = std::to_string(torque);
  return BuildSceneSystem(LoadScene("builtin:kahraman-blankenship-rig",
                                    {"mesh.pinion-wheel.model=\"blankenship_singh\"",
                                     "mesh.pinion-wheel.damping_ratio=0.05",
                                     "operating_point.torque=" + t, "load.brake.torque=" + t}))
      .model;
}

TimeResponseOptions Options(TimeIntegrator method) {
  TimeResponseOptions o;
  o.integration.integrator = method;
  o.integration.relative_tolerance = method == TimeIntegrator::kRungeKutta ? 1e-9 : 1e-8;
  o.integration.absolute_tolerance = o.integration.relative_tolerance;
  o.steady.tolerance = 1e-7;
  return o;
}

TEST(RigTimeResponse, LtvSteadyStateEqualsLinearHarmonicBalance) {
  const SystemModel model = KbRigLtvModel();
  for (TimeIntegrator method : {TimeIntegrator::kRungeKutta, TimeIntegrator::kGeneralizedAlpha}) {
    for (double f : {1500.0, 3000.0}) {
      HbOptions hb;
      hb.harmonics = 64;
      const HbResult h = SolveHarmonicBalance(model, hb, f);
      ASSERT_TRUE(h.summary.ok()) << h.summary.BriefReport();
      const TimeResponse r = SimulateSteadyState(model, f, Options(method));
      ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
      std::printf(
          "%s %.0f Hz: RMS %.6g (HB %.6g), mean %.6g (HB %.6g), %d periods, %ld steps, "
          "energy %.2g, %.3f s\n",
          ToString(method), f, r.meshes[0].rms_dte, h.meshes[0].rms_dte, r.meshes[0].mean_dte,
          h.meshes[0].mean_dte, r.periods, r.steps, r.max_energy_error, r.summary.wall_time_s);
      EXPECT_NEAR(r.meshes[0].rms_dte, h.meshes[0].rms_dte, 1e-3 * h.meshes[0].rms_dte);
      EXPECT_NEAR(r.meshes[0].mean_dte, h.meshes[0].mean_dte, 1e-4 * h.meshes[0].mean_dte);
      EXPECT_NEAR(r.meshes[0].peak_to_peak_dte, h.meshes[0].peak_to_peak_dte,
                  5e-3 * h.meshes[0].peak_to_peak_dte);
      EXPECT_LT(r.max_energy_error, 1e-4);
    }
  }
}

TEST(RigTimeResponse, SliceSteadyStateEqualsNonlinearHarmonicBalance) {
  const SystemModel model = testing::KbRigSliceModel();
  for (double f : {900.0, 1700.0}) {
    SystemNhbOptions o;
    o.hb.harmonics = 32;
    Summary summary;
    const SystemNhbPoint hb = SolveSystemNonlinearHb(model, f, o, &summary);
    ASSERT_TRUE(summary.ok()) << summary.BriefReport();
    ASSERT_EQ(hb.point.stable, FloquetVerdict::kStable);
    const TimeResponse r = SimulateSteadyState(model, f, Options(TimeIntegrator::kRungeKutta));
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    const MeshTimeHistory& m = r.meshes[0];
    std::printf(
        "%.0f Hz: RMS %.6g (HB %.6g), loss %.3f (HB %.3f), %d periods, %ld steps, %ld "
        "events, energy %.2g, %.3f s\n",
        f, m.rms_dte, hb.meshes[0].rms_dte, m.contact_loss_fraction,
        hb.meshes[0].contact_loss_fraction, r.periods, r.steps, r.events, r.max_energy_error,
        r.summary.wall_time_s);
    EXPECT_NEAR(m.rms_dte, hb.meshes[0].rms_dte, 0.01 * hb.meshes[0].rms_dte);
    EXPECT_NEAR(m.mean_dte, hb.meshes[0].mean_dte, 0.01 * std::abs(hb.meshes[0].mean_dte));
    EXPECT_NEAR(m.contact_loss_fraction, hb.meshes[0].contact_loss_fraction, 0.03);
    EXPECT_LT(r.max_energy_error, 1e-4);
  }
}

using test::JumpFrequency;

// The softening primary resonance of the slice rig (kb_rig_jumps_test.cpp): the up sweep stays
// on the small-amplitude branch up to its fold and jumps up, the down sweep (from the up sweep's
// end state) stays on the large-amplitude branch down to its fold and jumps down; both jump
// frequencies within 2 % of the nonlinear HB's folds (issue 14, "Must show").
TEST(RigTimeResponse, SweepsFindBothBranchesOfTheSliceJump) {
  const SystemModel model = testing::KbRigSliceModel(100.0);
  SystemNhbOptions o;
  o.hb.harmonics = 16;
  o.start_hz = 1800.0;
  o.end_hz = 2800.0;
  o.continuation.max_step = 0.1;
  o.continuation.max_tangent_angle = 0.4;
  o.compute_element_forces = false;
  const SystemNhbCurve c = TraceSystemNonlinearHb(model, o);
  ASSERT_TRUE(c.summary.ok()) << c.summary.BriefReport();
  ASSERT_EQ(c.jumps.size(), 2u);
  const SystemNhbJump& up = c.jumps[0].up_sweep ? c.jumps[0] : c.jumps[1];
  const SystemNhbJump& down = c.jumps[0].up_sweep ? c.jumps[1] : c.jumps[0];
  ASSERT_TRUE(up.up_sweep && !down.up_sweep);

  std::vector<double> f;
  for (double x = 1850.0; x <= 2800.0 + 1e-9; x += 10.0) f.push_back(x);
  TimeSweepOptions s;
  s.response = Options(TimeIntegrator::kAuto);
  s.response.steady.tolerance = 1e-6;
  const TimeSweep sweep = SimulateSweep(model, f, s);
  ASSERT_TRUE(sweep.summary.ok()) << sweep.summary.BriefReport();
  ASSERT_EQ(sweep.points.size(), 2 * f.size());
  double worst_energy = 0.0;
  for (const TimeSweepPoint& p : sweep.points) {
    EXPECT_EQ(p.steady, SteadyVerdict::kSteady) << p.mesh_frequency_hz << " Hz";
    worst_energy = std::max(worst_energy, p.max_energy_error);
  }
  EXPECT_LT(worst_energy, 1e-4);
  const double f_up = JumpFrequency(sweep, SweepBranch::kUp, 1.5);
  const double f_down = JumpFrequency(sweep, SweepBranch::kDown, 1.0 / 1.5);
  std::printf("jumps: up %.1f Hz (HB %.1f), down %.1f Hz (HB %.1f); %.2f s, %ld steps\n", f_up,
              up.mesh_frequency_hz, f_down, down.mesh_frequency_hz, sweep.summary.wall_time_s,
              sweep.summary.counters.at("steps"));
  EXPECT_NEAR(f_up, up.mesh_frequency_hz, 0.02 * up.mesh_frequency_hz);
  EXPECT_NEAR(f_down, down.mesh_frequency_hz, 0.02 * down.mesh_frequency_hz);
  // Both branches at one frequency inside the hysteresis loop: the up sweep's small orbit and
  // the down sweep's large one.
  const auto at = [&](SweepBranch b, double hz) {
    for (const TimeSweepPoint& p : sweep.points)
      if (p.branch == b && std::abs(p.mesh_frequency_hz - hz) < 1e-6) return p.rms_dte[0];
    return std::nan("");
  };
  EXPECT_GT(at(SweepBranch::kDown, 2300.0), 1.5 * at(SweepBranch::kUp, 2300.0));
}

}  // namespace
}  // namespace geardyn
