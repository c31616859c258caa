// Tests of geardyn/system/mesh_core.hpp against independent truths: hand-written K2 of each level
// (spec 01 §3, §5), exact means of trigonometric polynomials and steps, finite differences of the
// slice energy and force, hand-computed clearance laws (Kahraman & Singh 1990), allocation counts
// and error messages. No geardyn::models code is used: the cores are built from hand-made
// coefficients, as an analysis would see them.
#include "geardyn/system/mesh_core.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"
#include "support/no_malloc.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kB = 0.012;  // half face width b [m]
constexpr double kK = 4e8;    // mesh stiffness scale [N/m]
// Sums of O(10) products of ≈1e8 values: a few ulps.
constexpr double kRoundoff = 1e-13;
// Central differences of a piecewise quadratic (energy) or piecewise linear (force) function
// with no kink inside ±h are exact up to the cancellation error ε·|U|/h.
constexpr double kFdTol = 1e-7;

/// (K, K·h, K·μ·b²) of one uniformly loaded line of length F centred at h: μ = κ² + F²/(12b²).
Vector3 Channels(double K, double h, double F) {
  const double mu = (h * h + F * F / 12.0) / (kB * kB);
  return Vector3(K, K * h, K * mu * kB * kB);
}

/// A spur-like rectangular wave: 2 pairs on [0, 1.9), 1 pair on [1.9, 2π) (ε_α = 1.3).
PiecewiseConstantCoefficient Steps() {
  VectorX bp(2);
  bp << 0.0, 1.9;
  MatrixX v(3, 2);
  v.col(0) = Channels(2 * kK, 0.0, 2 * kB);
  v.col(1) = Channels(kK, 0.0, 2 * kB);
  return PiecewiseConstantCoefficient(bp, v);
}

/// A smooth helical-like series: K, K·h, K·μb² with a few harmonics, PSD everywhere.
FourierCoefficient Smooth() {
  const Vector3 mean = Channels(2.2 * kK, 0.001, 2 * kB);
  MatrixXc h = MatrixXc::Zero(3, 3);
  h(0, 0) = Complex(0.05 * kK, 0.02 * kK);
  h(1, 0) = Complex(0.3e-3 * kK, -0.1e-3 * kK);
  h(2, 0) = Complex(0.0, 0.01 * kK * kB * kB);
  h(0, 2) = Complex(-0.01 * kK, 0.0);
  h(1, 1) = Complex(0.0, 0.05e-3 * kK);
  return FourierCoefficient(mean, h);
}

TableCoefficient Table() {
  MatrixX s(3, 5);
  for (int i = 0; i < 5; ++i) s.col(i) = Channels((1.5 + 0.1 * i) * kK, 1e-3 * (i - 2), 2 * kB);
  return TableCoefficient(s);
}

std::vector<Coefficient> AllForms() {
  return {ConstantCoefficient(Channels(kK, 0.002, kB)), Steps(), Smooth(), Table()};
}

Matrix2 HandCore(const Vector3& c, MeshCoreLevel level) {
  Matrix2 K2;
  if (level == MeshCoreLevel::kBlankenshipSingh) {
    K2 << c[0], -c[1], -c[1], c[2];
  } else {
    K2 << c[0], 0.0, 0.0, 0.0;
  }
  return K2;
}

// ---------------------------------------------------------------------------- levels

TEST(MeshCoreTest, StiffnessCoreOfEachLevelIsTheHandWrittenK2) {
  const std::vector<double> thetas = {0.0, 0.3, 1.9, 2.5, 6.1, -4.0, 40.0};
  for (const Coefficient& coef : AllForms()) {
    for (MeshCoreLevel level : {MeshCoreLevel::kBlankenshipSingh, MeshCoreLevel::kCoupling4Dof,
                                MeshCoreLevel::kTorsional}) {
      const LinearMeshCore core(level, coef, kB);
      for (double theta : thetas) {
        VectorX c(3);
        Evaluate(coef, theta, c);
        const Matrix2 K2 = EvalStiffnessCore(core, theta);
        EXPECT_EQ(K2, HandCore(c, level)) << ToString(level) << " theta " << theta;
        // Symmetric PSD always; B–S rank 2 for a line (μ > κ²), reduced levels rank 1.
        const Eigen::SelfAdjointEigenSolver<Matrix2> eig(K2);
        EXPECT_GE(eig.eigenvalues().minCoeff(), -kRoundoff * K2.norm());
        const double det = K2.determinant();
        if (level == MeshCoreLevel::kBlankenshipSingh) {
          EXPECT_GT(det, 1e-6 * K2(0, 0) * K2(1, 1));
        } else {
          EXPECT_EQ(det, 0.0);
          EXPECT_GT(K2(0, 0), 0.0);
        }
      }
    }
  }
}

