// Convergence in H of the linear LTV harmonic balance and its error estimate, and the equality
// of the solution paths: the condensed (mesh-deflection Woodbury) solve equals the full dense
// block-Toeplitz solve (MakeLinearHbSystem) to round-off for the same H.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "hb_fixtures.hpp"

namespace geardyn {
namespace {

using test::HandPairParams;

double RmsDte(const SystemModel& model, int H, double f_m) {
  HbOptions options;
  options.harmonics = H;
  options.time_samples = 2048;  // the same samples for every H: only the truncation differs
  options.compute_forces = false;
  const HbResult r = SolveHarmonicBalance(model, options, f_m);
  EXPECT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  return r.meshes[0].rms_dte;
}

SystemModel SmoothPair() {
  const HandPairParams p;
  return test::LoadedPair(
      LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, test::SmoothStiffness(p.k, 0.3, 0.15), p.b,
                     std::nullopt, MeshDamping::FromRatio(0.05)),
      200.0, 0.03);
}

SystemModel SteppedPair() {
  const HandPairParams p;
  return test::LoadedPair(LinearMeshCore(MeshCoreLevel::kTorsional, test::SpurWave(3e8, 5e8, 1.55),
                                         p.b, std::nullopt, MeshDamping::FromRatio(0.05)),
                          200.0, 0.03);
}

TEST(HbConvergenceTest, SmoothStiffnessConvergesExponentially) {
  const SystemModel model = SmoothPair();
  const double f_m = 2600.0;
  const double ref = RmsDte(model, 64, f_m);
  double previous = 0.0;
  for (const int H : {2, 4, 8, 16}) {
    const double err = std::abs(RmsDte(model, H, f_m) - ref) / ref;
    if (H > 2) {
      // Exponential: each doubling of H gains at least a factor 20 (until round-off).
      EXPECT_TRUE(err < previous / 20.0 || err < 1e-12) << "H " << H << " err " << err;
    }
    previous = err;
  }
}

// The step stiffness against an independent steady state (GSL rk8pd, restarted at every stiffness
// step, hb_fixtures.hpp) at the same 2048 samples, so only the truncation differs. Order: K(θ)
// jumps, so q̈ jumps and the harmonics of q decay as k⁻³ (q is C¹). The truncation tail then has
// an L² norm (Σ_{k>H} k⁻⁶)^{1/2} ~ H^{-5/2} and a maximum Σ_{k>H} k⁻³ ~ H⁻², and the Galerkin
// error of the kept harmonics, driven by Σ_{|j|>H} K_{k−j} Q_j with K_m ~ 1/m, is O(H⁻³): the
// waveform error falls at order 5/2 in L² and 2 in the maximum.
TEST(HbConvergenceTest, StepStiffnessWaveformConvergesAtTheOrderOfItsSmoothness) {
  constexpr int kSamples = 2048;
  constexpr double kOrderTol = 0.2;  // pre-asymptotic H = 8 (observed 2.41–2.48 and 1.97)
  const SystemModel model = SteppedPair();
  const double f_m = 2600.0;
  const test::OdeSteadyState ode = test::IntegrateSteadyState(model, f_m, 80, kSamples);
  const VectorX ref = ode.dte.row(0).transpose();
  const double ref_l2 = (ref.array() - ref.mean()).matrix().norm();
  const double ref_pp = ref.maxCoeff() - ref.minCoeff();
  std::vector<double> l2, sup;
  for (const int H : {8, 16, 32, 64}) {
    HbOptions options;
    options.harmonics = H;
    options.time_samples = kSamples;
    options.compute_forces = false;
    options.keep_harmonics = true;
    const HbResult r = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    const VectorX got = r.dte_samples.row(0).transpose();
    l2.push_back((got - ref).norm() / ref_l2);
    sup.push_back((got - ref).cwiseAbs().maxCoeff() / ref_pp);
  }
  for (size_t i = 1; i < l2.size(); ++i) {
    const double order_l2 = std::log2(l2[i - 1] / l2[i]);
    const double order_sup = std::log2(sup[i - 1] / sup[i]);
    std::cout << "H " << (8 << i) << ": L2 error " << l2[i] << " (order " << order_l2
              << "), max error " << sup[i] << " (order " << order_sup << ")\n";
    EXPECT_NEAR(order_l2, 2.5, kOrderTol) << "H " << (8 << i);
    EXPECT_NEAR(order_sup, 2.0, kOrderTol) << "H " << (8 << i);
  }
  // The reference (tolerance 1e-11) is far below the H = 64 error: the errors are truncation.
  EXPECT_GT(l2.back(), 1e-8);
}

TEST(HbConvergenceTest, ToleranceModeMeetsTheToleranceAndItsEstimateBoundsTheError) {
  for (const bool smooth : {true, false}) {
    const SystemModel model = smooth ? SmoothPair() : SteppedPair();
    const double f_m = 1800.0;
    HbOptions options;
    options.tolerance = smooth ? 1e-6 : 3e-3;
    options.min_harmonics = 4;
    options.time_samples = 2048;
    options.compute_forces = false;
    const HbResult r = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    EXPECT_LE(r.summary.error_estimate, options.tolerance);
    const double ref = RmsDte(model, smooth ? 64 : 256, f_m);
    const double err = std::abs(r.meshes[0].rms_dte - ref) / ref;
    std::cout << (smooth ? "smooth" : "steps") << ": H " << r.harmonics << ", estimate "
              << r.summary.error_estimate << ", error " << err << "\n";
    // The H/2 → H change over-estimates the error of H (≤ 1.5× the estimate allowed).
    EXPECT_LE(err, 1.5 * r.summary.error_estimate + 1e-12) << (smooth ? "smooth" : "steps");
    if (!smooth) {
      // Algebraic convergence: the estimate is within a factor 10 of the true error.
      EXPECT_GE(err, r.summary.error_estimate / 10.0);
    }
  }
}

TEST(HbConvergenceTest, CondensedEqualsTheFullBlockToeplitzSolve) {
  for (const bool smooth : {true, false}) {
    const SystemModel model = smooth ? SmoothPair() : SteppedPair();
    HbOptions options;
    options.harmonics = 10;
    options.keep_harmonics = true;
    options.method = HbMethod::kCondensed;
    const HbResult condensed = SolveHarmonicBalance(model, options, 3900.0);
    options.method = HbMethod::kDirect;
    const HbResult direct = SolveHarmonicBalance(model, options, 3900.0);
    ASSERT_TRUE(condensed.summary.ok() && direct.summary.ok());
    const MatrixXc diff = condensed.response_harmonics - direct.response_harmonics;
    EXPECT_LE(diff.norm(), 1e-9 * direct.response_harmonics.norm());
    EXPECT_NEAR(condensed.meshes[0].rms_dte, direct.meshes[0].rms_dte,
                1e-9 * direct.meshes[0].rms_dte);
    EXPECT_NEAR(condensed.meshes[0].rms_force, direct.meshes[0].rms_force,
                1e-8 * direct.meshes[0].rms_force);
  }
}

}  // namespace
}  // namespace geardyn
