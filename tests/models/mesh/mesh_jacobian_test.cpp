// Tests of the mesh Jacobian G (spec 01 §3) and of B–S's scaled relative-displacement map
// (B–S Eq. 41d): G against finite differences of the exact large-motion approach computed
// geometrically, the meaning of its signs (approach = compression), rigid and conjugate motions,
// and the mapping to B–S's coordinates.
#include "geardyn/models/mesh/mesh_jacobian.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/stiffness_core.hpp"
#include "support/exact_approach.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"
#include "support/mesh_scenes.hpp"

namespace geardyn {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// G's entries are cross products of O(0.1 m) arms with unit vectors: a few roundings each.
constexpr double kAlgebraTol = 1e3 * kEps;
// Central differences with step kFdStep: truncation O(step² · arm) ≈ 1e-14, cancellation
// ≈ eps · |x| / step ≈ 1e-10 relative to G's largest entry.
constexpr double kFdStep = 1e-6;
constexpr double kFdTol = 1e-8;

// ---------------------------------------------------------------------------------------------
// Scenes: the shared mesh scenes (support/mesh_scenes.hpp) and one more.
using Scene = test::MeshScene;

std::vector<Scene> AllScenes() {
  std::vector<Scene> scenes = test::AllMeshScenes();
  // A mesh whose mid face is off the centres' plane (one half of a double-helical pair).
  MeshPlacement offset = test::MakeMeshPlacement(false, HelixHand::kRight, 1, true);
  offset.face_offset = 0.021;
  scenes.push_back({"external_rh_drive_pos_face_offset", offset});
  // A pinion on a rack (issue 19): the rack's reference point at the pitch point, a_i / cos φ
  // from the pinion axis (MeshPlacement::rack).
  for (HelixHand hand : {HelixHand::kNone, HelixHand::kRight}) {
    for (int s : {1, -1}) {
      MeshPlacement rack = test::MakeMeshPlacement(false, hand, s, true);
      rack.rack = true;
      rack.gear_base_radius = 0.0;
      rack.operating_pressure_angle = DegToRad(20.0);
      rack.gear_center = rack.pinion_center + rack.pinion_base_radius /
                                                  std::cos(rack.operating_pressure_angle) *
                                                  Vector3(std::cos(2.31), std::sin(2.31), 0.0);
      scenes.push_back({std::string("rack_") + (hand == HelixHand::kNone ? "spur" : "rh") +
                            (s > 0 ? "_drive_pos" : "_drive_neg"),
                        rack});
    }
  }
  return scenes;
}

// The conjugate (rolling) motion of the pair: the pinion turns by 1/a_i, the gear by ∓1/a_j,
// a rack translates with the pinion's pitch point.
Vector12 ConjugateMotion(const MeshPlacement& p, const MeshFrame& f) {
  Vector12 q = Vector12::Zero();
  q(5) = 1.0 / p.pinion_base_radius;
  if (p.rack) {
    q.segment<3>(6) = q(5) * Vector3::UnitZ().cross(f.reference_point - f.pinion_center);
  } else {
    q(11) = (p.internal ? 1.0 : -1.0) / p.gear_base_radius;
  }
  return q;
}

double ExactApproach(const MeshFrame& f, const Vector12& q, double sigma) {
  return test::ExactMaterialApproach(f, q, sigma);
}

// Common rigid rotation ω about the axis through point p: t = ω × (c − p), θ = ω for both.
Vector12 CommonRotation(const MeshFrame& f, const Vector3& omega, const Vector3& p) {
  Vector12 q;
  q << omega.cross(f.pinion_center - p), omega, omega.cross(f.gear_center - p), omega;
  return q;
}

class MeshJacobianSceneTest : public ::testing::TestWithParam<Scene> {};

TEST_P(MeshJacobianSceneTest, IsTheDerivativeOfTheExactApproachAlongTheContactLine) {
  const MeshFrame f = CalcMeshFrame(GetParam().placement);
  const Matrix2x12 G = CalcMeshJacobian(f);
  // A contact point at σ approaches by δ_η − σ δ_ζ (spec 01 §3): check σ = 0 and ±8 mm.
  for (double sigma : {0.0, 0.008, -0.008}) {
    Eigen::Matrix<double, 1, 12> fd;
    for (int k = 0; k < 12; ++k) {
      Vector12 dq = Vector12::Zero();
      dq(k) = kFdStep;
      fd(k) = (ExactApproach(f, dq, sigma) - ExactApproach(f, -dq, sigma)) / (2.0 * kFdStep);
    }
    const Eigen::Matrix<double, 1, 12> expected = G.row(0) - sigma * G.row(1);
    EXPECT_TRUE(test::CompareMatrices(fd, expected, kFdTol)) << "sigma = " << sigma;
  }
}

TEST_P(MeshJacobianSceneTest, PositiveNormalDeflectionIsApproach) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const Matrix2x12 G = CalcMeshJacobian(f);
  const double s = p.drive_sign;
  const double cos_psi = std::cos(p.base_helix_angle);
  // Pinion pushed along η into the gear: unit approach, no twist.
  Vector12 q = Vector12::Zero();
  q.segment<3>(0) = f.eta;
  EXPECT_MATRIX_NEAR(G * q, Vector2(1.0, 0.0), kAlgebraTol);
  // Pinion turned further in its drive direction: approach a_i cos ψ_b per radian.
  q.setZero();
  q(5) = s;
  EXPECT_NEAR((G * q)(0), p.pinion_base_radius * cos_psi, kAlgebraTol);
  // Gear turned further in its driven direction (against the pinion externally, with it
  // internally): separation.
  q.setZero();
  q(11) = p.internal ? s : -s;
  EXPECT_NEAR((G * q)(0), -p.gear_base_radius * cos_psi, kAlgebraTol);
  // Relative twist about ζ.
  q.setZero();
  q.segment<3>(3) = f.zeta;
  EXPECT_MATRIX_NEAR(G * q, Vector2(f.pinion_lever_arm.cross(f.eta).dot(f.zeta), 1.0), kAlgebraTol);
}