TEST(MeshCoreTest, TorsionalLevelKeepsOnlyTheAxialRotationColumnsOfG) {
  Matrix2x12 G;
  for (int c = 0; c < 12; ++c) G.col(c) = Vector2(c + 1.0, -0.5 * c);
  EXPECT_EQ(CalcLevelJacobian(MeshCoreLevel::kBlankenshipSingh, G), G);
  EXPECT_EQ(CalcLevelJacobian(MeshCoreLevel::kCoupling4Dof, G), G);
  const Matrix2x12 Gt = CalcLevelJacobian(MeshCoreLevel::kTorsional, G);
  for (int c = 0; c < 12; ++c) {
    const Vector2 expected = (c == 5 || c == 11) ? Vector2(G.col(c)) : Vector2::Zero();
    EXPECT_EQ(Vector2(Gt.col(c)), expected) << c;
  }
  EXPECT_STREQ(ToString(MeshCoreLevel::kBlankenshipSingh), "blankenship_singh");
  EXPECT_STREQ(ToString(MeshCoreLevel::kCoupling4Dof), "coupling_4dof");
  EXPECT_STREQ(ToString(MeshCoreLevel::kTorsional), "torsional");
}

// ---------------------------------------------------------------------------- LTI

TEST(MeshCoreTest, MeanLtiCoreIsTheMeanOfTheLtvCore) {
  // Fourier: the uniform M-point average of a trigonometric polynomial of degree < M is its
  // exact mean. Steps: the interval-width-weighted average, by hand.
  const FourierCoefficient smooth = Smooth();
  const VectorX te_mean = Vector2(2e-6, -1e-5);
  MatrixXc te_h = MatrixXc::Zero(2, 1);
  te_h(0, 0) = Complex(1e-6, 0.5e-6);
  const FourierCoefficient te(te_mean, te_h);
  for (MeshCoreLevel level : {MeshCoreLevel::kBlankenshipSingh, MeshCoreLevel::kCoupling4Dof}) {
    const LinearMeshCore ltv(level, smooth, kB, te, MeshDamping::FromCoefficient(900.0));
    const LinearMeshCore lti = MakeMeanLinearMeshCore(ltv);
    EXPECT_TRUE(lti.is_mean_lti());
    EXPECT_FALSE(ltv.is_mean_lti());
    EXPECT_EQ(lti.level(), level);
    Matrix2 average = Matrix2::Zero();
    constexpr int kPoints = 16;
    for (int i = 0; i < kPoints; ++i) average += EvalStiffnessCore(ltv, kTwoPi * i / kPoints);
    average /= kPoints;
    for (double theta : {0.0, 1.0, 4.0}) {
      EXPECT_TRUE(test::CompareMatrices(EvalStiffnessCore(lti, theta), average, kRoundoff));
      // ε is kept (spec 01 §5 "ε independent"); the load is K̄2 ε(θ).
      EXPECT_EQ(EvalTransmissionError(lti, theta), EvalTransmissionError(ltv, theta));
      EXPECT_TRUE(test::CompareMatrices(EvalTransmissionErrorLoad(lti, theta),
                                        average * EvalTransmissionError(ltv, theta), kRoundoff));
    }
    EXPECT_EQ(Classify(lti), TimeDependence::kConstant);
    EXPECT_EQ(Classify(ltv), TimeDependence::kSmoothPeriodic);
    EXPECT_EQ(ClassifyExcitation(lti), TimeDependence::kSmoothPeriodic);
    EXPECT_EQ(lti.damping().value, 900.0);
  }
  const LinearMeshCore steps(MeshCoreLevel::kBlankenshipSingh, Steps(), kB);
  const Matrix2 by_hand =
      (1.9 * HandCore(Steps().values().col(0), MeshCoreLevel::kBlankenshipSingh) +
       (kTwoPi - 1.9) * HandCore(Steps().values().col(1), MeshCoreLevel::kBlankenshipSingh)) /
      kTwoPi;
  EXPECT_TRUE(test::CompareMatrices(EvalStiffnessCore(MakeMeanLinearMeshCore(steps), 0.7), by_hand,
                                    kRoundoff));
  EXPECT_EQ(Classify(steps), TimeDependence::kPiecewiseConstant);
}

