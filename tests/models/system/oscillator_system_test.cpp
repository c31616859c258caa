// The oscillator scene's SystemModel (MakeOscillatorSystemModel) against independent truths:
// the bare B&K NhbProblem (MakeClearanceOscillator) for the nonlinear HB that `geardyn hb` runs,
// the closed-form FRF for the linear oscillator, 1 Hz for its mode, and the Mathieu system
// (MakeMathieuSystem) and the first-order principal-tongue threshold α = 4ζ for its Floquet.
#include "geardyn/models/system/oscillator_system.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/floquet_system.hpp"
#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"

namespace geardyn {
namespace {

constexpr double kWn = 2.0 * std::numbers::pi;  // ω_n of the model [rad/s]

OscillatorDef BlankenshipKahraman() {
  OscillatorDef o;
  o.zeta = 0.05;
  o.alpha = 0.2;
  o.mean_force = 0.1;
  o.alternating_force = 0.02;
  o.force_phase = 0.3;
  return o;
}

ClearanceOscillatorParameters Bare(const OscillatorDef& o) {
  ClearanceOscillatorParameters p;
  p.zeta = o.zeta;
  p.alpha = o.alpha;
  p.mean_force = o.mean_force;
  p.alternating_force = o.alternating_force;
  p.force_phase = o.force_phase;
  p.back_contact = o.back_contact;
  return p;
}

TEST(OscillatorSystemTest, OneDofOneMeshAndItsModeAtOneHertz) {
  for (OscillatorModel level :
       {OscillatorModel::kSlices, OscillatorModel::kTorsional, OscillatorModel::kLti}) {
    OscillatorDef o = BlankenshipKahraman();
    o.model = level;
    const SystemModel model = MakeOscillatorSystemModel(o);
    ASSERT_EQ(model.num_dofs(), 1);
    ASSERT_EQ(model.num_meshes(), 1);
    EXPECT_EQ(model.harmonic_loads().size(), 1u);
    EXPECT_EQ(model.time_dependence() == TimeDependence::kNonlinear,
              level == OscillatorModel::kSlices);
    const ModalResult modes = ComputeModes(model);
    ASSERT_EQ(modes.frequencies_hz.size(), 1);
    EXPECT_NEAR(modes.frequencies_hz(0), 1.0, 1e-12) << ToString(level);
  }
}

// The system NHB (what `geardyn hb` runs) equals the bare NhbProblem: single solves away from the
// multi-valued range, and the folds (the ends of both branches near the jump) of the two traces.
TEST(OscillatorSystemTest, SystemNhbEqualsTheBareClearanceOscillator) {
  for (bool back : {true, false}) {
    OscillatorDef o = BlankenshipKahraman();
    o.back_contact = back;
    const SystemModel model = MakeOscillatorSystemModel(o);
    const NhbProblem bare = MakeClearanceOscillator(Bare(o));
    SystemNhbOptions options;
    options.hb.harmonics = 16;
    options.hb.stability = NhbStabilityMethod::kNone;
    options.compute_element_forces = false;
    NhbOptions bare_options = options.hb;
    for (double omega : {0.4, 0.6, 1.3, 1.6}) {
      Summary summary;
      const SystemNhbPoint p = SolveSystemNonlinearHb(model, omega, options, &summary);
      ASSERT_TRUE(summary.ok()) << summary.BriefReport();
      const NhbSolveResult r = SolveNonlinearHarmonicBalance(bare, omega, bare_options);
      ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
      // x = δ_η, the mesh's DTE (slice core: ε = 0).
      EXPECT_NEAR(p.meshes[0].rms_dte, r.point.rms[0], 1e-6 * r.point.rms[0]) << omega;
      EXPECT_NEAR(p.meshes[0].mean_dte, r.point.mean[0], 1e-6 * std::abs(r.point.mean[0]));
      EXPECT_NEAR(p.meshes[0].peak_to_peak_dte, r.point.peak_to_peak[0],
                  1e-4 * r.point.peak_to_peak[0]);  // sampled vs refined extrema
    }
    // The trace with F_a = 0.1 (the built-in scene's): jumps in the range (with 0.02 none).
    o.alternating_force = 0.1;
    const SystemModel jumping = MakeOscillatorSystemModel(o);
    const NhbProblem bare_jumping = MakeClearanceOscillator(Bare(o));
    options.start_hz = 0.5;
    options.end_hz = 1.5;
    options.hb.samples_per_harmonic = 256;  // the AFT's kink error ∝ S⁻² (see below)
    options.continuation.branch_search = 0;
    const SystemNhbCurve curve = TraceSystemNonlinearHb(jumping, options);
    ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
    NhbContinuationOptions c = options.continuation;
    c.omega_start = 0.5;
    c.omega_end = 1.5;
    const NhbCurve bare_curve = TraceNonlinearHarmonicBalance(bare_jumping, bare_options, c);
    ASSERT_TRUE(bare_curve.summary.ok()) << bare_curve.summary.BriefReport();
    ASSERT_GE(bare_curve.folds.size(), 2u) << "the softening resonance has a jump";
    ASSERT_EQ(curve.fold_frequencies_hz.size(), bare_curve.folds.size());
    // The bare problem integrates the clearance law exactly; the system's slice law with a
    // smooth (Fourier) stiffness goes through the AFT, whose kink error falls as S⁻² (S = 256 H
    // here; at the default 16 H the folds differed by up to 1.4e-3 and an RMS by 3 %). Measured
    // at S = 256 H: folds within 5e-4, RMS at the jumps within 4e-3 (the largest on the
    // one-sided case's large-amplitude branch).
    for (std::size_t i = 0; i < bare_curve.folds.size(); ++i) {
      EXPECT_NEAR(curve.fold_frequencies_hz[i], bare_curve.folds[i].omega,
                  5e-4 * bare_curve.folds[i].omega)
          << i;
    }
    ASSERT_EQ(curve.jumps.size(), bare_curve.jumps.size());
    for (std::size_t i = 0; i < curve.jumps.size(); ++i) {
      EXPECT_NEAR(curve.jumps[i].rms_dte_before, bare_curve.jumps[i].rms_before,
                  1e-2 * bare_curve.jumps[i].rms_before);
      if (std::isnan(bare_curve.jumps[i].rms_after)) {  // no landing branch traced: both
        EXPECT_TRUE(std::isnan(curve.jumps[i].rms_dte_after));
        continue;
      }
      EXPECT_NEAR(curve.jumps[i].rms_dte_after, bare_curve.jumps[i].rms_after,
                  1e-2 * bare_curve.jumps[i].rms_after);
    }
  }
}

TEST(OscillatorSystemTest, LinearOscillatorHbEqualsTheClosedFormFrf) {
  OscillatorDef o;
  o.zeta = 0.05;
  o.alpha = 0.0;
  o.mean_force = 0.1;
  o.alternating_force = 0.3;
  o.backlash = false;
  for (OscillatorModel level : {OscillatorModel::kTorsional, OscillatorModel::kLti}) {
    o.model = level;
    const SystemModel model = MakeOscillatorSystemModel(o);
    HbOptions options;
    options.harmonics = 4;
    for (double ratio : {0.3, 0.9, 1.0, 2.2}) {
      const HbResult r = SolveHarmonicBalance(model, options, ratio);
      ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
      const double amplitude =
          o.alternating_force /
          std::abs(std::complex<double>(1.0 - ratio * ratio, 2.0 * o.zeta * ratio));
      EXPECT_NEAR(r.meshes[0].rms_dte, amplitude / std::sqrt(2.0), 1e-10 * amplitude) << ratio;
      EXPECT_NEAR(r.meshes[0].mean_dte, o.mean_force, 1e-12);
    }
  }
}

// The linear LTV oscillator x'' + 2ζx' + (1 + α cos Ωτ) x = 0: the model's Floquet multipliers
// equal those of the Mathieu system with the same coefficients (another code path), and the
// principal tongue at Ω ≈ 2 opens at α = 4ζ (first order in α, ζ; Nayfeh & Mook).
TEST(OscillatorSystemTest, FloquetOfTheLtvOscillatorMatchesMathieu) {
  constexpr double kZeta = 0.02;
  OscillatorDef o;
  o.zeta = kZeta;
  o.backlash = false;
  o.model = OscillatorModel::kTorsional;
  FloquetOptions options;
  options.tolerance = 1e-10;
  for (double alpha : {0.05, 0.2}) {
    o.alpha = alpha;
    const SystemModel model = MakeOscillatorSystemModel(o);
    for (double ratio : {1.5, 1.98, 2.0, 2.5}) {
      options.mesh_frequency_hz = ratio;
      const FloquetResult r = ComputeFloquet(model, options);
      ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
      const FloquetResult m = ComputeFloquet(
          MakeMathieuSystem(kWn * kWn, alpha * kWn * kWn, 1.0 / ratio, 2.0 * kZeta * kWn), options);
      ASSERT_TRUE(m.summary.ok()) << m.summary.BriefReport();
      EXPECT_NEAR(r.max_abs_multiplier, m.max_abs_multiplier, 1e-8) << alpha << " " << ratio;
    }
  }
  // Tongue threshold α = 4ζ = 0.08: above it some Ω near 2 is unstable, below it none.
  auto any_unstable = [&](double alpha) {
    o.alpha = alpha;
    const SystemModel model = MakeOscillatorSystemModel(o);
    bool unstable = false;
    for (double ratio = 1.95; ratio <= 2.05; ratio += 0.0025) {
      options.mesh_frequency_hz = ratio;
      const FloquetResult r = ComputeFloquet(model, options);
      EXPECT_NE(r.verdict, FloquetVerdict::kUndetermined);
      unstable = unstable || r.verdict == FloquetVerdict::kUnstable;
    }
    return unstable;
  };
  EXPECT_TRUE(any_unstable(1.1 * 4.0 * kZeta));
  EXPECT_FALSE(any_unstable(0.9 * 4.0 * kZeta));
  options.mesh_frequency_hz = 1.5;  // outside the tongue
  o.alpha = 0.2;
  EXPECT_EQ(ComputeFloquet(MakeOscillatorSystemModel(o), options).verdict, FloquetVerdict::kStable);
  options.mesh_frequency_hz = 2.0;  // inside
  EXPECT_EQ(ComputeFloquet(MakeOscillatorSystemModel(o), options).verdict,
            FloquetVerdict::kUnstable);
}

TEST(OscillatorSystemTest, BadParametersThrowNamingTheField) {
  OscillatorDef o;
  o.zeta = -0.1;
  EXPECT_THROW(MakeOscillatorSystemModel(o), InvalidInput);
  o = OscillatorDef{};
  o.alpha = 1.0;
  EXPECT_THROW(MakeOscillatorSystemModel(o), InvalidInput);
  o = OscillatorDef{};
  o.backlash = false;
  o.model = OscillatorModel::kSlices;
  EXPECT_THROW(MakeOscillatorSystemModel(o), InvalidInput);
}

}  // namespace
}  // namespace geardyn
