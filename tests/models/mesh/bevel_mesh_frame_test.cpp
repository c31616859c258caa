// The straight bevel pair's mesh interface (issue 19): the frame at the mean point and its mesh
// Jacobian against independent truths —
// * the textbook force components of a straight bevel mesh (Shigley's Mechanical Engineering
//   Design, 10th ed., Eq. 13-38: W_r = W_t tan α cos γ, W_a = W_t tan α sin γ, the axial thrust
//   towards the heel, the radial force separating) and the torque −s F r_m cos α;
// * G against central differences of the exact large-motion approach of the material contact
//   point (each body carrying the point and the normal rigidly: the same geometric truth as
//   mesh_jacobian_test);
// * energy invariants: K̄ = Gᵀ K₂ G symmetric PSD, the six rigid motions and the rolling
//   (ω₁ r_m1 = −ω₂ r_m2 about the apex-outward axes) without deflection, so the approach row
//   leaves 12 − 1 = 11 zero-energy motions of a free pair (10 with the twist row);
// * the parallel-axis limit: as Σ → 0 the frame and G tend to those of the spur pair with the
//   mean pitch radii and α_wt = α (CalcMeshFrame), to first order in Σ;
// * bad placements refused at their field.
#include "geardyn/models/mesh/bevel_mesh_frame.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "support/bevel_specs.hpp"
#include "support/exact_approach.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

BevelPairSpec Spec(double sigma_deg, int z1 = 20, int z2 = 40, double m_et = 3e-3,
                   double b = 20e-3) {
  return test::BevelSpec(z1, z2, m_et, b, sigma_deg);
}

// A placement at Σ: the pinion's axis along an oblique unit vector, the gear's turned by Σ
// about an axis normal to it, the apex off the origin.
BevelPlacement Placement(double sigma, int s) {
  BevelPlacement p;
  p.apex = Vector3(0.11, -0.07, 0.23);
  p.pinion_axis = Vector3(0.3, -0.4, 0.866).normalized();
  const Vector3 normal = p.pinion_axis.cross(Vector3(1.0, 0.2, 0.1)).normalized();
  p.gear_axis = Eigen::AngleAxisd(sigma, normal) * p.pinion_axis;
  p.drive_sign = s;
  return p;
}

struct Case {
  std::string name;
  double sigma_deg;
  int drive_sign;
};

std::vector<Case> Cases() {
  std::vector<Case> cases;
  for (double sigma : {90.0, 60.0, 115.0}) {
    for (int s : {1, -1}) {
      cases.push_back({"sigma" + std::to_string(static_cast<int>(sigma)) +
                           (s > 0 ? "_drive_pos" : "_drive_neg"),
                       sigma, s});
    }
  }
  return cases;
}

class BevelMeshFrameTest : public ::testing::TestWithParam<Case> {
 protected:
  BevelPairGeometry geometry() const { return CalcBevelPairGeometry(Spec(GetParam().sigma_deg)); }
  BevelMeshFrame frame() const {
    return CalcBevelMeshFrame(geometry(),
                              Placement(DegToRad(GetParam().sigma_deg), GetParam().drive_sign));
  }
};