TEST(MeshCoreTest, LtvCoreWithConstantCoefficientsEqualsTheLtiCoreExactly) {
  // Spec 01 §6: "the LTV model with constant coefficients reproduces the LTI model exactly" —
  // exactly up to round-off: the LTI core's mean of a piecewise-constant, Fourier or table
  // coefficient is a weighted sum of equal values, and clang's code for it differs from GCC's in
  // the last bit (1 ulp, seen with clang 14 -O2).
  const Vector3 c = Channels(3 * kK, -0.004, 1.5 * kB);
  for (const Coefficient& constant : std::vector<Coefficient>{
           ConstantCoefficient(c),
           PiecewiseConstantCoefficient(Vector2(0.0, 3.0), MatrixX(c.replicate(1, 2))),
           FourierCoefficient(c, MatrixXc::Zero(3, 4)), TableCoefficient(c.replicate(1, 7))}) {
    const LinearMeshCore ltv(MeshCoreLevel::kBlankenshipSingh, constant, kB);
    const LinearMeshCore lti = MakeMeanLinearMeshCore(ltv);
    EXPECT_EQ(Classify(ltv), TimeDependence::kConstant);
    for (double theta : {0.0, 0.5, 3.0, 5.9}) {
      EXPECT_TRUE(test::CompareMatrices(EvalStiffnessCore(ltv, theta),
                                        EvalStiffnessCore(lti, theta), kRoundoff));
      EXPECT_TRUE(test::CompareMatrices(EvalDampingCore(ltv, theta, 1e3),
                                        EvalDampingCore(lti, theta, 1e3), kRoundoff));
    }
  }
}

// ---------------------------------------------------------------------------- damping, periods

TEST(MeshCoreTest, DampingCoreIsProportionalToTheStiffnessCore) {
  // B–S Eq. (39): C2 = c_m/K K2; zero where K = 0 (a contact-loss interval).
  VectorX bp(2);
  bp << 0.0, 4.0;
  MatrixX v(3, 2);
  v.col(0) = Channels(kK, 0.003, kB);
  v.col(1).setZero();
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh, PiecewiseConstantCoefficient(bp, v),
                            kB, std::nullopt, MeshDamping::FromRatio(0.05));
  const double m_e = 2.5;  // [kg]
  const double c_m = ResolveDampingCoefficient(core, m_e);
  const double mean_k = kK * 4.0 / kTwoPi;
  EXPECT_NEAR(c_m, 2.0 * 0.05 * std::sqrt(mean_k * m_e), kRoundoff * c_m);
  EXPECT_TRUE(test::CompareMatrices(EvalDampingCore(core, 1.0, c_m),
                                    (c_m / kK) * EvalStiffnessCore(core, 1.0), kRoundoff));
  EXPECT_EQ(EvalDampingCore(core, 5.0, c_m), Matrix2::Zero());
  EXPECT_EQ(ResolveDampingCoefficient(MeshDamping::FromCoefficient(77.0), 0.0, 0.0), 77.0);
  EXPECT_EQ(ResolveDampingCoefficient(MeshDamping::None(), 0.0, 0.0), 0.0);
}

TEST(MeshCoreTest, PeriodAndTimeDependenceCombineCoefficients) {
  const ConstantCoefficient k(Channels(kK, 0.0, kB));
  const TableCoefficient te(MatrixX::Random(2, 12) * 1e-6, /*period_meshes=*/6);
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            FourierCoefficient(Channels(kK, 0.0, kB), MatrixXc::Zero(3, 2), 4), kB,
                            te);
  EXPECT_EQ(PeriodMeshes(core), 12);
  EXPECT_EQ(Classify(core), TimeDependence::kConstant);  // all harmonics zero
  EXPECT_EQ(ClassifyExcitation(core), TimeDependence::kSmoothPeriodic);
  const LinearMeshCore plain(MeshCoreLevel::kTorsional, k, kB);
  EXPECT_EQ(ClassifyExcitation(plain), TimeDependence::kConstant);
  EXPECT_EQ(EvalTransmissionErrorLoad(plain, 1.0), Vector2::Zero());
  const MeshCore variant = core;
  EXPECT_EQ(Classify(variant), TimeDependence::kConstant);
  EXPECT_EQ(PeriodMeshes(variant), 12);
}

// ---------------------------------------------------------------------------- slices

/// Brute-force slice energy written from the spec formula (independent of the kernel).
double SliceEnergy(const VectorX& k, const VectorX& sigma, const VectorX& e, double j,
                   const Vector2& d) {
  double u = 0.0;
  for (Eigen::Index s = 0; s < k.size(); ++s) {
    const double a = d[0] - sigma[s] * d[1] - e[s];
    u += 0.5 * k[s] * (std::pow(std::max(a, 0.0), 2) + std::pow(std::max(-a - j, 0.0), 2));
  }
  return u;
}

struct RandomSlices {
  VectorX sigma, k, e;
  double j = 0.0;
};

RandomSlices MakeRandomSlices(int n, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RandomSlices r;
  r.sigma.resize(n);
  r.k.resize(n);
  r.e.resize(n);
  for (int s = 0; s < n; ++s) {
    r.sigma[s] = kB * ((s + 0.5) / n * 2.0 - 1.0);
    r.k[s] = kK / n * (1.0 + 0.5 * u(*rng));
    r.e[s] = 5e-6 * u(*rng);
  }
  r.k[n / 2] = 0.0;  // an empty slice (no contact line in it at this θ)
  r.j = 20e-6;
  return r;
}

