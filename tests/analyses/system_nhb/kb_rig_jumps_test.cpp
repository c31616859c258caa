/// @file
/// @brief The Kahraman–Blankenship rig's primary-resonance jumps (docs/benchmarks.md, "The rig's
/// DTE curves": 2 687 Hz up, 1 942 Hz down at 100 N·m) pinned against an independent slow
/// stepped-sweep time integration (GSL rk8pd on all DOFs, system_time_integration.hpp), with the
/// exact jump count the physics fixes over the range.
///
/// * Count: between the super-harmonic resonance (jumps near 1 475 / 1 229 Hz) and the mesh mode
///   (3 379 Hz), the softening primary resonance is one S-shaped curve: exactly two folds, i.e.
///   one up-sweep jump and one down-sweep jump, over [1 800, 2 800] Hz.
/// * Sweeps: between the folds both orbits attract (from rest the rig lands on the large one), so
///   each sweep starts on the HB orbit of the branch it is to leave, 10 steps before the fold;
///   the integration first confirms that the orbit is an attracting periodic solution of its own
///   equation (RMS within 2 %), then steps the mesh frequency towards the fold with the state and
///   the mesh phase carried over, and leaves the branch in the first step past the fold. Where
///   it jumps is decided by the integration alone.
/// * Tolerance: the integration leaves the branch within one step past the fold (the slow
///   passage past a saddle-node lingers near its ghost for a few periods only), so the step
///   midpoint is compared: ≤ half a step (0.1 %) plus the fold shift of H = 16 against the
///   converged H (≲ 0.1 %, docs/benchmarks.md, the rig's H table) plus margin: kJumpTol = 0.25 %.
///   Measured: up 2 687.0 (integration) vs 2 689.3 Hz (HB), down 1 942.1 vs 1 942.4 Hz.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "analyses/system_nhb/kb_rig_fixture.hpp"
#include "analyses/system_nhb/system_time_integration.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"

