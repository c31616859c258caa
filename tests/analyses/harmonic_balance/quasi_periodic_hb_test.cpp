// Quasi-periodic linear harmonic balance (issue 18) against independent truths: the
// single-frequency harmonic balance when every mesh runs at one frequency (the equations are the
// same: exact to round-off), and a long GSL rk8pd integration of the same LTV equations with two
// mesh frequencies in the ratio 21/13 (hb_fixtures.hpp's ODE right-hand side, integrated over
// the 13-cycle period until the transient has died).
#include "geardyn/analyses/quasi_periodic_hb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/errors.hpp"
#include "hb_fixtures.hpp"

namespace geardyn {
namespace {

using test::HandPairParams;

// The 9-DOF planar two-mesh system with smooth stiffness and transmission error on both meshes;
// mesh-b at `ratio_b` times the frequency of mesh-a.
SystemModel SmoothTwoMesh(double ratio_b) {
  const HandPairParams p;
  const LinearMeshCore core_a(MeshCoreLevel::kBlankenshipSingh,
                              test::SmoothStiffness(p.k, 0.25, 0.1), p.b,
                              test::SmoothTransmissionError(2e-6, 1e-6, 0.0));
  const LinearMeshCore core_b(MeshCoreLevel::kBlankenshipSingh,
                              test::SmoothStiffness(0.8 * p.k, 0.2, -0.1), p.b,
                              test::SmoothTransmissionError(-1e-6, 0.0, 5e-7));
  return test::PlanarTwoMesh(core_a, core_b, 0.9, 0.1, ratio_b);
}

// q(θ) = Re Σ_κ Q_κ e^{iκ·ψ(θ)}, ψ_b = r_b θ / P_b (θ the phase of ratio 1).
VectorX Synthesize(const QuasiPeriodicHbResult& r, double theta) {
  VectorXc q = VectorXc::Zero(r.harmonics.rows());
  for (Eigen::Index i = 0; i < r.harmonics.cols(); ++i) {
    double phase = 0.0;
    for (std::size_t b = 0; b < r.bases.size(); ++b) {
      phase += r.orders(static_cast<Eigen::Index>(b), i) * r.bases[b].phase_ratio * theta /
               static_cast<double>(r.bases[b].period_meshes);
    }
    q += r.harmonics.col(i) * std::polar(1.0, phase);
  }
  return q.real();
}

TEST(QuasiPeriodicHbTest, OneFrequencyIsTheSingleFrequencyHarmonicBalance) {
  const SystemModel model = SmoothTwoMesh(1.0);
  QuasiPeriodicHbOptions options;
  options.total_order = 24;
  const double f_m = 1700.0;
  const QuasiPeriodicHbResult qp = SolveQuasiPeriodicHb(model, f_m, options);
  ASSERT_TRUE(qp.summary.ok()) << qp.summary.BriefReport();
  ASSERT_EQ(qp.bases.size(), 1u);
  EXPECT_EQ(qp.harmonics.cols(), 2 * 24 + 1);
  HbOptions hb_options;
  hb_options.harmonics = 24;
  const HbResult hb = SolveHarmonicBalance(model, hb_options, f_m);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  for (int k = 0; k < 2; ++k) {
    const double rms = hb.meshes[k].rms_dte;
    EXPECT_NEAR(qp.meshes[k].rms_dte, rms, 1e-9 * rms) << k;
    EXPECT_NEAR(qp.meshes[k].mean_dte, hb.meshes[k].mean_dte,
                1e-9 * std::abs(hb.meshes[k].mean_dte));
    // Every spectral line is the single-frequency HB's harmonic of the same order.
    ASSERT_FALSE(qp.meshes[k].lines.empty());
    for (const QuasiPeriodicLine& line : qp.meshes[k].lines) {
      ASSERT_EQ(line.order.size(), 1u);
      const int order = line.order[0];
      ASSERT_GE(order, 1);
      EXPECT_NEAR(line.frequency_hz, order * f_m, 1e-9 * f_m);
      EXPECT_NEAR(line.amplitude, hb.meshes[k].dte_amplitudes(order), 1e-9 * rms);
    }
    // Peak-to-peak from the torus grid (128 points) and from the HB's 256 time samples: the
    // same band-limited signal, sampled; both are lower bounds of the true value.
    EXPECT_NEAR(qp.meshes[k].peak_to_peak_dte, hb.meshes[k].peak_to_peak_dte,
                1e-3 * hb.meshes[k].peak_to_peak_dte);
  }
}

TEST(QuasiPeriodicHbTest, TwoIncommensurateBasesMatchALongIntegration) {
  // Mesh-b at 21/13 of mesh-a's frequency: the response repeats every 13 cycles of mesh-a, but
  // the harmonic balance does not know that — it solves on the 2-torus. Equal-frequency pairs κ,
  // κ' (κ − κ' ∥ (21, −13)) need |κ − κ'|_1 ≥ 34 > 2H, so the torus RMS is the line's RMS.
  constexpr double kRatio = 21.0 / 13.0;
  const SystemModel model = SmoothTwoMesh(kRatio);
  const double f_m = 1700.0;
  QuasiPeriodicHbOptions options;
  options.total_order = 16;
  const QuasiPeriodicHbResult qp = SolveQuasiPeriodicHb(model, f_m, options);
  ASSERT_TRUE(qp.summary.ok()) << qp.summary.BriefReport();
  ASSERT_EQ(qp.bases.size(), 2u);
  EXPECT_NEAR(qp.bases[1].frequency_hz, kRatio * f_m, 1e-9 * f_m);
  EXPECT_EQ(qp.harmonics.cols(), CountQuasiPeriodicHarmonics(2, 16));
  EXPECT_EQ(CountQuasiPeriodicHarmonics(2, 16), 2 * 16 * 16 + 2 * 16 + 1);
  EXPECT_LT(qp.summary.error_estimate, 1e-6);

  // Reference: rk8pd (rel. tol. 1e-11) from rest over 12 periods of 13 mesh cycles; modal
  // damping ζ = 0.1 removes the transient (e^{−ζ ω T} ≲ e^{−4} per period for every mode).
  const int n = model.num_dofs();
  const double T_theta = 2.0 * std::numbers::pi * 13.0;
  const double omega_m = 2.0 * std::numbers::pi * f_m;
  SystemWorkspace ws(model, StorageKind::kDense);
  Eigen::LLT<MatrixX> mass(model.DenseMass());
  test::detail::OdeParams params{&model, &ws,       &mass,     omega_m,
                                 false,  MatrixX(), MatrixX(), VectorX()};
  gsl_odeiv2_system sys{test::detail::OdeRhs, nullptr, static_cast<size_t>(2 * n), &params};
  gsl_odeiv2_driver* driver =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-7 / omega_m, 1e-13, 1e-11);
  std::vector<double> y(static_cast<std::size_t>(2 * n), 0.0);
  double t = 0.0;
  const int periods = 12;
  ASSERT_EQ(gsl_odeiv2_driver_apply(driver, &t, (periods - 1) * T_theta / omega_m, y.data()),
            GSL_SUCCESS);
  const int S = 13 * 24;
  MatrixX ref(2, S), got(2, S);
  VectorX dte(2);
  for (int s = 0; s < S; ++s) {
    const double theta = (periods - 1) * T_theta + T_theta * s / S;
    ASSERT_EQ(gsl_odeiv2_driver_apply(driver, &t, theta / omega_m, y.data()), GSL_SUCCESS);
    EvalMeshDte(model, theta, Eigen::Map<const VectorX>(y.data(), n), dte);
    ref.col(s) = dte;
    EvalMeshDte(model, theta, Synthesize(qp, theta), dte);
    got.col(s) = dte;
  }
  gsl_odeiv2_driver_free(driver);
  for (int k = 0; k < 2; ++k) {
    const VectorX r = ref.row(k).transpose(), g = got.row(k).transpose();
    const double pp = r.maxCoeff() - r.minCoeff();
    EXPECT_LE((g - r).cwiseAbs().maxCoeff(), 1e-6 * pp) << "mesh " << k;
    EXPECT_NEAR(qp.meshes[k].rms_dte, test::RmsAboutMean(r), 1e-6 * test::RmsAboutMean(r)) << k;
    EXPECT_NEAR(qp.meshes[k].mean_dte, r.mean(), 1e-6 * pp) << k;
    // The torus grid holds the line: its peak-to-peak is at least the line's.
    EXPECT_GE(qp.meshes[k].peak_to_peak_dte, (1.0 - 1e-6) * pp) << k;
  }
  // Both meshes respond at both bases: the lines include cross orders (κ_a ≠ 0 and κ_b ≠ 0).
  bool cross = false;
  for (const QuasiPeriodicLine& line : qp.meshes[0].lines) {
    cross = cross || (line.order[0] != 0 && line.order[1] != 0 &&
                      line.amplitude > 1e-3 * qp.meshes[0].lines.front().amplitude);
  }
  EXPECT_TRUE(cross);
}

TEST(QuasiPeriodicHbTest, ErrorEstimateFallsWithTheTotalOrder) {
  // A spur rectangular stiffness wave: harmonics decay algebraically, so the truncation is seen.
  const HandPairParams p;
  const LinearMeshCore core_a(MeshCoreLevel::kBlankenshipSingh, test::SpurWave(3e8, 5e8, 1.6), p.b,
                              test::SmoothTransmissionError(2e-6, 0.0, 0.0),
                              MeshDamping::FromRatio(0.05));
  const LinearMeshCore core_b(MeshCoreLevel::kBlankenshipSingh, test::SpurWave(2.5e8, 4e8, 1.4),
                              p.b, std::nullopt, MeshDamping::FromRatio(0.05));
  const SystemModel model = test::PlanarTwoMesh(core_a, core_b, 0.4, 0.05, std::sqrt(2.0));
  double previous = 1.0, previous_rms = 0.0;
  for (const int H : {4, 8, 16}) {
    QuasiPeriodicHbOptions options;
    options.total_order = H;
    const QuasiPeriodicHbResult qp = SolveQuasiPeriodicHb(model, 1300.0, options);
    ASSERT_TRUE(qp.summary.ok()) << qp.summary.BriefReport();
    std::printf("H = %d: %s\n", H, qp.summary.BriefReport().c_str());
    EXPECT_LT(qp.summary.error_estimate, previous) << H;
    previous = qp.summary.error_estimate;
    if (H == 16) {
      // The RMS has settled to within the estimate at H = 8 (a few times it: an estimate).
      EXPECT_NEAR(qp.meshes[0].rms_dte, previous_rms,
                  10.0 * previous * previous_rms + 1e-3 * previous_rms);
    }
    previous_rms = qp.meshes[0].rms_dte;
  }
}

TEST(QuasiPeriodicHbTest, TooLargeATotalOrderIsRefusedWithTheEstimate) {
  const SystemModel model = SmoothTwoMesh(std::sqrt(3.0));
  QuasiPeriodicHbOptions options;
  options.total_order = 64;
  options.memory_limit_bytes = 1e8;
  const double bytes = EstimateQuasiPeriodicHbBytes(model, options);
  EXPECT_GT(bytes, 1e8);
  try {
    SolveQuasiPeriodicHb(model, 1000.0, options);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("total_order"), std::string::npos) << what;
    EXPECT_NE(what.find("GB"), std::string::npos) << what;
  }
  options.total_order = 0;
  EXPECT_THROW(SolveQuasiPeriodicHb(model, 1000.0, options), InvalidInput);
  options.total_order = 8;
  EXPECT_THROW(SolveQuasiPeriodicHb(model, -1.0, options), InvalidInput);
  options.samples_per_base = 10;  // ≤ 2H
  EXPECT_THROW(SolveQuasiPeriodicHb(model, 1000.0, options), InvalidInput);
}

TEST(QuasiPeriodicHbTest, CountsTheCrossPolytope) {
  // |{κ ∈ Z^d : |κ|_1 ≤ H}| by brute force.
  for (int d = 1; d <= 3; ++d) {
    for (int H = 0; H <= 6; ++H) {
      std::int64_t count = 0;
      const int w = 2 * H + 1;
      std::int64_t total = 1;
      for (int b = 0; b < d; ++b) total *= w;
      for (std::int64_t code = 0; code < total; ++code) {
        std::int64_t c = code;
        int norm = 0;
        for (int b = 0; b < d; ++b) {
          norm += std::abs(static_cast<int>(c % w) - H);
          c /= w;
        }
        if (norm <= H) ++count;
      }
      EXPECT_EQ(CountQuasiPeriodicHarmonics(d, H), count) << d << " " << H;
    }
  }
}

}  // namespace
}  // namespace geardyn