TEST(SliceMeshCoreTest, ForceAndJacobianMatchFiniteDifferences) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  constexpr int kSlices = 12;
  const RandomSlices r = MakeRandomSlices(kSlices, &rng);
  const SliceMeshCore core(r.sigma, ConstantCoefficient(r.k), kB, ConstantCoefficient(r.e), r.j);
  SliceMeshWorkspace ws(core);
  const double h = 1e-10;  // [m]; the rotation step is h/b
  int tested = 0, mixed = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vector2 d(30e-6 * u(rng), 2e-3 * u(rng));
    // Skip states within the FD stencil of a kink (a = 0 or a = −j).
    bool near_kink = false;
    for (int s = 0; s < kSlices; ++s) {
      const double a = d[0] - r.sigma[s] * d[1] - r.e[s];
      near_kink = near_kink || std::abs(a) < 10 * h || std::abs(a + r.j) < 10 * h;
    }
    if (near_kink) continue;
    ++tested;
    const SliceForce f = EvalSliceForce(core, ws, 0.3, d[0], d[1]);
    EXPECT_NEAR(f.energy, SliceEnergy(r.k, r.sigma, r.e, r.j, d), kRoundoff * (1.0 + f.energy));
    const Vector2 steps(h, h / kB);
    Vector2 fd_force;
    Matrix2 fd_jac;
    for (int i = 0; i < 2; ++i) {
      Vector2 dp = d, dm = d;
      dp[i] += steps[i];
      dm[i] -= steps[i];
      fd_force[i] =
          (SliceEnergy(r.k, r.sigma, r.e, r.j, dp) - SliceEnergy(r.k, r.sigma, r.e, r.j, dm)) /
          (2 * steps[i]);
      fd_jac.col(i) = (EvalSliceForce(core, ws, 0.3, dp[0], dp[1]).force -
                       EvalSliceForce(core, ws, 0.3, dm[0], dm[1]).force) /
                      (2 * steps[i]);
    }
    // Scale: force [N] and moment [N·m] → compare in units of (F_η, M_ζ/b).
    const Vector2 scale(1.0, 1.0 / kB);
    const double force_scale = kK * 1e-5;
    EXPECT_LE((scale.asDiagonal() * (f.force - fd_force)).norm(), kFdTol * force_scale)
        << "trial " << trial;
    const Matrix2 jac_scale = scale.asDiagonal() * (f.jacobian - fd_jac) * scale.asDiagonal();
    EXPECT_LE(jac_scale.norm(), 1e-5 * kK) << "trial " << trial;
    EXPECT_EQ(f.jacobian, f.jacobian.transpose());
    if (f.num_loaded > 0 && f.num_loaded + f.num_back_loaded < kSlices - 1) ++mixed;
  }
  EXPECT_GT(tested, 300);
  EXPECT_GT(mixed, 50);  // partial contact loss was exercised
}

TEST(SliceMeshCoreTest, ASliceWithNegativeApproachCarriesNoForceAndLeavesTheJacobian) {
  // Three slices; δ_ζ tilts the approach so that slice 2 (σ = +b) separates.
  const VectorX sigma = Eigen::Vector3d(-kB, 0.0, kB);
  const VectorX k = Eigen::Vector3d(1e8, 2e8, 3e8);
  const SliceMeshCore core(sigma, ConstantCoefficient(k), kB);
  SliceMeshWorkspace ws(core);
  const double d_eta = 5e-6, d_zeta = 8e-6 / kB;  // a = (13, 5, −3) µm
  const SliceForce f = EvalSliceForce(core, ws, 0.0, d_eta, d_zeta);
  EXPECT_EQ(f.num_loaded, 2);
  EXPECT_EQ(f.num_back_loaded, 0);
  // The same as a core without slice 2, by hand: F = Σ k a [1, −σ], J = Σ k [[1, −σ], [−σ, σ²]].
  Vector2 F = Vector2::Zero();
  Matrix2 J = Matrix2::Zero();
  for (int s = 0; s < 2; ++s) {
    const double a = d_eta - sigma[s] * d_zeta;
    F += k[s] * a * Vector2(1.0, -sigma[s]);
    J += k[s] * (Matrix2() << 1.0, -sigma[s], -sigma[s], sigma[s] * sigma[s]).finished();
  }
  EXPECT_TRUE(test::CompareMatrices(f.force, F, kRoundoff));
  EXPECT_TRUE(test::CompareMatrices(f.jacobian, J, kRoundoff));
  // Fully separated: nothing at all.
  const SliceForce off = EvalSliceForce(core, ws, 0.0, -1e-6, 0.0);
  EXPECT_EQ(off.force, Vector2::Zero());
  EXPECT_EQ(off.jacobian, Matrix2::Zero());
  EXPECT_EQ(off.num_loaded, 0);
  EXPECT_EQ(off.energy, 0.0);
}