namespace geardyn {
namespace {

constexpr double kStepHz = 4.0;        // sweep step of the time integration
constexpr int kSettlePeriods = 40;     // per step: ≈ 15 decay times of the mesh mode (ζ = 0.05)
constexpr int kRecordPeriods = 4;      // RMS over the last periods of each step
constexpr int kSamplesPerPeriod = 32;  // DTE samples per recorded period
constexpr double kJumpTol = 2.5e-3;    // relative, see the file comment
constexpr double kTiTol = 1e-8;        // rk8pd tolerance: the jumps are O(1) changes of the RMS

// Stepped sweep from f0 by ±kStepHz until the RMS DTE changes by the factor `ratio` (> 1: up,
// < 1: down) from one step to the next; returns the midpoint of that step, or NaN.
double SweepToJump(testing::SystemTimeIntegrator& ti, VectorX* y, double f0, double direction,
                   double ratio, double f_limit, double first_rms) {
  double previous = first_rms;
  for (double f = f0 + direction * kStepHz; direction * (f_limit - f) >= 0.0;
       f += direction * kStepHz) {
    const testing::SystemTiStats st =
        ti.Continue(f, kSettlePeriods, kRecordPeriods, kSamplesPerPeriod, y, kTiTol);
    if (!st.ok) return std::nan("");
    std::printf("  %.1f Hz: RMS DTE %.4g m, contact loss %.3f\n", f, st.rms,
                st.contact_loss_fraction);
    if (ratio > 1.0 ? st.rms > ratio * previous : st.rms < ratio * previous) {
      return f - 0.5 * direction * kStepHz;
    }
    previous = st.rms;
  }
  return std::nan("");
}

// Starts the integration on the HB orbit of the branch the sweep leaves (the stable point
// nearest 10 steps before the fold with the smallest RMS for the lower branch, the largest for
// the upper one), checks that the integration keeps it (an attracting orbit of its own
// equation), then sweeps towards the fold until it jumps, and compares the frequencies.
void SweepFromBranch(const SystemModel& model, const SystemNhbCurve& c, const SystemNhbJump& jump,
                     bool lower) {
  const double direction = jump.up_sweep ? 1.0 : -1.0;
  const double target = jump.mesh_frequency_hz - direction * 10.0 * kStepHz;
  const SystemNhbPoint* start = nullptr;
  for (const SystemNhbPoint& p : c.points) {
    if (p.point.stable != FloquetVerdict::kStable ||
        std::abs(p.mesh_frequency_hz - target) > kStepHz)
      continue;
    const double rms = p.meshes[0].rms_dte;
    if (start == nullptr ||
        (lower ? rms < start->meshes[0].rms_dte : rms > start->meshes[0].rms_dte)) {
      start = &p;
    }
  }
  ASSERT_NE(start, nullptr) << "no stable HB point near " << target << " Hz";
  testing::SystemTimeIntegrator ti(model);
  VectorX y = ti.StateFromHarmonics(start->response, start->mesh_frequency_hz, c.period_multiple);
  const testing::SystemTiStats first = ti.Continue(start->mesh_frequency_hz, kSettlePeriods,
                                                   kRecordPeriods, kSamplesPerPeriod, &y, kTiTol);
  ASSERT_TRUE(first.ok);
  std::printf("%s-sweep from %.1f Hz: RMS DTE %.4g m (HB %.4g m; fold %.1f Hz, %.4g -> %.4g m)\n",
              jump.up_sweep ? "up" : "down", start->mesh_frequency_hz, first.rms,
              start->meshes[0].rms_dte, jump.mesh_frequency_hz, jump.rms_dte_before,
              jump.rms_dte_after);
  EXPECT_NEAR(first.rms, start->meshes[0].rms_dte, 0.02 * start->meshes[0].rms_dte);
  const double f_ti =
      SweepToJump(ti, &y, start->mesh_frequency_hz, direction, jump.up_sweep ? 1.5 : 1.0 / 1.5,
                  jump.mesh_frequency_hz + direction * 60.0, first.rms);
  ASSERT_TRUE(std::isfinite(f_ti)) << "the time integration did not jump";
  EXPECT_NEAR(f_ti, jump.mesh_frequency_hz, kJumpTol * jump.mesh_frequency_hz)
      << "time integration " << f_ti << " Hz, HB " << jump.mesh_frequency_hz << " Hz";
}

TEST(KbRigJumps, PrimaryJumpsMatchASlowTimeIntegrationSweep) {
  const SystemModel model = testing::KbRigSliceModel(100.0);
  SystemNhbOptions o;
  o.hb.harmonics = 16;
  o.start_hz = 1800.0;
  o.end_hz = 2800.0;
  o.continuation.max_step = 0.1;
  o.continuation.max_tangent_angle = 0.4;
  o.compute_element_forces = false;
  o.keep_response = true;
  const SystemNhbCurve c = TraceSystemNonlinearHb(model, o);
  ASSERT_TRUE(c.summary.ok()) << c.summary.BriefReport();

  // Exactly one up-sweep and one down-sweep jump (the two folds of the S-curve).
  ASSERT_EQ(c.jumps.size(), 2u);
  ASSERT_EQ(c.fold_frequencies_hz.size(), 2u);
  const SystemNhbJump& up = c.jumps[0].up_sweep ? c.jumps[0] : c.jumps[1];
  const SystemNhbJump& down = c.jumps[0].up_sweep ? c.jumps[1] : c.jumps[0];
  ASSERT_TRUE(up.up_sweep && !down.up_sweep);
  EXPECT_LT(down.mesh_frequency_hz, up.mesh_frequency_hz);  // hysteresis of a softening mesh
  // The documented values (docs/benchmarks.md, H = 24) within the H = 16 fold shift.
  EXPECT_NEAR(up.mesh_frequency_hz, 2687.0, 1e-3 * 2687.0);
  EXPECT_NEAR(down.mesh_frequency_hz, 1942.0, 1e-3 * 1942.0);

  // Up-sweep from the small-amplitude orbit 40 Hz below the upper fold (from rest the rig lands
  // on the large one there: both are attracting between the folds).
  SweepFromBranch(model, c, up, /*lower=*/true);
  // Down-sweep from the large-amplitude orbit 40 Hz above the lower fold.
  SweepFromBranch(model, c, down, /*lower=*/false);
}

}  // namespace
}  // namespace geardyn