TEST_P(MeshJacobianSceneTest, RigidAndConjugateMotionsDeflectNothing) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const Matrix2x12 G = CalcMeshJacobian(f);
  const double scale = G.cwiseAbs().maxCoeff();
  const Vector3 t(0.3, -0.7, 0.2);
  Vector12 q;
  q << t, Vector3::Zero(), t, Vector3::Zero();
  EXPECT_LE((G * q).norm(), kAlgebraTol * scale * q.norm());
  for (const Vector3& omega :
       {Vector3(0.0, 0.0, 1.0), Vector3(1.0, 0.0, 0.0), Vector3(0.0, 1.0, 0.0),
        Vector3(0.3, -0.5, 0.8), Vector3(f.u), Vector3(f.v)}) {
    for (const Vector3& point : {Vector3(f.pinion_center), Vector3(f.gear_center),
                                 Vector3(f.reference_point), Vector3(0.4, 0.9, -0.6)}) {
      q = CommonRotation(f, omega, point);
      EXPECT_LE((G * q).norm(), kAlgebraTol * scale * q.norm())
          << "omega = " << omega.transpose() << ", point = " << point.transpose();
    }
  }
  // Conjugate rotation: a_i θ_iz = −a_j θ_jz (external), = +a_j θ_jz (internal); a rack moves
  // with the pinion's pitch point, θ_iz Z × (p0 − c_i).
  q = ConjugateMotion(p, f);
  EXPECT_LE((G * q).norm(), kAlgebraTol * scale * q.norm());
}

// B–S's K_o acts on δ_BS = T q (B–S Eq. 41d); [δ_η, δ_ζ] = P δ_BS with P from g's pattern.
// P T reproduces G exactly for spur gears with p0 in the centres' plane; for helical gears B–S's
// arm projection (B–S Eq. 25) drops the documented tilt terms about u.
TEST_P(MeshJacobianSceneTest, BsScaledCoordinatesReproduceGUpToTheDocumentedArmTerms) {
  const MeshFrame f = CalcMeshFrame(GetParam().placement);
  const double b = 0.012;
  const Matrix2x12 G = CalcMeshJacobian(f);
  const double psi = f.signed_helix_angle;
  const Matrix2x6 P = CalcBsDeflectionProjection(std::cos(psi), std::sin(psi), b);
  const Matrix6x12 T = CalcBsRelativeDisplacementMap(f, b);
  const Matrix2x12 G_bs = P * T;
  // The missing part: moments about u of the axial component (arm r·v) and of the transverse
  // component at an axial offset (arm r·w); see CalcBsRelativeDisplacementMap.
  const double s = f.drive_sign;
  const Vector3& r_i = f.pinion_lever_arm;
  const Vector3& r_j = f.gear_lever_arm;
  Matrix2x12 arm_terms = Matrix2x12::Zero();
  arm_terms.block<1, 3>(0, 3) =
      s * (std::sin(psi) * r_i.dot(f.v) - std::cos(psi) * r_i.dot(f.w)) * f.u.transpose();
  arm_terms.block<1, 3>(0, 9) =
      -s * (std::sin(psi) * r_j.dot(f.v) - std::cos(psi) * r_j.dot(f.w)) * f.u.transpose();
  EXPECT_MATRIX_NEAR(G_bs + arm_terms, G, kAlgebraTol);
  EXPECT_MATRIX_NEAR(G_bs.row(1), G.row(1), kAlgebraTol);  // the twist row is always exact
  const bool coplanar = std::abs(r_i.z()) + std::abs(r_j.z()) == 0.0;
  if (f.base_helix_angle == 0.0 && coplanar) {
    EXPECT_MATRIX_NEAR(G_bs, G, kAlgebraTol);
  } else {
    EXPECT_GT(arm_terms.norm(), 1e-3 * G.norm());  // a first-order effect, not rounding
  }
}

