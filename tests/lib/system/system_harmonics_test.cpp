// System harmonics K_m, C_m, f_m against two independent truths: the sum Σ K_m e^{imθ/P}
// reproduces the directly assembled K(θ), C(θ), f(θ) for trigonometric coefficients, and for
// piecewise-constant ones the harmonics equal the exact integrals over the step structure.
#include "geardyn/system/system_harmonics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <vector>

#include "geardyn/system/system_steps.hpp"
#include "geardyn/system/workspace.hpp"
#include "periodic_fixture.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn::test {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
using Complex = std::complex<double>;

// Σ_{m=−N..N} X_m e^{imθ/P} with X_{−m} = conj(X_m).
template <class T>
auto Synthesize(const std::vector<T>& harmonics, std::int64_t P, double theta) {
  auto sum = harmonics[0].real().eval();
  for (std::size_t m = 1; m < harmonics.size(); ++m) {
    const Complex e = std::polar(1.0, static_cast<double>(m) * theta / static_cast<double>(P));
    sum += 2.0 * (harmonics[m] * e).real();
  }
  return sum;
}

TEST(SystemHarmonics, TrigonometricCoefficientsAreReproducedExactly) {
  // Stiffness of degree 2 (period 1), ε of degree 3 with period 2 meshes: in system harmonics
  // (P = 2) K2 has degree 4 and K2 ε degree 7, so N = 12 holds them exactly.
  MatrixX te_cos = MatrixX::Zero(2, 3), te_sin = MatrixX::Zero(2, 3);
  te_cos(0, 0) = 2e-6;
  te_sin(0, 2) = 1e-6;
  te_cos(1, 1) = 3e-5;
  const FourierCoefficient te =
      FourierCoefficient::FromCosSin(Vector2(1e-6, 0.0), te_cos, te_sin, 2);
  const LinearMeshCore a(MeshCoreLevel::kBlankenshipSingh, SmoothStiffness(4e8, 0.15, 0.05), 0.0125,
                         Coefficient(te));
  const LinearMeshCore b(MeshCoreLevel::kBlankenshipSingh, SmoothStiffness(3e8, -0.1, 0.08),
                         0.0125);
  const SystemModel model = TwoMeshSystem(a, b, 0.77);
  ASSERT_EQ(model.period_meshes(), 2);
  const SystemHarmonics h = ExpandSystemHarmonics(model, 12);
  EXPECT_EQ(h.period_meshes, 2);
  SystemWorkspace ws(model);
  for (const double theta : {0.0, 0.3, 2.1, 4.4, 7.9, 11.0}) {
    const MatrixX K = AssembleStiffness(model, ws, theta);
    EXPECT_MATRIX_NEAR(Synthesize(h.stiffness, 2, theta), K, 1e-12 * K.norm());
    const VectorX f = AssembleLoad(model, ws, theta);
    EXPECT_MATRIX_NEAR(Synthesize(h.load, 2, theta), f, 1e-11 * f.norm());
  }
  // Odd system harmonics of the stiffness vanish (the stiffness has period 1 = half of P).
  EXPECT_LT(h.stiffness[3].norm(), 1e-9 * h.stiffness[0].norm());
  EXPECT_GT(h.stiffness[2].norm(), 1e-3 * h.stiffness[0].norm());
}

TEST(SystemHarmonics, LoadOfStepwiseStiffnessTimesAHuntingPeriodErrorIsTheExactIntegral) {
  // A spur step stiffness (period 1) times ε of period 3 meshes (tooth errors): the load
  // harmonics come from the convolution of K2's exact step harmonics with ε's (FFT synthesis, no
  // samples over the hunting period). Truth: (1/2πP) ∫_0^{2πP} f(θ) e^{−imθ/P} dθ of the directly
  // assembled load f(θ) = Σ Gᵀ K2 ε, by composite Simpson between the steps (where f is a smooth
  // trigonometric polynomial): 6000 panels per radian, error O((ωh)⁴/180) < 1e-12 for ω ≤ 9.
  constexpr std::int64_t kP = 3;
  MatrixX te_cos = MatrixX::Zero(2, 5), te_sin = MatrixX::Zero(2, 5);
  te_cos(0, 0) = 2e-6;  // harmonic 1/3: a runout-like line
  te_sin(0, 2) = 1e-6;  // harmonic 1: the mesh order
  te_cos(0, 4) = 4e-7;
  te_sin(1, 1) = 3e-5;
  te_cos(1, 3) = -1e-5;
  const FourierCoefficient te =
      FourierCoefficient::FromCosSin(Vector2(1e-6, 2e-6), te_cos, te_sin, kP);
  const double start = 0.3, split = kTwoPi * 0.6;
  const LinearMeshCore a(MeshCoreLevel::kBlankenshipSingh, SpurWave(3e8, 6e8, 1.6, start), 0.0125,
                         Coefficient(te), MeshDamping::FromCoefficient(800.0));
  const LinearMeshCore b(MeshCoreLevel::kBlankenshipSingh, SmoothStiffness(3e8, -0.1, 0.08),
                         0.0125);
  const SystemModel model = TwoMeshSystem(a, b, 0.9);
  ASSERT_EQ(model.period_meshes(), kP);
  const int N = 21;  // 7 mesh orders in harmonics of ω_m/3
  const SystemHarmonics h = ExpandSystemHarmonics(model, N);
  SystemWorkspace ws(model);
  std::vector<double> breaks = {0.0, kTwoPi * kP};
  for (int j = 0; j < kP; ++j) {
    breaks.push_back(start + kTwoPi * j);
    breaks.push_back(start + split + kTwoPi * j);
  }
  std::sort(breaks.begin(), breaks.end());
  const int n = model.num_dofs();
  std::vector<VectorXc> truth(N + 1, VectorXc::Zero(n));
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double lo = breaks[k], hi = breaks[k + 1];
    if (!(hi > lo)) continue;
    const int panels = 2 * static_cast<int>(std::ceil(3000.0 * (hi - lo)));
    const double step = (hi - lo) / panels;
    for (int i = 0; i <= panels; ++i) {
      const double w = (i == 0 || i == panels) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      // Inside the interval (a step is right-continuous): evaluate a hair inside its ends.
      const double theta = std::clamp(lo + i * step, lo + 1e-13, hi - 1e-13);
      const VectorX f = AssembleLoad(model, ws, theta);
      for (int m = 0; m <= N; ++m) {
        truth[m] += f.cast<Complex>() * std::polar(w * step / 3.0, -m * theta / kP) /
                    (kTwoPi * static_cast<double>(kP));
      }
    }
  }
  const double scale = truth[0].norm() + truth[3].norm();
  for (int m = 0; m <= N; ++m) {
    EXPECT_LT((h.load[m] - truth[m]).norm(), 1e-9 * scale) << "m = " << m;
  }
  // Not trivially zero: the ε line at 1/3 mixes with K2's mesh orders into every harmonic.
  EXPECT_GT(h.load[1].norm(), 1e-3 * scale);
  EXPECT_GT(h.load[4].norm(), 1e-3 * scale);
}

