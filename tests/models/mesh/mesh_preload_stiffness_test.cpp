// Tests of the preloaded mesh's tangent stiffness K_g (mesh_preload_stiffness.hpp, issue 19)
// against the exact geometry of two rigid involute flanks: the second derivatives of their
// approach along the common tangent of the displaced base circles, computed here from the
// involute's definition (the end of a string unwound from the base circle) by central
// differences; plus its structure (rank one, sign, rigid motions) and the rack's limit.
#include "geardyn/models/mesh/mesh_preload_stiffness.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "support/mesh_scenes.hpp"

namespace geardyn {
namespace {

// The six transverse coordinates of the pair, as indices into [q_i; q_j]: pinion x, y, θz and
// gear x, y, θz.
constexpr std::array<int, 6> kTransverse = {0, 1, 5, 6, 7, 11};

double Angle(const Vector2& x) { return std::atan2(x.y(), x.x()); }
// a − b wrapped to (−π, π].
double AngleDifference(double a, double b) { return std::remainder(a - b, 2.0 * std::numbers::pi); }
Vector2 Perp(const Vector2& x) { return {-x.y(), x.x()}; }  // Z × x
Vector2 Xy(const Vector3& x) { return x.head<2>(); }

// Exact transverse approach of the pinion's and the gear's drive flanks (> 0: overlap) after the
// rigid displacements x = (pinion x, y, θz, gear x, y, θz) [m, rad] from the reference pose.
// Independent of the formulas of mesh_preload_stiffness.cpp: the common tangent of the moved base
// circles is solved for, and each flank is the involute that passes through the reference point
// p0 normal to v at x = 0, unwound from its base circle by the angle its tangent point turned
// (the gear's tangent point lies on the far side of its base circle externally, on the near side
// internally: mesh_frame.hpp).
double ExactTransverseApproach(const MeshFrame& f, const Eigen::Matrix<double, 6, 1>& x) {
  const Vector2 u0 = Xy(f.u).normalized(), v0 = Xy(f.v).normalized(), p0 = Xy(f.reference_point);
  const double a_i = f.pinion_base_radius, a_j = f.gear_base_radius;
  const double side_j = f.internal ? 1.0 : -1.0;  // T_j = c_j + side_j a_j m
  // Reference: tangent points, string directions (from the tangent point towards p0), unwinding
  // senses σ (the string leaves along −σ Z × e_r) and the involutes' start angles α.
  const Vector2 c_i0 = Xy(f.pinion_center), c_j0 = Xy(f.gear_center);
  const Vector2 T_i0 = c_i0 + a_i * u0, T_j0 = c_j0 + side_j * a_j * u0;
  const double rho_i0 = (p0 - T_i0).norm(), rho_j0 = (p0 - T_j0).norm();
  const double sigma_i = (Perp(u0).dot(p0 - T_i0) > 0.0) ? -1.0 : 1.0;
  const double sigma_j = (Perp(side_j * u0).dot(p0 - T_j0) > 0.0) ? -1.0 : 1.0;
  const double alpha_i = Angle(u0) - sigma_i * rho_i0 / a_i;
  const double alpha_j = Angle(side_j * u0) - sigma_j * rho_j0 / a_j;
  // Moved pose: the common tangent m·(c_j − c_i) = a_i − side_j a_j, the root closest to u0.
  const Vector2 c_i = c_i0 + x.segment<2>(0), c_j = c_j0 + x.segment<2>(3);
  const Vector2 D = c_j - c_i;
  const double offset = std::acos((a_i - side_j * a_j) / D.norm());
  const double psi_plus = Angle(D) + offset, psi_minus = Angle(D) - offset;
  const auto along_u0 = [&](double psi) { return std::cos(psi) * u0.x() + std::sin(psi) * u0.y(); };
  const double psi = along_u0(psi_plus) > along_u0(psi_minus) ? psi_plus : psi_minus;
  const Vector2 m(std::cos(psi), std::sin(psi));
  // The string lengths: the angle each tangent point has turned relative to the involute's
  // start, which rotated with its body.
  const double t_i = sigma_i * AngleDifference(psi, alpha_i + x(2));
  const double t_j = sigma_j * AngleDifference(Angle(side_j * m), alpha_j + x(5));
  const Vector2 P_i = c_i + a_i * m + a_i * t_i * (-sigma_i * Perp(m));
  const Vector2 P_j = c_j + side_j * a_j * m + a_j * t_j * (-sigma_j * Perp(side_j * m));
  const Vector2 n = Perp(m).dot(v0) > 0.0 ? Perp(m) : Vector2(-Perp(m));
  return (P_i - P_j).dot(n);
}

using Scene = test::MeshScene;

std::vector<Scene> PreloadScenes() { return test::AllMeshScenes(); }

class MeshPreloadSceneTest : public ::testing::TestWithParam<Scene> {};

constexpr double kForce = 2.7e4;  // F̄_η [N]

TEST_P(MeshPreloadSceneTest, TheExactApproachHasTheJacobianAsItsGradient) {
  // The test's exact geometry agrees with the mesh Jacobian to first order (so that its second
  // derivatives below are those of the same approach): δ_η = cos ψ_b δ_t.
  const MeshFrame f = CalcMeshFrame(GetParam().placement);
  const Matrix2x12 G = CalcMeshJacobian(f);
  constexpr double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> dx = Eigen::Matrix<double, 6, 1>::Zero();
    dx(k) = h;
    const double gradient =
        (ExactTransverseApproach(f, dx) - ExactTransverseApproach(f, -dx)) / (2.0 * h);
    EXPECT_NEAR(std::cos(f.base_helix_angle) * gradient, G(0, kTransverse[k]), 1e-8)
        << "coordinate " << kTransverse[k];
  }
  EXPECT_NEAR(ExactTransverseApproach(f, Eigen::Matrix<double, 6, 1>::Zero()), 0.0, 1e-15);
}

TEST_P(MeshPreloadSceneTest, IsTheForceTimesTheSecondDerivativeOfTheExactApproach) {
  const MeshFrame f = CalcMeshFrame(GetParam().placement);
  const Matrix12 K = CalcMeshPreloadStiffness(f, kForce);
  // Central second differences, step h: truncation h^2/12 |d4 delta| (about 1e-7 relative at
  // h = 1e-5 on the internal pair's L = 25 mm, so 1e-8 here) and cancellation eps |delta| / h^2
  // (about 5e-7 1/m) against entries cos(psi_b) / L of about 40 1/m (times F): 1e-6 holds both.
  constexpr double h = 3e-6;
  const double scale = K.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  const auto approach = [&](int a, double sa, int b, double sb) {
    Eigen::Matrix<double, 6, 1> dx = Eigen::Matrix<double, 6, 1>::Zero();
    dx(a) += sa * h;
    dx(b) += sb * h;
    return ExactTransverseApproach(f, dx);
  };
  const double normal_over_transverse = kForce * std::cos(f.base_helix_angle);
  for (int a = 0; a < 6; ++a) {
    for (int b = 0; b < 6; ++b) {
      const double second = (approach(a, 1, b, 1) - approach(a, 1, b, -1) - approach(a, -1, b, 1) +
                             approach(a, -1, b, -1)) /
                            (4.0 * h * h);
      EXPECT_NEAR(normal_over_transverse * second, K(kTransverse[a], kTransverse[b]), 1e-6 * scale)
          << "coordinates " << kTransverse[a] << ", " << kTransverse[b];
    }
  }
}

TEST_P(MeshPreloadSceneTest, IsARankOneStrutAcrossTheLineOfAction) {
  const MeshFrame f = CalcMeshFrame(GetParam().placement);
  const Matrix12 K = CalcMeshPreloadStiffness(f, kForce);
  EXPECT_LE((K - K.transpose()).cwiseAbs().maxCoeff(), 0.0);
  // The closed form: |κ| = F cos ψ_b / (C sin φ), softening externally, stiffening internally.
  const double expected = kForce * std::cos(f.base_helix_angle) /
                          (f.center_distance * std::sin(f.operating_pressure_angle));
  const double kappa = CalcMeshPreloadCoefficient(f, kForce);
  EXPECT_NEAR(kappa, f.internal ? expected : -expected, 1e-12 * expected);
  Eigen::SelfAdjointEigenSolver<Matrix12> eig(K);
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  EXPECT_NEAR(largest, 2.0 * expected, 1e-12 * expected);  // κ |b|², |b|² = 2
  int nonzero = 0;
  for (int k = 0; k < 12; ++k) nonzero += std::abs(eig.eigenvalues()(k)) > 1e-12 * largest;
  EXPECT_EQ(nonzero, 1);
  // A common translation, any rotation of either body, the conjugate rolling: no energy; a
  // relative shift along the line of action (v) neither: only across it (u).
  for (int k : {0, 1, 2}) {
    Vector12 q = Vector12::Zero();
    q(k) = q(6 + k) = 1.0;
    EXPECT_LE((K * q).norm(), 1e-12 * largest);
  }
  for (int k : {3, 4, 5, 9, 10, 11}) EXPECT_LE(K.col(k).norm(), 0.0);
  Vector12 along = Vector12::Zero();
  along.segment<3>(6) = f.v;
  EXPECT_LE((K * along).norm(), 1e-12 * largest);
  // The work of the preload in a relative shift across the line: ½ κ |Δ|².
  Vector12 across = Vector12::Zero();
  across.segment<3>(6) = f.u;
  EXPECT_NEAR(across.dot(K * across), kappa, 1e-12 * expected);
}

INSTANTIATE_TEST_SUITE_P(Meshes, MeshPreloadSceneTest, ::testing::ValuesIn(PreloadScenes()),
                         [](const auto& info) { return info.param.name; });

TEST(MeshPreloadStiffnessTest, VanishesOnARackAndGrowsWithTheForce) {
  MeshPlacement rack = test::MakeMeshPlacement(false, HelixHand::kNone, 1, false);
  rack.rack = true;
  rack.gear_base_radius = 0.0;
  rack.operating_pressure_angle = DegToRad(20.0);
  rack.gear_center = rack.pinion_center + rack.pinion_base_radius /
                                              std::cos(rack.operating_pressure_angle) *
                                              Vector3::UnitX();
  EXPECT_EQ(CalcMeshPreloadStiffness(CalcMeshFrame(rack), kForce).cwiseAbs().maxCoeff(), 0.0);
  // The rack is the limit of a growing gear: κ ∝ 1/(C sin φ) → 0 as z₂ → ∞.
  MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kNone, 1, false);
  double previous = std::abs(CalcMeshPreloadCoefficient(CalcMeshFrame(p), kForce));
  for (double factor : {10.0, 100.0, 1000.0}) {
    MeshPlacement big = p;
    big.gear_base_radius = p.gear_base_radius * factor;
    const double C =
        (big.pinion_base_radius + big.gear_base_radius) / std::cos(big.operating_pressure_angle);
    big.gear_center = big.pinion_center + C * Vector3::UnitX();
    const double kappa = std::abs(CalcMeshPreloadCoefficient(CalcMeshFrame(big), kForce));
    EXPECT_LT(kappa, previous / 5.0) << factor;
    previous = kappa;
  }
  // Linear in the force; zero force, zero stiffness; a non-finite force is refused.
  const MeshFrame f = CalcMeshFrame(p);
  EXPECT_NEAR(CalcMeshPreloadCoefficient(f, 2.0 * kForce),
              2.0 * CalcMeshPreloadCoefficient(f, kForce),
              1e-15 * std::abs(CalcMeshPreloadCoefficient(f, kForce)));
  EXPECT_EQ(CalcMeshPreloadCoefficient(f, 0.0), 0.0);
  EXPECT_THROW(CalcMeshPreloadCoefficient(f, std::nan("")), InvalidInput);
}

}  // namespace
}  // namespace geardyn