TEST(SliceMeshCoreTest, BackFlankEngagesOnlyAfterTheBacklashCloses) {
  // One slice at σ = 0: the clearance law of Kahraman & Singh (1990),
  // g(a) = a (a > 0), 0 (−j ≤ a ≤ 0), a + j (a < −j).
  const double k = 3e8, j = 40e-6, e = 2e-6;
  const SliceMeshCore core(VectorX::Zero(1), ConstantCoefficient(VectorX::Constant(1, k)), kB,
                           ConstantCoefficient(VectorX::Constant(1, e)), j);
  EXPECT_TRUE(core.has_back_flank());
  SliceMeshWorkspace ws(core);
  for (double d = 20e-6; d >= -70e-6; d -= 0.5e-6) {
    const double a = d - e;
    const double g = a > 0 ? a : (a < -j ? a + j : 0.0);
    const SliceForce f = EvalSliceForce(core, ws, 0.0, d, 0.37);  // δ_ζ has no arm at σ = 0
    EXPECT_NEAR(f.force[0], k * g, 1e-9 * k * 1e-6) << "delta " << d;
    EXPECT_EQ(f.force[1], 0.0);
    EXPECT_EQ(f.jacobian(0, 0), g != 0.0 ? k : 0.0) << "delta " << d;
    EXPECT_EQ(f.num_back_loaded, a < -j ? 1 : 0);
    EXPECT_EQ(f.num_loaded, a > 0 ? 1 : 0);
  }
  // Without back flank (default) nothing pushes back, however far the gap opens.
  const SliceMeshCore one_sided(VectorX::Zero(1), ConstantCoefficient(VectorX::Constant(1, k)), kB);
  EXPECT_FALSE(one_sided.has_back_flank());
  SliceMeshWorkspace ws1(one_sided);
  EXPECT_EQ(EvalSliceForce(one_sided, ws1, 0.0, -1.0, 0.0).force, Vector2::Zero());
  // Zero backlash: a tight mesh, linear through a = 0.
  const SliceMeshCore tight(VectorX::Zero(1), ConstantCoefficient(VectorX::Constant(1, k)), kB,
                            std::nullopt, 0.0);
  SliceMeshWorkspace ws0(tight);
  EXPECT_NEAR(EvalSliceForce(tight, ws0, 0.0, -3e-6, 0.0).force[0], -3e-6 * k, 1e-12 * k);
}

TEST(SliceMeshCoreTest, AllSlicesLoadedIsTheLinearCoreOfTheSliceChannels) {
  std::mt19937 rng(7);
  const RandomSlices r = MakeRandomSlices(9, &rng);
  const SliceMeshCore core(r.sigma, ConstantCoefficient(r.k), kB, ConstantCoefficient(r.e), r.j);
  SliceMeshWorkspace ws(core);
  const Vector3 c = EvalSliceChannels(core, ws, 0.0);
  // Linear limit: F = K2 δ − [Σk e, −Σk σ e] with K2 from the channels (spec 01 §3).
  const LinearMeshCore linear(MeshCoreLevel::kBlankenshipSingh, ConstantCoefficient(c), kB);
  const Vector2 rhs((r.k.array() * r.e.array()).sum(),
                    -(r.k.array() * r.sigma.array() * r.e.array()).sum());
  const Vector2 d(40e-6, 1e-4);  // every a_s > 0
  const SliceForce f = EvalSliceForce(core, ws, 0.0, d[0], d[1]);
  EXPECT_EQ(f.num_loaded, 8);  // 9 slices, one empty
  const Matrix2 K2 = EvalStiffnessCore(linear, 0.0);
  EXPECT_TRUE(test::CompareMatrices(f.jacobian, K2, kRoundoff));
  EXPECT_TRUE(test::CompareMatrices(f.force, K2 * d - rhs, kRoundoff));
  EXPECT_NEAR(c[0], r.k.sum(), kRoundoff * c[0]);
  // Damping on the loaded slices equals the linear C2 when all are loaded.
  EXPECT_TRUE(
      test::CompareMatrices(CalcSliceDampingCore(f, 500.0), (500.0 / K2(0, 0)) * K2, kRoundoff));
  // In the backlash (−j < a_s < 0 for every slice): no contact, no damping.
  EXPECT_EQ(CalcSliceDampingCore(EvalSliceForce(core, ws, 0.0, -10e-6, 0.0), 500.0),
            Matrix2::Zero());
}