// CalcBsProjectedJacobian (model = "bs_projected") is G minus the θ_u arm terms (closed form
// from the frame's vectors), and loads a rigid motion only through them: common translations, the
// conjugate rotation and common rotations with u·ω = 0 deflect nothing; a common rotation about
// u gives −s (sin ψ C·v − cos ψ C·w) ω_u, C = c_j − c_i (derived in mesh_jacobian.hpp).
TEST_P(MeshJacobianSceneTest, BsProjectedJacobianLoadsOnlyTheDerivedRigidMotions) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const double b = 0.009;
  const Matrix2x12 G = CalcMeshJacobian(f);
  const Matrix2x12 G_bs = CalcBsProjectedJacobian(f, b);
  const double s = f.drive_sign;
  const double sin_psi = std::sin(f.signed_helix_angle);
  const double cos_psi = std::cos(f.signed_helix_angle);
  const auto arm = [&](const Vector3& r) { return sin_psi * r.dot(f.v) - cos_psi * r.dot(f.w); };
  Matrix2x12 expected = G;
  expected.block<1, 3>(0, 3) -= s * arm(f.pinion_lever_arm) * f.u.transpose();
  expected.block<1, 3>(0, 9) += s * arm(f.gear_lever_arm) * f.u.transpose();
  EXPECT_MATRIX_NEAR(G_bs, expected, kAlgebraTol);
  // b cancels in P T.
  EXPECT_MATRIX_NEAR(CalcBsProjectedJacobian(f, 0.1), G_bs, kAlgebraTol);

  const double scale = G.cwiseAbs().maxCoeff();
  const Vector3 t(0.3, -0.7, 0.2);
  Vector12 q;
  q << t, Vector3::Zero(), t, Vector3::Zero();
  EXPECT_LE((G_bs * q).norm(), kAlgebraTol * scale * q.norm());
  q = ConjugateMotion(p, f);
  EXPECT_LE((G_bs * q).norm(), kAlgebraTol * scale * q.norm());
  const Vector3 C = f.gear_center - f.pinion_center;
  const double u_load = -s * (sin_psi * C.dot(f.v) - cos_psi * C.dot(f.w));
  for (const Vector3& omega : {Vector3(0.0, 0.0, 1.0), Vector3(f.v), Vector3(f.v - 0.4 * f.w),
                               Vector3(f.u), Vector3(0.3, -0.5, 0.8)}) {
    for (const Vector3& point :
         {Vector3(f.pinion_center), Vector3(f.reference_point), Vector3(0.4, 0.9, -0.6)}) {
      q = CommonRotation(f, omega, point);
      EXPECT_NEAR((G_bs * q)(0), u_load * f.u.dot(omega), kAlgebraTol * scale * q.norm())
          << "omega = " << omega.transpose() << ", point = " << point.transpose();
      EXPECT_NEAR((G_bs * q)(1), 0.0, kAlgebraTol * scale * q.norm());
    }
  }
  if (f.base_helix_angle != 0.0) {
    EXPECT_GT(std::abs(u_load), 1e-3 * C.norm());  // a helical pair's tilt about u is loaded
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, MeshJacobianSceneTest, ::testing::ValuesIn(AllScenes()),
                         [](const ::testing::TestParamInfo<Scene>& param_info) {
                           return param_info.param.name;
                         });

TEST(MeshJacobianTest, HasTheSpecLayout) {
  const MeshFrame f = CalcMeshFrame(test::MakeMeshPlacement(false, HelixHand::kLeft, -1, true));
  const Matrix2x12 G = CalcMeshJacobian(f);
  EXPECT_MATRIX_NEAR((G.block<1, 3>(0, 0).transpose()), f.eta, 0.0);
  EXPECT_MATRIX_NEAR((G.block<1, 3>(0, 6).transpose()), -f.eta, 0.0);
  EXPECT_MATRIX_NEAR((G.block<1, 3>(1, 0)), Eigen::RowVector3d::Zero(), 0.0);
  EXPECT_MATRIX_NEAR((G.block<1, 3>(1, 6)), Eigen::RowVector3d::Zero(), 0.0);
  EXPECT_MATRIX_NEAR((G.block<1, 3>(1, 3).transpose()), f.zeta, 0.0);
  EXPECT_MATRIX_NEAR((G.block<1, 3>(1, 9).transpose()), -f.zeta, 0.0);
}

TEST(MeshJacobianTest, BsMapRejectsBadHalfFaceWidth) {
  const MeshFrame f = CalcMeshFrame(test::MakeMeshPlacement(false, HelixHand::kNone, 1, false));
  EXPECT_THROWS_MESSAGE(CalcBsRelativeDisplacementMap(f, 0.0), InvalidInput,
                        "half_face_width: must be positive");
  EXPECT_THROWS_MESSAGE(CalcBsRelativeDisplacementMap(f, std::numeric_limits<double>::quiet_NaN()),
                        InvalidInput, "half_face_width");
}

}  // namespace
}  // namespace geardyn
