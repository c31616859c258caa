// Linear LTI harmonic balance (mean-LTI core, smooth transmission error): equals the direct
// frequency response solved per harmonic from the assembled K, C, M and the DFT of f(θ); takes
// the decoupled path automatically; equals the coupled (full direct) solve; rigid-body mode and
// balanced torques handled.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <complex>
#include <numbers>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "hb_fixtures.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::HandPairParams;
using Complex = std::complex<double>;

// Round-off of (H+1) 12×12 complex solves against the same solves done differently.
constexpr double kRoundOff = 1e-9;

LinearMeshCore LtiCoreWithError() {
  const HandPairParams p;
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            ConstantCoefficient(Vector3(p.k, 0.0, p.k * p.b * p.b / 3.0)), p.b,
                            test::SmoothTransmissionError(4e-6, 2e-6, 1e-6),
                            MeshDamping::FromRatio(0.06));
  return core;
}

TEST(HbLtiTest, EqualsTheDirectFrequencyResponsePerHarmonic) {
  const SystemModel model = test::LoadedPair(LtiCoreWithError(), 200.0, 0.02);
  ASSERT_EQ(model.time_dependence(), TimeDependence::kConstant);
  const int n = model.num_dofs();
  const int H = 6;
  HbOptions options;
  options.harmonics = H;
  options.keep_harmonics = true;
  for (const double f_m : {300.0, 2100.0, 4700.0}) {
    const HbResult hb = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
    EXPECT_EQ(hb.method_used, HbMethod::kDecoupled);
    // Truth: constant K, C from the assembly kernels at an arbitrary phase, F_k by a plain DFT
    // of f(θ) on 64 points (exact for the degree-3 transmission error).
    SystemWorkspace ws(model, StorageKind::kDense);
    const MatrixX K = AssembleStiffness(model, ws, 0.37);
    const MatrixX C = AssembleDamping(model, ws, 1.3);
    const MatrixX M = model.DenseMass();
    const int S = 64;
    std::vector<VectorXc> F(H + 1, VectorXc::Zero(n));
    for (int s = 0; s < S; ++s) {
      const double theta = 2.0 * std::numbers::pi * s / S;
      const VectorX f = AssembleLoad(model, ws, theta);
      for (int k = 0; k <= H; ++k) F[k] += f.cast<Complex>() * std::polar(1.0 / S, -k * theta);
    }
    const double w = 2.0 * std::numbers::pi * f_m;
    // Harmonics 4 … H are not excited (exactly 0 in the truth): compare them in absolute terms.
    const double scale = hb.response_harmonics.rightCols(H).norm();
    for (int k = 1; k <= H; ++k) {
      const MatrixXc A =
          (K - (k * w) * (k * w) * M).cast<Complex>() + Complex(0.0, k * w) * C.cast<Complex>();
      const VectorXc X = A.partialPivLu().solve(F[k]);
      const VectorXc got = hb.response_harmonics.col(k);
      EXPECT_LE((got - X).norm(), kRoundOff * scale) << "f_m " << f_m << " k " << k;
    }
    // The mean: K̄ q̄ = f̄ up to the free rotation; the DTE (insensitive to it) is the static one.
    const StaticDeflectionResult st = SolveStaticDeflection(model);
    EXPECT_GT(st.meshes[0].delta_eta, 0.0);  // the torques compress the teeth
    EXPECT_NEAR(hb.meshes[0].mean_dte, st.meshes[0].delta_eta, 1e-9 * st.meshes[0].delta_eta);
  }
}

TEST(HbLtiTest, DecoupledEqualsCoupledDirectAndCondensedSolves) {
  const SystemModel model = test::LoadedPair(LtiCoreWithError(), 150.0, 0.03);
  HbOptions options;
  options.harmonics = 5;
  options.keep_harmonics = true;
  const double f_m = 3300.0;
  options.method = HbMethod::kDecoupled;
  const HbResult decoupled = SolveHarmonicBalance(model, options, f_m);
  options.method = HbMethod::kDirect;
  const HbResult direct = SolveHarmonicBalance(model, options, f_m);
  ASSERT_TRUE(decoupled.summary.ok() && direct.summary.ok());
  // The DTE does not see the rigid rotation; the response harmonics k ≥ 1 are unique.
  const double scale = direct.response_harmonics.rightCols(5).norm();
  for (int k = 1; k <= 5; ++k) {
    EXPECT_LE((decoupled.response_harmonics.col(k) - direct.response_harmonics.col(k)).norm(),
              kRoundOff * scale)
        << k;
  }
  EXPECT_NEAR(decoupled.meshes[0].rms_dte, direct.meshes[0].rms_dte,
              kRoundOff * direct.meshes[0].rms_dte);
  EXPECT_NEAR(decoupled.meshes[0].mean_dte, direct.meshes[0].mean_dte,
              kRoundOff * std::abs(direct.meshes[0].mean_dte));
}

TEST(HbLtiTest, DecoupledIsRefusedForAnLtvModel) {
  const HandPairParams p;
  const SystemModel model = test::LoadedPair(
      LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, test::SpurWave(3e8, 5e8, 1.6), p.b));
  HbOptions options;
  options.harmonics = 4;
  options.method = HbMethod::kDecoupled;
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(model, options, 1000.0), InvalidInput,
                        "decoupled.*LTI");
}

TEST(HbLtiTest, InvalidOptionsNameTheField) {
  const SystemModel model = test::LoadedPair(LtiCoreWithError());
  HbOptions options;
  options.harmonics = -1;
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(model, options, 100.0), InvalidInput,
                        "HbOptions::harmonics");
  options.harmonics = 0;
  options.tolerance = 0.0;
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(model, options, 100.0), InvalidInput,
                        "HbOptions::tolerance");
  options = HbOptions();
  options.harmonics = 10;
  options.time_samples = 16;
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(model, options, 100.0), InvalidInput,
                        "HbOptions::time_samples");
  options = HbOptions();
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(model, options, -5.0), InvalidInput,
                        "mesh_frequency_hz");
}

}  // namespace
}  // namespace geardyn