TEST_P(BevelMeshFrameTest, ForceComponentsAreTheTextbookOnes) {
  const BevelPairGeometry g = geometry();
  const BevelMeshFrame b = frame();
  const MeshFrame& f = b.frame;
  const double s = GetParam().drive_sign, alpha = g.spec.pressure_angle;
  constexpr double F = 1000.0;  // normal mesh force [N]
  const Vector3 on_pinion = -F * f.eta;
  const Vector3 radial = f.pinion_lever_arm.normalized();
  const double W_t = F * std::cos(alpha);
  // Tangential: opposes the drive; radial: separating (towards the pinion's axis); axial:
  // towards the heel (+a_i). Shigley Eq. 13-38 with γ = δ₁.
  EXPECT_NEAR(on_pinion.dot(b.pitch_tangent), -s * W_t, 1e-9 * F);
  EXPECT_NEAR(on_pinion.dot(radial), -W_t * std::tan(alpha) * std::cos(g.pinion_cone_angle),
              1e-9 * F);
  EXPECT_NEAR(on_pinion.dot(b.pinion_axis), W_t * std::tan(alpha) * std::sin(g.pinion_cone_angle),
              1e-9 * F);
  // The same on the gear with γ = δ₂ (the reaction +F η).
  const Vector3 gear_radial = f.gear_lever_arm.normalized();
  EXPECT_NEAR((F * f.eta).dot(gear_radial), -W_t * std::tan(alpha) * std::cos(g.gear_cone_angle),
              1e-9 * F);
  EXPECT_NEAR((F * f.eta).dot(b.gear_axis), W_t * std::tan(alpha) * std::sin(g.gear_cone_angle),
              1e-9 * F);
  // Torques about each axis: −s F r_m1 cos α on the pinion, and the gear's is the same times
  // r_m2 / r_m1 (it turns the gear against its own axis' positive sense: external).
  EXPECT_NEAR(b.pinion_axis.dot(f.pinion_lever_arm.cross(on_pinion)),
              -s * W_t * g.pinion_mean_pitch_radius, 1e-9 * F * g.pinion_mean_pitch_radius);
  EXPECT_NEAR(b.gear_axis.dot(f.gear_lever_arm.cross(F * f.eta)),
              -s * W_t * g.gear_mean_pitch_radius, 1e-9 * F * g.gear_mean_pitch_radius);
  // Geometry of the frame: unit, orthogonal, η ⊥ the cone element, P on both pitch cones.
  EXPECT_NEAR(f.eta.norm(), 1.0, 1e-15);
  EXPECT_NEAR(f.u.dot(f.v), 0.0, 1e-15);
  EXPECT_NEAR(f.eta.dot(b.cone_element), 0.0, 1e-15);
  EXPECT_NEAR(f.pinion_lever_arm.norm(), g.pinion_mean_pitch_radius, 1e-15);
  EXPECT_NEAR(f.gear_lever_arm.norm(), g.gear_mean_pitch_radius, 1e-15);
  EXPECT_NEAR(f.pinion_lever_arm.dot(b.pinion_axis), 0.0, 1e-15);
  EXPECT_NEAR(f.gear_lever_arm.dot(b.gear_axis), 0.0, 1e-15);
  EXPECT_NEAR((f.reference_point - b.apex).norm(), g.mean_cone_distance, 1e-15);
}

TEST_P(BevelMeshFrameTest, JacobianIsTheDerivativeOfTheExactApproach) {
  const MeshFrame f = frame().frame;
  const Matrix2x12 G = CalcMeshJacobian(f);
  constexpr double h = 1e-6;
  for (double sigma : {0.0, 0.006, -0.006}) {
    Eigen::Matrix<double, 1, 12> fd;
    for (int k = 0; k < 12; ++k) {
      Vector12 dq = Vector12::Zero();
      dq(k) = h;
      fd(k) =
          (test::ExactMaterialApproach(f, dq, sigma) - test::ExactMaterialApproach(f, -dq, sigma)) /
          (2.0 * h);
    }
    EXPECT_LE((fd - (G.row(0) - sigma * G.row(1))).cwiseAbs().maxCoeff(), 1e-8)
        << "sigma = " << sigma;
  }
}

TEST_P(BevelMeshFrameTest, RigidAndRollingMotionsCarryNoEnergy) {
  const BevelPairGeometry g = geometry();
  const BevelMeshFrame b = frame();
  const Matrix2x12 G = CalcMeshJacobian(b.frame);
  const double scale = G.cwiseAbs().maxCoeff();
  // Six rigid motions of the pair.
  for (int k = 0; k < 3; ++k) {
    Vector12 q = Vector12::Zero();
    q(k) = q(6 + k) = 1.0;
    EXPECT_LE((G * q).norm(), 1e-14 * scale);
    q.setZero();
    const Vector3 omega = Vector3::Unit(k);
    q << omega.cross(b.frame.pinion_center - b.apex), omega,
        omega.cross(b.frame.gear_center - b.apex), omega;
    EXPECT_LE((G * q).norm(), 1e-14 * scale * q.norm());
  }
  // Rolling: ω₁ a_i and ω₂ a_j with ω₁ r_m1 = −ω₂ r_m2: no approach (row η).
  Vector12 roll = Vector12::Zero();
  roll.segment<3>(3) = b.pinion_axis / g.pinion_mean_pitch_radius;
  roll.segment<3>(9) = -b.gear_axis / g.gear_mean_pitch_radius;
  EXPECT_LE(std::abs(G.row(0).dot(roll)), 1e-14 * scale * roll.norm());
  // K̄ = Gᵀ diag(k, k_ζ) G: symmetric PSD; zero-energy motions 12 − 2 = 10 with the twist row,
  // 12 − 1 = 11 with the approach row alone (6 rigid + rolling + 4 that slide or twist the
  // teeth without approach).
  const Matrix12 K = G.transpose() * Vector2(4e8, 2e5).asDiagonal() * G;
  EXPECT_LE((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-15 * K.cwiseAbs().maxCoeff());
  const Eigen::SelfAdjointEigenSolver<Matrix12> eig(K);
  const double largest = eig.eigenvalues().maxCoeff();
  EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12 * largest);
  int zero = 0;
  for (int k = 0; k < 12; ++k) zero += eig.eigenvalues()(k) <= 1e-10 * largest;
  EXPECT_EQ(zero, 10);
  const Matrix12 K_eta = G.row(0).transpose() * G.row(0);
  const Eigen::SelfAdjointEigenSolver<Matrix12> eig_eta(K_eta);
  zero = 0;
  for (int k = 0; k < 12; ++k)
    zero += eig_eta.eigenvalues()(k) <= 1e-10 * eig_eta.eigenvalues().maxCoeff();
  EXPECT_EQ(zero, 11);
}

