// Linear LTV harmonic balance against an independent method: a long GSL rk8pd integration of
// M q̈ + C(θ) q̇ + K(θ) q = f(θ) (hb_fixtures.hpp) until the transients have died, comparing the
// DTE samples of the last period — the SDOF torsional pair with a spur rectangular stiffness wave
// (steps: algebraic convergence, H = 128) and a 9-DOF planar two-mesh system with smooth
// stiffness and transmission error (exponential convergence, H = 24).
#include <gtest/gtest.h>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "hb_fixtures.hpp"

namespace geardyn {
namespace {

using test::HandPairParams;

TEST(HbLtvTimeIntegrationTest, SdofSpurRectangularWave) {
  // f_n ≈ 4.6 kHz with the mean stiffness; mesh damping ζ = 0.05: the transient decays by
  // e^{−ζ ω_n T} ≈ 0.6 per mesh period, 80 periods leave e^{−40}.
  const HandPairParams p;
  const LinearMeshCore core(MeshCoreLevel::kTorsional, test::SpurWave(3.0e8, 5.0e8, 1.6), p.b,
                            std::nullopt, MeshDamping::FromRatio(0.05));
  const SystemModel model = test::TorsionalPair(core, 250.0);
  ASSERT_EQ(model.num_dofs(), 2);
  const int S = 64;
  HbOptions options;
  options.harmonics = 128;
  options.time_samples = 1024;  // multiple of S: HB sample 16 s is θ_s of the reference
  options.keep_harmonics = true;
  for (const double f_m : {1900.0, 3400.0}) {
    const HbResult hb = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
    EXPECT_EQ(hb.method_used, HbMethod::kCondensed);
    const test::OdeSteadyState ode = test::IntegrateSteadyState(model, f_m, 80, S);
    const VectorX ref = ode.dte.row(0).transpose();
    VectorX got(S);
    for (int s = 0; s < S; ++s) got(s) = hb.dte_samples(0, s * (1024 / S));
    const double pp = ref.maxCoeff() - ref.minCoeff();
    // Truncation at H = 128 of a response whose harmonics decay like k^-3 (C¹ with jumps in
    // q̈): Σ_{k>H} k^-3 ~ 3e-5 of the first harmonic; 1e-3 of the peak-to-peak is the bound.
    EXPECT_LE((got - ref).cwiseAbs().maxCoeff(), 1e-3 * pp) << f_m;
    EXPECT_NEAR(hb.meshes[0].rms_dte, test::RmsAboutMean(ref), 1e-3 * test::RmsAboutMean(ref));
    EXPECT_NEAR(hb.meshes[0].mean_dte, ref.mean(), 1e-3 * pp);
  }
}

TEST(HbLtvTimeIntegrationTest, MultiDofTwoMeshSmoothStiffness) {
  const HandPairParams p;
  const LinearMeshCore core_a(MeshCoreLevel::kBlankenshipSingh,
                              test::SmoothStiffness(p.k, 0.25, 0.1), p.b,
                              test::SmoothTransmissionError(2e-6, 1e-6, 0.0));
  const LinearMeshCore core_b(MeshCoreLevel::kBlankenshipSingh,
                              test::SmoothStiffness(0.8 * p.k, 0.2, -0.1), p.b);
  const SystemModel model = test::PlanarTwoMesh(core_a, core_b, 0.9, 0.1);
  ASSERT_EQ(model.num_dofs(), 9);
  ASSERT_EQ(model.time_dependence(), TimeDependence::kSmoothPeriodic);
  const int S = 32;
  HbOptions options;
  options.harmonics = 24;
  options.time_samples = 256;
  options.keep_harmonics = true;
  const double f_m = 1700.0;
  const HbResult hb = SolveHarmonicBalance(model, options, f_m);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  EXPECT_EQ(hb.method_used, HbMethod::kCondensed);
  const test::OdeSteadyState ode = test::IntegrateSteadyState(model, f_m, 30, S);
  for (int k = 0; k < 2; ++k) {
    const VectorX ref = ode.dte.row(k).transpose();
    VectorX got(S);
    for (int s = 0; s < S; ++s) got(s) = hb.dte_samples(k, s * (256 / S));
    const double pp = ref.maxCoeff() - ref.minCoeff();
    // Smooth coefficients: the truncation error at H = 24 is far below the integrator's
    // tolerance (1e-11 relative); 1e-6 of the peak-to-peak covers the integration error.
    EXPECT_LE((got - ref).cwiseAbs().maxCoeff(), 1e-6 * pp) << "mesh " << k;
    EXPECT_NEAR(hb.meshes[k].rms_dte, test::RmsAboutMean(ref), 1e-6 * test::RmsAboutMean(ref));
  }
}

}  // namespace
}  // namespace geardyn
