// Quasi-periodic nonlinear harmonic balance (issue 18: "for linear LTV and for the nonlinear
// slice models") against independent truths, on the 9-DOF planar two-mesh system (hb_fixtures.hpp)
// with the Kahraman–Blankenship rig's spur slice core on both meshes (10 slices, mesh damping
// ratio 0.05, modal damping 2 %, 300 N·m on the pinion):
// * one base (both meshes at one frequency): the single-frequency system nonlinear HB with the
//   same sampled AFT (the same equations: equal to the Newton tolerance);
// * mesh-b at √2 times mesh-a's frequency with contact loss on both meshes: a long GSL rk8pd
//   integration of the same equations with the slice forces of the model's cores
//   (system_time_integration.hpp), RMS DTE within 2 % (measured 0.06 %: 9.582 against 9.588 µm,
//   contact lost over 22.55 % of the torus against 22.53 % of the integrated samples);
// * full contact: the linear quasi-periodic HB (slices linearized with every slice loaded).
#include "geardyn/analyses/nonlinear_quasi_periodic_hb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <variant>
#include <vector>

#include "analyses/harmonic_balance/hb_fixtures.hpp"
#include "analyses/system_nhb/kb_rig_fixture.hpp"
#include "analyses/system_nhb/system_time_integration.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

SystemModel TwoSliceMeshes(double ratio_b) {
  const auto core = std::get<SliceMeshCore>(testing::KbRigSliceModel().meshes()[0].core);
  return test::PlanarTwoMesh(core, core, 0.1, 0.02, ratio_b);
}

NonlinearQuasiPeriodicHbOptions Options(int total_order, int samples = 0) {
  NonlinearQuasiPeriodicHbOptions o;
  o.torus.total_order = total_order;
  o.torus.samples_per_base = samples;
  return o;
}

TEST(NonlinearQuasiPeriodicHb, OneBaseIsTheSingleFrequencyNonlinearHb) {
  const SystemModel model = TwoSliceMeshes(1.0);
  const double f_m = 3600.0;  // near the mesh resonance: 20–30 % of the cycle without contact
  constexpr int kH = 16, kSamples = 128;
  const NonlinearQuasiPeriodicHbResult qp =
      SolveNonlinearQuasiPeriodicHb(model, f_m, Options(kH, kSamples));
  ASSERT_TRUE(qp.torus.summary.ok()) << qp.torus.summary.BriefReport();
  ASSERT_EQ(qp.torus.bases.size(), 1u);

  SystemNhbOptions o;
  o.hb.harmonics = kH;
  o.hb.force_integration = NhbForceIntegration::kSampled;
  o.hb.samples_per_harmonic = kSamples / kH;  // S = 128 samples, the torus grid
  o.hb.stability = NhbStabilityMethod::kNone;
  Summary summary;
  const SystemNhbPoint single = SolveSystemNonlinearHb(model, f_m, o, &summary);
  ASSERT_TRUE(summary.ok()) << summary.BriefReport();
  for (int k = 0; k < 2; ++k) {
    const SystemNhbMeshOutput& ref = single.meshes[static_cast<std::size_t>(k)];
    const QuasiPeriodicMeshOutput& got = qp.torus.meshes[static_cast<std::size_t>(k)];
    ASSERT_GT(ref.contact_loss_fraction, 0.1) << k;
    EXPECT_NEAR(got.rms_dte, ref.rms_dte, 1e-7 * ref.rms_dte) << k;
    EXPECT_NEAR(got.mean_dte, ref.mean_dte, 1e-7 * ref.rms_dte) << k;
    EXPECT_NEAR(got.peak_to_peak_dte, ref.peak_to_peak_dte, 1e-6 * ref.peak_to_peak_dte) << k;
    EXPECT_NEAR(got.mean_force, ref.mean_force, 1e-7 * ref.max_force) << k;
    EXPECT_NEAR(qp.contact[static_cast<std::size_t>(k)].max_force, ref.max_force,
                1e-6 * ref.max_force)
        << k;
    EXPECT_DOUBLE_EQ(qp.contact[static_cast<std::size_t>(k)].contact_loss_fraction,
                     ref.contact_loss_fraction)
        << k;
    // Every line is the harmonic of the same order.
    for (const QuasiPeriodicLine& line : got.lines) {
      ASSERT_EQ(line.order.size(), 1u);
      EXPECT_NEAR(line.amplitude, ref.dte_amplitudes(line.order[0]), 1e-7 * ref.rms_dte);
    }
  }
}

