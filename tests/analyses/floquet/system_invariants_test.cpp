// Floquet analysis of the hand-built 12-DOF pair (tests/lib/system/hand_pair.hpp): physics
// invariants as independent truths —
// * LTI limit: Φ(T) = expm(A T) with A formed here from M, K, C (Eigen's MatrixFunctions);
// * undamped (Hamiltonian): Φ symplectic, so det Φ = 1 and the multipliers are closed under
//   λ ↦ 1/λ (reciprocal pairs; Yakubovich & Starzhinskii 1975, Ch. III);
// * damped: Liouville's formula det Φ(T) = exp(−∫₀ᵀ tr(M⁻¹C(t)) dt);
// * rigid-body rotation: two multipliers exactly 1, never "unstable";
// * the block split gives the same multipliers and monodromy as the whole system.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/system_steps.hpp"
#include "geardyn/system/workspace.hpp"
#include "support/expect_throws.hpp"

namespace geardyn::test {
namespace {

constexpr double kMeshHz = 5000.0;  // f_m [Hz]: T = 0.2 ms, a few periods of the top mode

// A = [[0, I], [−M⁻¹K, −M⁻¹C]] (n×n dense inputs).
MatrixX StateMatrix(const MatrixX& M, const MatrixX& K, const MatrixX& C) {
  const int n = static_cast<int>(M.rows());
  MatrixX A = MatrixX::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -M.ldlt().solve(K);
  A.bottomRightCorner(n, n) = -M.ldlt().solve(C);
  return A;
}

// ‖D⁻¹(X − Y)D‖ / ‖D⁻¹ Y D‖ with D = diag(I, ω I): compares q and q̇ blocks on one scale.
double ScaledDifference(const MatrixX& X, const MatrixX& Y, double omega) {
  const int n = static_cast<int>(X.rows()) / 2;
  VectorX d = VectorX::Ones(2 * n);
  d.tail(n).setConstant(omega);
  const MatrixX S = d.asDiagonal().inverse() * (X - Y) * d.asDiagonal();
  const MatrixX R = d.asDiagonal().inverse() * Y * d.asDiagonal();
  return S.norm() / R.norm();
}

FloquetOptions Options(FloquetMethod method = FloquetMethod::kAuto) {
  FloquetOptions o;
  o.mesh_frequency_hz = kMeshHz;
  o.method = method;
  return o;
}

TEST(FloquetSystemTest, LtiLimitIsTheMatrixExponential) {
  const HandPairParams p;
  const SystemModel model =
      HandPairBuilder(p, LinearMeshCore(MeshCoreLevel::kBlankenshipSingh,
                                        ConstantCoefficient(Vector3(p.k, 0.0, p.k * p.b * p.b / 3)),
                                        p.b, std::nullopt, MeshDamping::FromCoefficient(900.0)))
          .Build();
  FloquetOptions o = Options();
  o.keep_monodromy = true;
  const FloquetResult r = ComputeFloquet(model, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.method_used, FloquetMethod::kExactSteps);
  SystemWorkspace ws(model);
  const MatrixX K = AssembleStiffness(model, ws, 0.0), C = AssembleDamping(model, ws, 0.0);
  // expm(A T) = D expm(D⁻¹ A D T) D⁻¹ with D = diag(I, ω I): the balanced form keeps Eigen's
  // scaling-and-squaring accurate (unbalanced, the K/M ≈ 1e9 block costs it five digits).
  const double w = 2e4;
  VectorX d = VectorX::Ones(24);
  d.tail(12).setConstant(w);
  const MatrixX A = StateMatrix(model.DenseMass(), K, C);
  const MatrixX balanced = d.asDiagonal().inverse() * A * d.asDiagonal();
  const MatrixX expected =
      d.asDiagonal() * MatrixX((balanced * r.period_s).exp()) * d.asDiagonal().inverse();
  EXPECT_LE(ScaledDifference(r.monodromy, expected, 2e4), 1e-12);
  EXPECT_NEAR(r.period_s, 1.0 / kMeshHz, 1e-18);
}

TEST(FloquetSystemTest, UndampedPairHasReciprocalMultipliersAndUnitDeterminant) {
  for (const bool smooth : {false, true}) {
    const SystemModel model = smooth ? HandPair(HandSmoothCore()) : HandPair(HandSpurWaveCore());
    FloquetOptions o = Options();
    o.keep_monodromy = true;
    o.split_blocks = false;
    const FloquetResult r = ComputeFloquet(model, o);
    ASSERT_TRUE(r.summary.ok()) << r.summary.message;
    EXPECT_EQ(r.method_used, smooth ? FloquetMethod::kMagnus : FloquetMethod::kExactSteps);
    ASSERT_EQ(r.multipliers.size(), 24);
    const VectorXc inverse = r.multipliers.cwiseInverse();
    EXPECT_LE(MultiplierDistance(r.multipliers, inverse), 1e-9) << "smooth " << smooth;
    EXPECT_NEAR(std::abs(r.multipliers.prod() - 1.0), 0.0, 1e-9);
    EXPECT_NEAR(r.monodromy.determinant(), 1.0, 1e-8);
    // One free rotation: the double multiplier 1 exactly, and a stable verdict.
    EXPECT_EQ(r.summary.counters.at("num_rigid_modes"), 1);
    EXPECT_EQ((r.multipliers.array() == std::complex<double>(1.0)).count(), 2);
    EXPECT_TRUE(r.stable());
    EXPECT_LE(r.max_abs_multiplier, 1.0 + r.summary.error_estimate);
  }
}

TEST(FloquetSystemTest, DampedDeterminantFollowsLiouville) {
  const SystemModel model = HandPair(HandSpurWaveCore(1500.0));
  FloquetOptions o = Options();
  o.keep_monodromy = true;
  const FloquetResult r = ComputeFloquet(model, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  // ∫ tr(M⁻¹C) dt over the steps (C constant on each).
  const SystemSteps steps = CollectSystemSteps(model);
  SystemWorkspace ws(model);
  const MatrixX M = model.DenseMass();
  double integral = 0.0;
  for (int k = 0; k < steps.num_intervals(); ++k) {
    const MatrixX C = AssembleDamping(model, ws, steps.interval_midpoint(k));
    integral +=
        M.ldlt().solve(C).trace() * steps.interval_width(k) / (2 * std::numbers::pi * kMeshHz);
  }
  ASSERT_GT(integral, 0.1);
  EXPECT_NEAR(std::abs(r.multipliers.prod()) / std::exp(-integral), 1.0, 1e-10);
  EXPECT_NEAR(r.monodromy.determinant() / std::exp(-integral), 1.0, 1e-8);
  EXPECT_LT(r.max_abs_multiplier, 1.0 + 1e-12);
}

TEST(FloquetSystemTest, BlockSplitGivesTheSameMultipliersAndMonodromy) {
  const SystemModel model = HandPair(HandSpurWaveCore(800.0));
  ASSERT_GT(model.num_blocks(), 1);
  FloquetOptions o = Options();
  o.keep_monodromy = true;
  const FloquetResult split = ComputeFloquet(model, o);
  o.split_blocks = false;
  const FloquetResult whole = ComputeFloquet(model, o);
  EXPECT_EQ(split.summary.counters.at("blocks"), model.num_blocks());
  EXPECT_LE(MultiplierDistance(split.multipliers, whole.multipliers), 1e-11);
  EXPECT_LE(ScaledDifference(split.monodromy, whole.monodromy, 2e4), 1e-11);
}

TEST(FloquetSystemTest, FreePairWithTenRigidModesIsStable) {
  HandPairParams p;
  p.bearings = false;
  const SystemModel model = HandPairBuilder(p, HandSpurWaveCore()).Build();
  FloquetOptions o = Options();
  o.split_blocks = false;
  const FloquetResult r = ComputeFloquet(model, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  // 12 DOFs, G of rank 2 (δ_η, δ_ζ): 10 rigid-body modes.
  EXPECT_EQ(r.summary.counters.at("num_rigid_modes"), 10);
  EXPECT_TRUE(r.stable());
  EXPECT_EQ((r.multipliers.array() == std::complex<double>(1.0)).count(), 20);
}

TEST(FloquetSystemTest, InvalidInputsNameTheProblem) {
  const SystemModel model = HandPair(HandSpurWaveCore());
  FloquetOptions o;  // mesh_frequency_hz = 0
  EXPECT_THROWS_MESSAGE(ComputeFloquet(model, o), InvalidInput, "mesh_frequency_hz");
  o = Options();
  o.magnus_order = 5;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(model, o), InvalidInput, "magnus_order");
  o = Options(FloquetMethod::kExactSteps);
  EXPECT_THROWS_MESSAGE(ComputeFloquet(HandPair(HandSmoothCore()), o), InvalidInput, "mesh");
}

}  // namespace
}  // namespace geardyn::test
