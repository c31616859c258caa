// System harmonics K_m, C_m, f_m against two independent truths: the sum Σ K_m e^{imθ/P}
// reproduces the directly assembled K(θ), C(θ), f(θ) for trigonometric coefficients, and for
// piecewise-constant ones the harmonics equal the exact integrals over the step structure.
#include "geardyn/system/system_harmonics.hpp"

#include <gtest/gtest.h>

#include <complex>
#include <numbers>

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
