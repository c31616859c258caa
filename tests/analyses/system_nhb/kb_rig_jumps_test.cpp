/// @file
/// @brief The Kahraman–Blankenship rig's primary-resonance jumps (docs/benchmarks.md, "The rig's
/// DTE curves": 2 687 Hz up, 1 942 Hz down at 100 N·m) pinned against an independent slow
/// stepped-sweep time integration (GSL rk8pd on all DOFs, system_time_integration.hpp), with the
/// exact jump count the physics fixes over the range.
///
/// * Count: between the super-harmonic resonance (jumps near 1 475 / 1 229 Hz) and the mesh mode
///   (3 379 Hz), the softening primary resonance is one S-shaped curve: exactly two folds, i.e.
///   one up-sweep jump and one down-sweep jump, over [1 800, 2 800] Hz.
/// * Up-sweep: the integration starts from the static deflection at rest below the fold (the
///   small-amplitude branch, the only one far from the resonance) and steps the mesh frequency
///   up with the state and the mesh phase carried over; it leaves the branch in the first step
///   past the fold. Down-sweep: it starts on the large-amplitude orbit (the HB orbit; the
///   integration first confirms it is an attracting orbit of its own equation) and steps down.
/// * Tolerance: the integration jumps within (f_fold, f_fold + Δf + delay] (up) — the slow
///   passage past a saddle-node lingers near its ghost for a few periods — so the step
///   midpoint is compared; H = 16 moves the folds by ≲ 0.1 % against H = 48 (docs/benchmarks.md,
///   the rig's H table). kJumpTol = 0.4 % = 2.5 steps of 4 Hz at 2 700 Hz.
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
constexpr double kJumpTol = 4e-3;      // relative, see the file comment
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

  // Up-sweep from the static deflection at rest, 40 Hz below the fold.
  {
    testing::SystemTimeIntegrator sweep(model);
    const double f0 = up.mesh_frequency_hz - 10.0 * kStepHz;
    VectorX y = VectorX::Zero(2 * model.num_dofs());
    y.head(model.num_dofs()) = SolveStaticDeflection(model).deflection;
    const testing::SystemTiStats first =
        sweep.Continue(f0, 300, kRecordPeriods, kSamplesPerPeriod, &y, kTiTol);
    ASSERT_TRUE(first.ok);
    std::printf("up-sweep from %.1f Hz: RMS DTE %.4g m (HB fold %.1f Hz, RMS %.4g → %.4g m)\n", f0,
                first.rms, up.mesh_frequency_hz, up.rms_dte_before, up.rms_dte_after);
    const double f_ti =
        SweepToJump(sweep, &y, f0, +1.0, 1.5, up.mesh_frequency_hz + 60.0, first.rms);
    ASSERT_TRUE(std::isfinite(f_ti)) << "the time integration did not jump up";
    EXPECT_NEAR(f_ti, up.mesh_frequency_hz, kJumpTol * up.mesh_frequency_hz)
        << "time integration " << f_ti << " Hz, HB " << up.mesh_frequency_hz << " Hz";
  }

  // Down-sweep from the large-amplitude orbit 40 Hz above the lower fold.
  {
    const double target = down.mesh_frequency_hz + 10.0 * kStepHz;
    const SystemNhbPoint* start = nullptr;
    for (const SystemNhbPoint& p : c.points) {
      if (!p.point.stable || std::abs(p.mesh_frequency_hz - target) > 20.0) continue;
      if (start == nullptr || p.meshes[0].rms_dte > start->meshes[0].rms_dte) start = &p;
    }
    ASSERT_NE(start, nullptr);
    ASSERT_GT(start->meshes[0].rms_dte, 1.5 * down.rms_dte_after);  // the upper branch
    testing::SystemTimeIntegrator ti(model);
    VectorX y = ti.StateFromHarmonics(start->response, start->mesh_frequency_hz, c.period_multiple);
    const testing::SystemTiStats first = ti.Continue(start->mesh_frequency_hz, kSettlePeriods,
                                                     kRecordPeriods, kSamplesPerPeriod, &y, kTiTol);
    ASSERT_TRUE(first.ok);
    EXPECT_NEAR(first.rms, start->meshes[0].rms_dte, 0.02 * start->meshes[0].rms_dte);
    const double f_ti = SweepToJump(ti, &y, start->mesh_frequency_hz, -1.0, 0.5,
                                    down.mesh_frequency_hz - 60.0, first.rms);
    ASSERT_TRUE(std::isfinite(f_ti)) << "the time integration did not jump down";
    EXPECT_NEAR(f_ti, down.mesh_frequency_hz, kJumpTol * down.mesh_frequency_hz)
        << "time integration " << f_ti << " Hz, HB " << down.mesh_frequency_hz << " Hz";
  }
}

}  // namespace
}  // namespace geardyn