TEST(SliceMeshCoreTest, WorkspaceCachesPerCoreAndTheta) {
  const VectorX sigma = Eigen::Vector2d(-kB / 2, kB / 2);
  MatrixX samples(2, 4);
  samples << 1e8, 2e8, 3e8, 4e8, 5e8, 6e8, 7e8, 8e8;
  const SliceMeshCore a(sigma, TableCoefficient(samples), kB);
  const SliceMeshCore b(sigma, ConstantCoefficient(Eigen::Vector2d(1.0, 1.0)), kB,
                        ConstantCoefficient(Eigen::Vector2d(1e-6, -1e-6)));
  const SliceMeshCore a_copy = a;  // same data, same id
  EXPECT_EQ(a.id(), a_copy.id());
  EXPECT_NE(a.id(), b.id());
  SliceMeshWorkspace ws(a);
  EvalSliceValues(a, ws, 0.0);
  EXPECT_EQ(ws.stiffness, Eigen::Vector2d(1e8, 5e8));
  EvalSliceValues(a, ws, kPi / 2);
  EXPECT_EQ(ws.stiffness, Eigen::Vector2d(2e8, 6e8));
  EvalSliceValues(b, ws, kPi / 2);  // another core at the same θ: re-evaluated
  EXPECT_EQ(ws.stiffness, Eigen::Vector2d(1.0, 1.0));
  EXPECT_EQ(ws.separation, Eigen::Vector2d(1e-6, -1e-6));
  EvalSliceValues(a_copy, ws, kPi / 2);  // separation reset for a core without one
  EXPECT_EQ(ws.separation, Eigen::Vector2d::Zero());
  EXPECT_EQ(ws.stiffness, Eigen::Vector2d(2e8, 6e8));
  EXPECT_EQ(Classify(a), TimeDependence::kNonlinear);
  EXPECT_EQ(Classify(MeshCore(a)), TimeDependence::kNonlinear);
  EXPECT_EQ(PeriodMeshes(MeshCore(b)), 1);
  // CalcSliceForce with precomputed values equals EvalSliceForce.
  const SliceForce f1 = EvalSliceForce(a, ws, 1.0, 3e-6, 1e-4);
  const SliceForce f2 = CalcSliceForce(a, ws.stiffness, VectorX(), 3e-6, 1e-4);
  EXPECT_EQ(f1.force, f2.force);
  EXPECT_EQ(f1.jacobian, f2.jacobian);
}

// ---------------------------------------------------------------------------- no allocation

TEST(MeshCoreTest, KernelsDoNotAllocate) {
  if (!GEARDYN_HAVE_ALLOCATION_COUNTER) GTEST_SKIP() << "no allocator interposition here";
  // Positive control: the counter sees Eigen's heap buffers and operator new.
  EXPECT_GE(test::CountAllocations([] {
              VectorX v = VectorX::Ones(100);
              auto p = std::make_unique<double>(v.sum());
              EXPECT_EQ(*p, 100.0);
            }),
            2);
  for (const Coefficient& coef : AllForms()) {
    const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh, coef, kB,
                              TableCoefficient(MatrixX::Constant(2, 8, 1e-6)));
    Matrix2 sink = Matrix2::Zero();
    const long count = test::CountAllocations([&] {
      for (int i = 0; i < 100; ++i) {
        const double theta = 0.1 * i;
        sink += EvalStiffnessCore(core, theta);
        sink += EvalDampingCore(core, theta, 100.0);
        sink.col(0) += EvalTransmissionError(core, theta) + EvalTransmissionErrorLoad(core, theta);
      }
    });
    EXPECT_EQ(count, 0) << "coefficient form " << coef.index();
    EXPECT_TRUE(sink.allFinite());
  }
}

TEST(SliceMeshCoreTest, KernelsDoNotAllocate) {
  if (!GEARDYN_HAVE_ALLOCATION_COUNTER) GTEST_SKIP() << "no allocator interposition here";
  constexpr int kSlices = 40;
  const VectorX sigma = VectorX::LinSpaced(kSlices, -kB, kB);
  MatrixX samples = MatrixX::Constant(kSlices, 64, 1e7);
  samples.row(3).setZero();
  MatrixX steps = MatrixX::Constant(kSlices, 2, 2e7);
  steps.col(1) *= 0.5;
  const std::vector<Coefficient> forms = {ConstantCoefficient(VectorX::Constant(kSlices, 1e7)),
                                          PiecewiseConstantCoefficient(Vector2(0.0, 2.0), steps),
                                          ToFourier(TableCoefficient(samples), 8),
                                          TableCoefficient(samples)};
  for (const Coefficient& coef : forms) {
    const SliceMeshCore core(sigma, coef, kB,
                             TableCoefficient(MatrixX::Constant(kSlices, 16, 1e-6)), 30e-6);
    SliceMeshWorkspace ws(core);
    double sink = 0.0;
    const long count = test::CountAllocations([&] {
      for (int i = 0; i < 100; ++i) {
        const double theta = 0.07 * i;  // a new θ every call: coefficients re-evaluated
        const SliceForce f = EvalSliceForce(core, ws, theta, 1e-6 * (i % 7 - 3), 1e-4);
        sink += f.force.sum() + f.jacobian.sum();
        sink += EvalSliceChannels(core, ws, theta).sum();
        sink += CalcSliceForce(core, ws.stiffness, ws.separation, 2e-6, 0.0).energy;
      }
    });
    EXPECT_EQ(count, 0) << "coefficient form " << coef.index();
    EXPECT_TRUE(std::isfinite(sink));
  }
}

