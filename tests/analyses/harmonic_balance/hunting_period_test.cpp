// Linear harmonic balance of systems whose forcing repeats over a hunting period of P > 1 mesh
// cycles while K and C repeat every mesh (a runout-like transmission error): H counts mesh orders
// and keeps their sidebands (harmonic_balance.hpp "Harmonic set"). The truth is independent: a
// long GSL rk8pd integration of M q̈ + C(θ) q̇ + K(θ) q = f(θ) (hb_fixtures.hpp) over the
// hunting period — DTE samples, RMS and the spectrum lines of the DTE (a DFT of the ODE samples)
// at the runout line, the mesh orders and their sidebands — at two mesh frequencies, and the
// exact decoupling of the forcing classes (the mesh-order lines do not depend on the runout).
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <numbers>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "hb_fixtures.hpp"

namespace geardyn {
namespace {

using test::HandPairParams;

constexpr int kPeriod = 5;  // hunting period of the transmission error [mesh cycles]

// ε_η over 5 mesh cycles: a once-per-5-meshes "runout" line (n = 1), the mesh order (n = 5) and
// its second order (n = 10) [m]; ε_ζ = 0.
FourierCoefficient HuntingTransmissionError() {
  MatrixX cosines = MatrixX::Zero(2, 10), sines = MatrixX::Zero(2, 10);
  cosines(0, 0) = 3e-6;  // n = 1: runout
  cosines(0, 4) = 1e-6;  // n = 5: mesh order 1
  sines(0, 9) = 0.3e-6;  // n = 10: mesh order 2
  return FourierCoefficient::FromCosSin(Vector2::Zero(), cosines, sines, kPeriod);
}

// |DFT line k| of x over its S samples, as an amplitude (|mean| for k = 0, 2|c_k| else).
double LineAmplitude(const VectorX& x, int k) {
  std::complex<double> c(0.0, 0.0);
  const auto S = static_cast<double>(x.size());
  for (Eigen::Index s = 0; s < x.size(); ++s) {
    c += x(s) * std::polar(1.0, -2.0 * std::numbers::pi * k * static_cast<double>(s) / S);
  }
  return (k == 0 ? 1.0 : 2.0) * std::abs(c) / S;
}

TEST(HbHuntingPeriodTest, SdofRunoutAgainstTimeIntegrationAtTwoSpeeds) {
  // Smooth LTV stiffness (period 1) and ε of period 5: P = 5, P_K = 1, classes 0 and ±1.
  const HandPairParams p;
  const LinearMeshCore core(MeshCoreLevel::kTorsional, test::SmoothStiffness(p.k, 0.25, 0.1), p.b,
                            HuntingTransmissionError(), MeshDamping::FromRatio(0.05));
  const SystemModel model = test::TorsionalPair(core, 250.0);
  ASSERT_EQ(model.period_meshes(), kPeriod);
  const int S = 80;  // ODE samples over the hunting period (16 per mesh)
  HbOptions options;
  options.harmonics = 16;  // mesh orders (smooth K: exponential convergence)
  options.time_samples = 1280;
  options.keep_harmonics = true;
  for (const double f_m : {1900.0, 3400.0}) {
    const HbResult hb = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
    EXPECT_EQ(hb.method_used, HbMethod::kCondensed);
    // The kept set: every mesh order j·5 (j ≤ 16) and its sidebands j·5 ± 1, nothing else.
    EXPECT_EQ(hb.highest_harmonic, 16 * kPeriod + 1);
    for (int j = 0; j <= 16; ++j) {
      EXPECT_TRUE(std::ranges::binary_search(hb.kept_harmonics, j * kPeriod)) << j;
      EXPECT_TRUE(std::ranges::binary_search(hb.kept_harmonics, j * kPeriod + 1)) << j;
    }
    EXPECT_FALSE(std::ranges::binary_search(hb.kept_harmonics, 2));
    // Transient decay: e^{−ζ ω_n t} with f_n ≈ 4.6 kHz, ζ = 0.05 over 14 hunting periods of
    // 5 meshes: below e^{−45} at 1900 Hz.
    const test::OdeSteadyState ode = test::IntegrateSteadyState(model, f_m, 14, S);
    const VectorX ref = ode.dte.row(0).transpose();
    VectorX got(S);
    for (int s = 0; s < S; ++s) got(s) = hb.dte_samples(0, s * (1280 / S));
    const double pp = ref.maxCoeff() - ref.minCoeff();
    // Smooth coefficients: truncation far below the integrator's 1e-11; 1e-6 covers both.
    EXPECT_LE((got - ref).cwiseAbs().maxCoeff(), 1e-6 * pp) << f_m;
    EXPECT_NEAR(hb.meshes[0].rms_dte, test::RmsAboutMean(ref), 1e-6 * test::RmsAboutMean(ref));
    // Spectrum lines: runout (1), sidebands (4, 6, 9, 11), mesh orders (5, 10).
    for (const int k : {1, 4, 5, 6, 9, 10, 11}) {
      EXPECT_NEAR(hb.meshes[0].dte_amplitudes(k), LineAmplitude(ref, k), 1e-6 * pp)
          << f_m << " Hz, line " << k;
    }
    // The mesh-order line is the bulk of the response (the failure this guards against: with
    // H counting harmonics of ω_m/P, H < P dropped it).
    EXPECT_GT(hb.meshes[0].dte_amplitudes(kPeriod), 0.1 * pp) << f_m;
  }
}

TEST(HbHuntingPeriodTest, MultiMeshRunoutAgainstTimeIntegration) {
  // Two meshes; only mesh a has the period-5 error: one class pair ±1 besides the mesh orders.
  const HandPairParams p;
  const LinearMeshCore core_a(MeshCoreLevel::kBlankenshipSingh,
                              test::SmoothStiffness(p.k, 0.25, 0.1), p.b,
                              HuntingTransmissionError());
  const LinearMeshCore core_b(MeshCoreLevel::kBlankenshipSingh,
                              test::SmoothStiffness(0.8 * p.k, 0.2, -0.1), p.b);
  const SystemModel model = test::PlanarTwoMesh(core_a, core_b, 0.9, 0.1);
  ASSERT_EQ(model.period_meshes(), kPeriod);
  const int S = 160;  // 32 per mesh: the DFT lines and the RMS of the samples do not alias
  HbOptions options;
  options.harmonics = 16;
  options.time_samples = 640;
  options.keep_harmonics = true;
  const double f_m = 1700.0;
  const HbResult hb = SolveHarmonicBalance(model, options, f_m);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  EXPECT_EQ(hb.summary.counters.at("forcing_classes"), 2);
  const test::OdeSteadyState ode = test::IntegrateSteadyState(model, f_m, 8, S);
  for (int k = 0; k < 2; ++k) {
    const VectorX ref = ode.dte.row(k).transpose();
    VectorX got(S);
    for (int s = 0; s < S; ++s) got(s) = hb.dte_samples(k, s * (640 / S));
    const double pp = ref.maxCoeff() - ref.minCoeff();
    EXPECT_LE((got - ref).cwiseAbs().maxCoeff(), 1e-6 * pp) << "mesh " << k;
    EXPECT_NEAR(hb.meshes[k].rms_dte, test::RmsAboutMean(ref), 1e-6 * test::RmsAboutMean(ref));
    for (const int line : {1, 4, 5, 6}) {
      EXPECT_NEAR(hb.meshes[k].dte_amplitudes(line), LineAmplitude(ref, line), 1e-6 * pp)
          << "mesh " << k << ", line " << line;
    }
  }
}

TEST(HbHuntingPeriodTest, MeshOrdersDoNotDependOnTheRunout) {
  // K is mesh-periodic, so the class of the mesh orders (k ≡ 0 mod P) is decoupled from the
  // runout's (k ≡ ±1): with and without the runout line, the mesh-order harmonics agree to
  // round-off — the first solved with P = 5, the second with P = 1 (a different period,
  // harmonic set and expansion).
  const HandPairParams p;
  MatrixX cos5 = MatrixX::Zero(2, 10), sin5 = MatrixX::Zero(2, 10);
  cos5(0, 0) = 3e-6;
  cos5(0, 4) = 1e-6;
  sin5(0, 9) = 0.3e-6;
  MatrixX cos1 = MatrixX::Zero(2, 2), sin1 = MatrixX::Zero(2, 2);
  cos1(0, 0) = 1e-6;
  sin1(0, 1) = 0.3e-6;
  const auto make = [&](const FourierCoefficient& eps) {
    return test::TorsionalPair(
        LinearMeshCore(MeshCoreLevel::kTorsional, test::SmoothStiffness(p.k, 0.25, 0.1), p.b, eps,
                       MeshDamping::FromRatio(0.05)),
        250.0);
  };
  const SystemModel hunting = make(FourierCoefficient::FromCosSin(Vector2::Zero(), cos5, sin5, 5));
  const SystemModel plain = make(FourierCoefficient::FromCosSin(Vector2::Zero(), cos1, sin1, 1));
  HbOptions options;
  options.harmonics = 12;
  options.keep_harmonics = true;
  const HbResult a = SolveHarmonicBalance(hunting, options, 2600.0);
  const HbResult b = SolveHarmonicBalance(plain, options, 2600.0);
  ASSERT_TRUE(a.summary.ok() && b.summary.ok());
  const double scale = b.response_harmonics.norm();
  for (int j = 0; j <= 12; ++j) {
    EXPECT_LE((a.response_harmonics.col(5 * j) - b.response_harmonics.col(j)).norm(), 1e-10 * scale)
        << j;
  }
}

}  // namespace
}  // namespace geardyn