TEST(NonlinearQuasiPeriodicHb, IncommensurateContactLossMatchesALongIntegration) {
  const double ratio = std::sqrt(2.0);
  const SystemModel model = TwoSliceMeshes(ratio);
  const double f_m = 2400.0;  // both meshes lose contact over ≈ 20 % of the torus
  const NonlinearQuasiPeriodicHbResult qp = SolveNonlinearQuasiPeriodicHb(model, f_m, Options(12));
  ASSERT_TRUE(qp.torus.summary.ok()) << qp.torus.summary.BriefReport();
  ASSERT_EQ(qp.torus.bases.size(), 2u);
  ASSERT_GT(qp.contact[0].contact_loss_fraction, 0.1);
  ASSERT_GT(qp.contact[1].contact_loss_fraction, 0.1);

  // Reference: rk8pd (rel. tol. 1e-10) from the static deflection, 600 mesh-a cycles to settle
  // (the slowest mode decays by e^{−ζωt} ≲ e^{−20}), then 600 cycles sampled 64 times each: the
  // torus average along the line, to O(1/600) from the finite window.
  testing::SystemTimeIntegrator integrator(model);
  const testing::SystemTiStats ti = integrator.Run(f_m, 600, 600, 64);
  ASSERT_TRUE(ti.ok);
  const QuasiPeriodicMeshOutput& mesh_a = qp.torus.meshes[0];
  EXPECT_NEAR(mesh_a.rms_dte, ti.rms, 0.02 * ti.rms);
  EXPECT_NEAR(mesh_a.mean_dte, ti.mean, 0.02 * ti.rms);
  EXPECT_NEAR(qp.contact[0].contact_loss_fraction, ti.contact_loss_fraction, 0.02);
  // Cross orders carry the coupling: a line with both orders non-zero.
  bool cross = false;
  for (const QuasiPeriodicLine& line : mesh_a.lines) {
    cross = cross || (line.order[0] != 0 && line.order[1] != 0 &&
                      line.amplitude > 1e-2 * mesh_a.lines.front().amplitude);
  }
  EXPECT_TRUE(cross);
}

TEST(NonlinearQuasiPeriodicHb, FullContactIsTheLinearQuasiPeriodicHb) {
  const SystemModel model = TwoSliceMeshes(std::sqrt(2.0));
  const double f_m = 600.0;
  QuasiPeriodicHbOptions o;
  o.total_order = 8;
  const QuasiPeriodicHbResult lin = SolveQuasiPeriodicHb(model, f_m, o);
  ASSERT_TRUE(lin.summary.ok()) << lin.summary.BriefReport();
  // The linear HB couples with the exact Fourier coefficients of the stiffness steps; the AFT
  // samples them, and its aliasing of their 1/n harmonics falls as 1/N (measured: 4 % at N = 64,
  // 0.28 % at N = 1024 on mesh a).
  double previous_error = 0.0;
  for (int N : {256, 1024}) {
    const NonlinearQuasiPeriodicHbResult nl =
        SolveNonlinearQuasiPeriodicHb(model, f_m, Options(8, N));
    ASSERT_TRUE(nl.torus.summary.ok()) << nl.torus.summary.BriefReport();
    double error = 0.0;
    for (int k = 0; k < 2; ++k) {
      const auto m = static_cast<std::size_t>(k);
      ASSERT_EQ(nl.contact[m].contact_loss_fraction, 0.0);
      const double rms = lin.meshes[m].rms_dte;
      error = std::max(error, std::abs(nl.torus.meshes[m].rms_dte - rms) / rms);
      EXPECT_NEAR(nl.torus.meshes[m].mean_dte, lin.meshes[m].mean_dte,
                  (N == 1024 ? 1e-3 : 3e-3) * std::abs(lin.meshes[m].mean_dte))
          << k;
    }
    if (N == 1024) {
      EXPECT_LT(error, 5e-3);
      EXPECT_LT(error, 0.5 * previous_error);  // first order in 1/N: ≈ 1/4 per ×4
    }
    previous_error = error;
  }
}

// The RMS DTE settles in the total order (measured 9.5754, 9.5825, 9.5845 µm at H = 6, 12, 18):
// the change from 12 to 18 is below a third of that from 6 to 12, and the error estimate falls.
TEST(NonlinearQuasiPeriodicHb, ConvergesInTheTotalOrder) {
  const SystemModel model = TwoSliceMeshes(std::sqrt(2.0));
  std::vector<double> rms, estimate;
  for (int H : {6, 12, 18}) {
    const NonlinearQuasiPeriodicHbResult r =
        SolveNonlinearQuasiPeriodicHb(model, 2400.0, Options(H));
    ASSERT_TRUE(r.torus.summary.ok()) << r.torus.summary.BriefReport();
    rms.push_back(r.torus.meshes[0].rms_dte);
    estimate.push_back(r.torus.summary.error_estimate);
  }
  EXPECT_LT(std::abs(rms[2] - rms[1]), std::abs(rms[1] - rms[0]) / 3.0);
  EXPECT_LT(std::abs(rms[2] - rms[1]), 1e-3 * rms[2]);
  EXPECT_LT(estimate[2], estimate[0]);
}

TEST(NonlinearQuasiPeriodicHb, BadInputIsRefusedByName) {
  const SystemModel model = TwoSliceMeshes(std::sqrt(2.0));
  NonlinearQuasiPeriodicHbOptions o = Options(8);
  o.newton_tolerance = 0.0;
  EXPECT_THROWS_MESSAGE(SolveNonlinearQuasiPeriodicHb(model, 1000.0, o), InvalidInput,
                        "newton_tolerance");
  EXPECT_THROWS_MESSAGE(SolveNonlinearQuasiPeriodicHb(model, -1.0, Options(8)), InvalidInput,
                        "mesh frequency");
  o = Options(200);
  o.torus.memory_limit_bytes = 1e8;
  EXPECT_THROWS_MESSAGE(SolveNonlinearQuasiPeriodicHb(model, 1000.0, o), InvalidInput,
                        "total_order: H = 200");
  const MatrixXc wrong = MatrixXc::Zero(1, 3);
  EXPECT_THROWS_MESSAGE(SolveNonlinearQuasiPeriodicHb(model, 1000.0, Options(8), &wrong),
                        InvalidInput, "initial guess");
}

}  // namespace
}  // namespace geardyn