INSTANTIATE_TEST_SUITE_P(ShaftAngles, BevelMeshFrameTest, ::testing::ValuesIn(Cases()),
                         [](const auto& info) { return info.param.name; });

TEST(BevelMeshFrameLimitTest, SmallShaftAngleTendsToTheSpurPair) {
  // Pinion axis +Z, the gear's turned by Σ about −Y so that the gear lies on +X; the pinion's
  // reference point at the origin. The spur pair of the mean pitch radii sits at the same
  // centres with parallel axes.
  double previous = INFINITY;
  for (double sigma : {1e-2, 1e-3, 1e-4}) {
    const BevelPairGeometry g = CalcBevelPairGeometry(Spec(RadToDeg(sigma), 20, 40, 3e-3, 10e-3));
    BevelPlacement p;
    p.pinion_axis = Vector3::UnitZ();
    p.gear_axis = Vector3(std::sin(sigma), 0.0, std::cos(sigma));
    p.apex = -g.mean_cone_distance * std::cos(g.pinion_cone_angle) * Vector3::UnitZ();
    for (int s : {1, -1}) {
      p.drive_sign = s;
      const BevelMeshFrame b = CalcBevelMeshFrame(g, p);
      ASSERT_LE(b.frame.pinion_center.norm(), 1e-12);
      MeshPlacement spur;
      spur.pinion_center = b.frame.pinion_center;
      spur.pinion_base_radius = g.pinion_mean_pitch_radius * std::cos(g.spec.pressure_angle);
      spur.gear_base_radius = g.gear_mean_pitch_radius * std::cos(g.spec.pressure_angle);
      spur.operating_pressure_angle = g.spec.pressure_angle;
      spur.drive_sign = s;
      spur.gear_center = spur.pinion_center +
                         (g.pinion_mean_pitch_radius + g.gear_mean_pitch_radius) * Vector3::UnitX();
      const MeshFrame f = CalcMeshFrame(spur);
      const Matrix2x12 G_bevel = CalcMeshJacobian(b.frame), G_spur = CalcMeshJacobian(f);
      const double error = (G_bevel - G_spur).cwiseAbs().maxCoeff() / G_spur.cwiseAbs().maxCoeff();
      EXPECT_LE(error, 2.0 * sigma) << "Σ = " << sigma << ", s = " << s;
      EXPECT_LE((b.frame.eta - f.eta).norm(), 2.0 * sigma);
      if (s == 1) {
        EXPECT_LT(error, previous / 5.0) << "Σ = " << sigma;  // first order
        previous = error;
      }
    }
  }
}

TEST(BevelMeshFrameLimitTest, BadPlacementsAreRefusedAtTheirField) {
  const BevelPairGeometry g = CalcBevelPairGeometry(Spec(90.0));
  BevelPlacement p;
  p.pinion_axis = Vector3(0.0, 0.0, 2.0);
  EXPECT_THROWS_MESSAGE(CalcBevelMeshFrame(g, p), InvalidInput, "^pinion_axis: must be a unit");
  p = BevelPlacement();
  p.gear_axis = Vector3(1.0, 0.0, 1.0).normalized();
  EXPECT_THROWS_MESSAGE(CalcBevelMeshFrame(g, p), InvalidInput,
                        "^gear_axis: the axes make 45 deg, the pair's shaft angle is 90 deg");
  p = BevelPlacement();
  p.gear_axis = Vector3(std::nan(""), 0.0, 0.0);
  EXPECT_THROWS_MESSAGE(CalcBevelMeshFrame(g, p), InvalidInput, "^gear_axis: must be finite");
  p = BevelPlacement();
  p.drive_sign = 0;
  EXPECT_THROWS_MESSAGE(CalcBevelMeshFrame(g, p), InvalidInput, "^drive_sign");
}

}  // namespace
}  // namespace geardyn