// ---------------------------------------------------------------------------- nonlinear core

/// Test double: a clearance spring between two coordinates, f = −k g(x0 − x1) [1, −1].
class ClearanceSpringCore final : public NonlinearMeshCore {
 public:
  ClearanceSpringCore(double k, double j) : k_(k), j_(j) {}
  int num_coordinates() const override { return 2; }
  std::int64_t period_meshes() const override { return 3; }
  std::unique_ptr<NonlinearMeshCoreWorkspace> MakeWorkspace() const override {
    return std::make_unique<NonlinearMeshCoreWorkspace>();
  }

 protected:
  void DoCalcForces(NonlinearMeshCoreWorkspace& /*ws*/, double /*theta*/, double /*theta_rate*/,
                    const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& /*v*/,
                    bool with_jacobians, NonlinearMeshCoreOutput* out) const override {
    const double a = x[0] - x[1];
    const double g = a > 0 ? a : (a < -j_ ? a + j_ : 0.0);
    out->force << -k_ * g, k_ * g;
    out->energy = 0.5 * k_ * g * g;
    out->num_contacts = g != 0.0 ? 1 : 0;
    if (with_jacobians) {
      const double kt = g != 0.0 ? k_ : 0.0;
      out->stiffness << kt, -kt, -kt, kt;
      out->damping.setZero();
    }
  }

 private:
  double k_, j_;
};

TEST(NonlinearMeshCoreTest, TestDoubleRunsThroughTheInterfaceAndTheVariant) {
  const auto core = std::make_shared<const ClearanceSpringCore>(1e8, 1e-5);
  const MeshCore variant = core;
  EXPECT_EQ(Classify(variant), TimeDependence::kNonlinear);
  EXPECT_EQ(PeriodMeshes(variant), 3);
  auto ws = core->MakeWorkspace();
  NonlinearMeshCoreOutput out = core->MakeOutput();
  EXPECT_EQ(out.force.size(), 2);
  EXPECT_EQ(out.stiffness.rows(), 2);
  core->CalcForces(*ws, 0.0, 0.0, Eigen::Vector2d(3e-6, 0.0), Eigen::Vector2d::Zero(), true, &out);
  EXPECT_NEAR(out.force[0], -300.0, 1e-9);
  EXPECT_EQ(out.stiffness(0, 1), -1e8);
  EXPECT_EQ(out.num_contacts, 1);
  core->CalcForces(*ws, 0.0, 0.0, Eigen::Vector2d(-3e-6, 0.0), Eigen::Vector2d::Zero(), false,
                   &out);
  EXPECT_EQ(out.force, Eigen::Vector2d::Zero());
  EXPECT_THROWS_MESSAGE(core->CalcForces(*ws, 0.0, 0.0, Eigen::Vector3d::Zero(),
                                         Eigen::Vector2d::Zero(), false, &out),
                        InvalidInput, "x: size 3 does not match the expected 2");
  EXPECT_THROWS_MESSAGE(core->CalcForces(*ws, 0.0, 0.0, Eigen::Vector2d::Zero(),
                                         Eigen::Vector2d::Zero(), false, nullptr),
                        InvalidInput, "out: must not be null");
  NonlinearMeshCoreOutput small;
  small.force = VectorX::Zero(2);
  EXPECT_THROWS_MESSAGE(core->CalcForces(*ws, 0.0, 0.0, Eigen::Vector2d::Zero(),
                                         Eigen::Vector2d::Zero(), true, &small),
                        InvalidInput, "out: stiffness and damping must be 2x2");
  const MeshCore null_core = std::shared_ptr<const NonlinearMeshCore>();
  EXPECT_THROWS_MESSAGE(PeriodMeshes(null_core), InvalidInput, "core: null NonlinearMeshCore");
  EXPECT_THROWS_MESSAGE(core->CalcForces(*ws, 0.0, std::nan(""), Eigen::Vector2d::Zero(),
                                         Eigen::Vector2d::Zero(), false, &out),
                        InvalidInput, "theta_rate: must be finite");
  EXPECT_EQ(core->num_internal_coordinates(), 0);
  EXPECT_EQ(core->InternalMass().norm(), 0.0);
  EXPECT_EQ(out.channels.size(), 0);
}

// ---------------------------------------------------------------------------- error paths