TEST(SystemHarmonics, DampingOfASmoothCoreConvergesToTheAssembledDamping) {
  const LinearMeshCore a(MeshCoreLevel::kBlankenshipSingh, SmoothStiffness(4e8, 0.15, 0.05), 0.0125,
                         std::nullopt, MeshDamping::FromCoefficient(900.0));
  const SystemModel model = TwoMeshSystem(a, SpurCore(HandPairParams{}), 0.0);
  const SystemHarmonics h = ExpandSystemHarmonics(model, 40);
  SystemWorkspace ws(model);
  for (const double theta : {0.1, 1.7, 3.3, 5.0}) {
    const MatrixX C = AssembleDamping(model, ws, theta);
    EXPECT_MATRIX_NEAR(Synthesize(h.damping, 1, theta), C, 1e-10 * C.norm());
  }
}

TEST(SystemHarmonics, StepwiseHarmonicsEqualTheExactIntegralsOverTheSteps) {
  const LinearMeshCore a(MeshCoreLevel::kBlankenshipSingh, SpurWave(3e8, 6e8, 1.6), 0.0125,
                         std::nullopt, MeshDamping::FromCoefficient(800.0));
  const LinearMeshCore b(MeshCoreLevel::kBlankenshipSingh, SpurWave(2e8, 4.5e8, 1.35, 0.2), 0.0125,
                         std::nullopt, MeshDamping::FromCoefficient(500.0));
  const SystemModel model = TwoMeshSystem(a, b, 0.9);
  const int N = 9;
  const SystemHarmonics h = ExpandSystemHarmonics(model, N);
  const SystemSteps steps = CollectSystemSteps(model);
  SystemWorkspace ws(model);
  for (int m = 0; m <= N; ++m) {
    MatrixXc K_m = MatrixXc::Zero(model.num_dofs(), model.num_dofs());
    MatrixXc C_m = K_m;
    for (int k = 0; k < steps.num_intervals(); ++k) {
      // (1/T) ∫_α^β e^{−imθ} dθ of a constant step.
      const double alpha = steps.interval_begin(k), beta = steps.interval_end(k);
      const Complex w = m == 0 ? Complex(beta - alpha)
                               : (std::polar(1.0, -m * beta) - std::polar(1.0, -m * alpha)) /
                                     Complex(0.0, -static_cast<double>(m));
      K_m += AssembleStiffness(model, ws, steps.interval_midpoint(k)).cast<Complex>() * w / kTwoPi;
      C_m += AssembleDamping(model, ws, steps.interval_midpoint(k)).cast<Complex>() * w / kTwoPi;
    }
    EXPECT_LT((h.stiffness[m] - K_m).norm(), 1e-12 * h.stiffness[0].norm()) << "m = " << m;
    EXPECT_LT((h.damping[m] - C_m).norm(), 1e-12 * h.damping[0].norm()) << "m = " << m;
  }
}

TEST(SystemHarmonics, MeanHarmonicIsTheMeanStiffnessAndMeshHarmonicsMatchTheSystemOnes) {
  const LinearMeshCore a(MeshCoreLevel::kBlankenshipSingh, SpurWave(3e8, 6e8, 1.6), 0.0125);
  const SystemModel model = TwoMeshSystem(a, SpurCore(HandPairParams{}), 0.3);
  const std::vector<MeshHarmonics> meshes = ExpandMeshHarmonics(model, 5);
  ASSERT_EQ(meshes.size(), 2u);
  const SystemHarmonics h = AssembleSystemHarmonics(model, meshes);
  SystemWorkspace ws(model);
  EXPECT_MATRIX_NEAR(h.stiffness[0].real(), AssembleMeanStiffness(model, ws), 1e-6);
  EXPECT_MATRIX_NEAR(h.stiffness[0].imag(), MatrixX::Zero(model.num_dofs(), model.num_dofs()), 0.0);
  // A constant core has no harmonics above 0.
  for (int m = 1; m <= 5; ++m) EXPECT_EQ(meshes[1].stiffness[m].norm(), 0.0);
  EXPECT_THROW((void)ExpandMeshHarmonics(model, -1), InvalidInput);
}

}  // namespace
}  // namespace geardyn::test