TEST(MeshCoreTest, InvalidInputNamesTheField) {
  const ConstantCoefficient k3(Channels(kK, 0.0, kB));
  EXPECT_THROWS_MESSAGE(
      LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, ConstantCoefficient(Vector2(1.0, 2.0)), kB),
      InvalidInput, "stiffness: has 2 channels, expected 3");
  EXPECT_THROWS_MESSAGE(LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, k3, kB,
                                       ConstantCoefficient(Vector3(1.0, 2.0, 3.0))),
                        InvalidInput, "transmission_error: has 3 channels, expected 2");
  EXPECT_THROWS_MESSAGE(LinearMeshCore(MeshCoreLevel::kCoupling4Dof,
                                       ConstantCoefficient(Vector3(kK, 0.01 * kK, 1e-6 * kK)), kB),
                        InvalidInput, "stiffness: value 0 .* makes K2 indefinite");
  EXPECT_THROWS_MESSAGE(LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, k3, 0.0), InvalidInput,
                        "half_face_width: must be positive");
  EXPECT_THROWS_MESSAGE(LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, Steps(), kB, std::nullopt,
                                       MeshDamping{}, /*mean_lti=*/true),
                        InvalidInput, "mean_lti: the LTI level needs constant stiffness channels");
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -1.0}) {
    EXPECT_THROWS_MESSAGE(LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, k3, kB, std::nullopt,
                                         MeshDamping::FromCoefficient(bad)),
                          InvalidInput, "damping.value: must be finite and >= 0");
    EXPECT_THROWS_MESSAGE(SliceMeshCore(VectorX::Zero(1), ConstantCoefficient(VectorX::Ones(1)), kB,
                                        std::nullopt, kNoBackFlank, MeshDamping::FromRatio(bad)),
                          InvalidInput, "damping.value: .*damping ratio");
  }
  const LinearMeshCore ratio(MeshCoreLevel::kBlankenshipSingh, k3, kB, std::nullopt,
                             MeshDamping::FromRatio(0.1));
  EXPECT_THROWS_MESSAGE(ResolveDampingCoefficient(ratio, 0.0), InvalidInput,
                        "equivalent_mass: must be positive");

  const VectorX sigma4 = VectorX::LinSpaced(4, -kB, kB);
  EXPECT_THROWS_MESSAGE(SliceMeshCore(VectorX(), ConstantCoefficient(VectorX::Ones(1)), kB),
                        InvalidInput, "sigma: needs at least one slice");
  EXPECT_THROWS_MESSAGE(SliceMeshCore(sigma4, ConstantCoefficient(VectorX::Ones(3)), kB),
                        InvalidInput, "stiffness: has 3 channels but sigma has 4 slices");
  EXPECT_THROWS_MESSAGE(SliceMeshCore(sigma4, ConstantCoefficient(VectorX::Ones(4)), kB,
                                      ConstantCoefficient(VectorX::Ones(5))),
                        InvalidInput, "separation: has 5 channels but sigma has 4 slices");
  EXPECT_THROWS_MESSAGE(
      SliceMeshCore(sigma4, ConstantCoefficient(VectorX::Ones(4)), kB, std::nullopt, -1e-6),
      InvalidInput, "backlash: must be >= 0");
  EXPECT_THROWS_MESSAGE(SliceMeshCore(sigma4, ConstantCoefficient(VectorX::Ones(4)), kB,
                                      std::nullopt, std::numeric_limits<double>::quiet_NaN()),
                        InvalidInput, "backlash: must be >= 0");
  EXPECT_THROWS_MESSAGE(SliceMeshCore(sigma4, ConstantCoefficient(-VectorX::Ones(4)), kB),
                        InvalidInput, "stiffness: slice 0 has the negative value");
  EXPECT_THROWS_MESSAGE(SliceMeshCore(Eigen::Vector2d(0.0, std::numeric_limits<double>::infinity()),
                                      ConstantCoefficient(VectorX::Ones(2)), kB),
                        InvalidInput, "sigma\\[1\\] = inf m is not finite");
  const SliceMeshCore four(sigma4, ConstantCoefficient(VectorX::Ones(4)), kB);
  const SliceMeshCore two(Eigen::Vector2d(0.0, 1e-3), ConstantCoefficient(VectorX::Ones(2)), kB);
  SliceMeshWorkspace ws2(two);
  EXPECT_THROWS_MESSAGE(EvalSliceForce(four, ws2, 0.0, 0.0, 0.0), InvalidInput,
                        "ws: workspace for 2 slices used with a core of 4 slices");
  EXPECT_THROWS_MESSAGE(CalcSliceForce(four, VectorX::Ones(3), VectorX(), 0.0, 0.0), InvalidInput,
                        "stiffness: size 3 does not match the 4 slices");
  SliceMeshWorkspace ws4(four);
  EXPECT_THROWS_MESSAGE(EvalSliceForce(four, ws4, std::numeric_limits<double>::infinity(), 0, 0),
                        InvalidInput, "not finite");
}

}  // namespace
}  // namespace geardyn
