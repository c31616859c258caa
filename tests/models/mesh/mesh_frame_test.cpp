// Tests of the Blankenship–Singh mesh frame (spec 01 §2): geometry of the plane of action for
// external and internal pairs, the drive and helix-hand conventions (checked against the base
// helices, independently of the formulas in mesh_frame.cpp), covariance under rigid
// re-placement, rotation by π about X (= reversed drive) and mirroring (= flipped hand), and
// the input checks.
#include "geardyn/models/mesh/mesh_frame.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"
#include "support/mesh_scenes.hpp"

namespace geardyn {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Frame vectors are a few trigonometric evaluations and products of O(1) numbers.
constexpr double kUnitTol = 64.0 * kEps;
// Points and distances: O(0.1 m) coordinates with O(10) roundings; relative to 1 m.
constexpr double kLengthTol = 1e3 * kEps;

// ---------------------------------------------------------------------------------------------
// Scenes: the shared mesh scenes (support/mesh_scenes.hpp).
using Scene = test::MeshScene;

int HandSign(HelixHand hand) {
  return hand == HelixHand::kRight ? 1 : (hand == HelixHand::kLeft ? -1 : 0);
}

// Transverse projection.
Vector3 Xy(const Vector3& x) { return Vector3(x.x(), x.y(), 0.0); }

// Unit tangent of the base helix of a gear (centre c, base radius a, hand sign h: +1 right-hand,
// i.e. angle increasing with z) at the point of its base cylinder whose radial direction is
// `radial`. Parametrisation: P(z) = c + a (cos(θ0 + k z), sin(θ0 + k z), 0) + z Z, k = h tan ψ_b /
// a.
Vector3 BaseHelixTangent(double a, int h, double psi_b, const Vector3& radial) {
  const double theta0 = std::atan2(radial.y(), radial.x());
  const double k = h * std::tan(psi_b) / a;
  return (a * k * Vector3(-std::sin(theta0), std::cos(theta0), 0.0) + Vector3::UnitZ())
      .normalized();
}

class MeshFrameSceneTest : public ::testing::TestWithParam<Scene> {};

TEST_P(MeshFrameSceneTest, FramesAreOrthonormalAndDetWIsTheDriveSign) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const Matrix3 W = CalcDirectionalMatrix(f);
  EXPECT_MATRIX_NEAR(W.transpose() * W, Matrix3::Identity(), kUnitTol);
  EXPECT_NEAR(W.determinant(), p.drive_sign, kUnitTol);
  EXPECT_MATRIX_NEAR(f.w, Vector3::UnitZ(), 0.0);
  Matrix3 H;
  H << f.zeta, f.eta, f.sigma;
  EXPECT_MATRIX_NEAR(H.transpose() * H, Matrix3::Identity(), kUnitTol);
  EXPECT_NEAR(H.determinant(), 1.0, kUnitTol);  // (ζ, η, σ) right-handed for both drives
  EXPECT_MATRIX_NEAR(f.zeta, f.u, 0.0);
  // η is (u, v, w) rotated about u by the signed helix angle ψ = −s h ψ_b.
  const double psi = -p.drive_sign * HandSign(p.pinion_hand) * p.base_helix_angle;
  EXPECT_NEAR(f.signed_helix_angle, psi, kUnitTol);
  EXPECT_MATRIX_NEAR(f.eta, std::cos(psi) * f.v + std::sin(psi) * f.w, kUnitTol);
}

TEST_P(MeshFrameSceneTest, PlaneOfActionTouchesBothBaseCircles) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const double a_i = p.pinion_base_radius;
  const double a_j = p.gear_base_radius;
  // Pinion: tangent at c_i + a_i u. Gear: opposite side (external) or SAME side (internal).
  EXPECT_NEAR(f.u.dot(f.reference_point - p.pinion_center), a_i, kLengthTol);
  EXPECT_NEAR(f.u.dot(f.reference_point - p.gear_center), p.internal ? a_j : -a_j, kLengthTol);
  // The tangent points and p0 lie on one line along v in the transverse plane.
  const Vector3 t_i = Xy(p.pinion_center) + a_i * f.u;
  const Vector3 t_j = Xy(p.gear_center) + (p.internal ? a_j : -a_j) * f.u;
  EXPECT_NEAR(std::abs(f.v.dot((t_j - t_i).normalized())), 1.0, kUnitTol);
  // p0 is the operating pitch point: on the line of centres at r_w = a / cos φ from each centre.
  const double cos_phi = std::cos(p.operating_pressure_angle);
  EXPECT_NEAR(Xy(f.reference_point - p.pinion_center).norm(), a_i / cos_phi, kLengthTol);
  EXPECT_NEAR(Xy(f.reference_point - p.gear_center).norm(), a_j / cos_phi, kLengthTol);
  const double along =
      Xy(f.reference_point - p.pinion_center).dot(Xy(f.reference_point - p.gear_center));
  if (p.internal) {
    EXPECT_GT(along, 0.0);  // beyond the pinion, on the side away from the ring's centre
    EXPECT_NEAR(f.center_distance, (a_j - a_i) / cos_phi, kLengthTol);
  } else {
    EXPECT_LT(along, 0.0);  // between the centres
    EXPECT_NEAR(f.center_distance, (a_i + a_j) / cos_phi, kLengthTol);
  }
  EXPECT_NEAR(f.reference_point.z(), 0.5 * (p.pinion_center.z() + p.gear_center.z()), kLengthTol);
  EXPECT_MATRIX_NEAR(f.pinion_lever_arm, f.reference_point - p.pinion_center, 0.0);
  EXPECT_MATRIX_NEAR(f.gear_lever_arm, f.reference_point - p.gear_center, 0.0);
}

TEST_P(MeshFrameSceneTest, MeshForceSeparatesTheGearsAndOpposesTheDrive) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const double s = p.drive_sign;
  const double cos_psi = std::cos(p.base_helix_angle);
  // Radial part of the force F v on the driven gear: away from the pinion (external), outwards
  // for the ring, i.e. towards the side of the pinion seen from the ring's centre (internal).
  const Vector3 outwards = p.internal ? Xy(p.pinion_center - p.gear_center).normalized()
                                      : Xy(p.gear_center - p.pinion_center).normalized();
  EXPECT_NEAR(f.v.dot(outwards), std::sin(p.operating_pressure_angle), kUnitTol);
  // Torques about the own centres of F η on the gear and −F η on the pinion (F = 1 N).
  const double torque_pinion = f.pinion_lever_arm.cross(-f.eta).z();
  const double torque_gear = f.gear_lever_arm.cross(f.eta).z();
  EXPECT_NEAR(torque_pinion, -s * p.pinion_base_radius * cos_psi, kLengthTol);  // opposes drive
  // External: the gear turns against the pinion; internal: the ring turns with it.
  EXPECT_NEAR(torque_gear, (p.internal ? s : -s) * p.gear_base_radius * cos_psi, kLengthTol);
}

TEST_P(MeshFrameSceneTest, ToothNormalIsPerpendicularToBothBaseHelices) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const int h_i = HandSign(p.pinion_hand);
  const int h_j = p.internal ? h_i : -h_i;  // an external mate has the opposite hand
  const Vector3 radial_i = f.u;
  const Vector3 radial_j = p.internal ? f.u : Vector3(-f.u);
  const Vector3 tangent_i =
      BaseHelixTangent(p.pinion_base_radius, h_i, p.base_helix_angle, radial_i);
  const Vector3 tangent_j = BaseHelixTangent(p.gear_base_radius, h_j, p.base_helix_angle, radial_j);
  // Contact lines are the generators of both involute helicoids: along σ, normal to η.
  EXPECT_NEAR(f.eta.dot(tangent_i), 0.0, kUnitTol);
  EXPECT_NEAR(f.eta.dot(tangent_j), 0.0, kUnitTol);
  EXPECT_NEAR(f.sigma.cross(tangent_i).norm(), 0.0, kUnitTol);
  EXPECT_NEAR(f.sigma.cross(tangent_j).norm(), 0.0, kUnitTol);
  EXPECT_GT(f.eta.dot(f.v), 0.0);              // η carries the transverse force
  EXPECT_NEAR(f.eta.dot(f.u), 0.0, kUnitTol);  // η lies in the plane of action
}

TEST_P(MeshFrameSceneTest, ReversingTheTorqueOrTheHandFlipsTheAxialForce) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  MeshPlacement reversed = p;
  reversed.drive_sign = -p.drive_sign;
  MeshPlacement mirrored_hand = p;
  mirrored_hand.pinion_hand = p.pinion_hand == HelixHand::kRight  ? HelixHand::kLeft
                              : p.pinion_hand == HelixHand::kLeft ? HelixHand::kRight
                                                                  : HelixHand::kNone;
  // Axial component of the unit mesh force on the driven gear: −s h sin ψ_b.
  const double axial = f.eta.z();
  EXPECT_NEAR(axial, -p.drive_sign * HandSign(p.pinion_hand) * std::sin(p.base_helix_angle),
              kUnitTol);
  EXPECT_NEAR(CalcMeshFrame(reversed).eta.z(), -axial, kUnitTol);
  EXPECT_NEAR(CalcMeshFrame(mirrored_hand).eta.z(), -axial, kUnitTol);
  // The transverse part follows the drive only: v flips its tangential component.
  EXPECT_NEAR(CalcMeshFrame(mirrored_hand).v.dot(f.v), 1.0, kUnitTol);
}

// Rotation about Z by any angle about any point plus any translation moves every vector with R.
TEST_P(MeshFrameSceneTest, RigidReplacementAboutZTransformsTheFrame) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const Matrix3 R = Eigen::AngleAxisd(1.234, Vector3::UnitZ()).toRotationMatrix();
  const Vector3 shift(0.5, -0.3, 0.2);
  MeshPlacement q = p;
  q.pinion_center = R * p.pinion_center + shift;
  q.gear_center = R * p.gear_center + shift;
  const MeshFrame g = CalcMeshFrame(q);
  EXPECT_MATRIX_NEAR(g.u, R * f.u, kUnitTol);
  EXPECT_MATRIX_NEAR(g.v, R * f.v, kUnitTol);
  EXPECT_MATRIX_NEAR(g.eta, R * f.eta, kUnitTol);
  EXPECT_MATRIX_NEAR(g.sigma, R * f.sigma, kUnitTol);
  EXPECT_MATRIX_NEAR(g.reference_point, R * f.reference_point + shift, kLengthTol);
}

// Turning the whole scene over (rotation by π about X) is the same physical mesh seen with the
// axis reversed: the torque about the new +Z changes sign, the hands do not (a helix's hand is
// intrinsic). Every polar vector must follow the rotation — this pins the hand convention.
TEST_P(MeshFrameSceneTest, TurningTheSceneOverIsAReversedDriveWithTheSameHand) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const Matrix3 R = Vector3(1.0, -1.0, -1.0).asDiagonal();
  MeshPlacement q = p;
  q.pinion_center = R * p.pinion_center;
  q.gear_center = R * p.gear_center;
  q.drive_sign = -p.drive_sign;
  const MeshFrame g = CalcMeshFrame(q);
  EXPECT_MATRIX_NEAR(g.u, R * f.u, kUnitTol);
  EXPECT_MATRIX_NEAR(g.v, R * f.v, kUnitTol);
  EXPECT_MATRIX_NEAR(g.eta, R * f.eta, kUnitTol);
  EXPECT_MATRIX_NEAR(g.zeta, R * f.zeta, kUnitTol);
  EXPECT_MATRIX_NEAR(g.sigma, R * f.sigma, kUnitTol);
  EXPECT_MATRIX_NEAR(g.reference_point, R * f.reference_point, kLengthTol);
}

// The mirror image (z → −z) of a right-hand gear is a left-hand gear; the torque about Z (an
// axial vector) keeps its sign. Polar vectors follow the mirror; σ = ζ × η flips (axial).
TEST_P(MeshFrameSceneTest, MirroringTheSceneFlipsTheHand) {
  const MeshPlacement& p = GetParam().placement;
  const MeshFrame f = CalcMeshFrame(p);
  const Matrix3 M = Vector3(1.0, 1.0, -1.0).asDiagonal();
  MeshPlacement q = p;
  q.pinion_center = M * p.pinion_center;
  q.gear_center = M * p.gear_center;
  q.pinion_hand = p.pinion_hand == HelixHand::kRight  ? HelixHand::kLeft
                  : p.pinion_hand == HelixHand::kLeft ? HelixHand::kRight
                                                      : HelixHand::kNone;
  const MeshFrame g = CalcMeshFrame(q);
  EXPECT_MATRIX_NEAR(g.u, M * f.u, kUnitTol);
  EXPECT_MATRIX_NEAR(g.v, M * f.v, kUnitTol);
  EXPECT_MATRIX_NEAR(g.eta, M * f.eta, kUnitTol);
  EXPECT_MATRIX_NEAR(g.sigma, -(M * f.sigma), kUnitTol);
  EXPECT_MATRIX_NEAR(g.reference_point, M * f.reference_point, kLengthTol);
}

INSTANTIATE_TEST_SUITE_P(Scenes, MeshFrameSceneTest, ::testing::ValuesIn(test::AllMeshScenes()),
                         [](const ::testing::TestParamInfo<Scene>& param_info) {
                           return param_info.param.name;
                         });

TEST(MeshFrameTest, RightHandPinionWithPositiveDrivePushesTheGearTowardsMinusZ) {
  // The convention stated in mesh_frame.hpp, as a worm: a right-hand screw turned positively
  // about +Z is pushed towards +Z by the nut it drives, and pushes the nut towards −Z.
  const MeshFrame f = CalcMeshFrame(test::MakeMeshPlacement(false, HelixHand::kRight, 1, false));
  EXPECT_LT(f.eta.z(), 0.0);  // force on the driven gear
  EXPECT_NEAR(f.eta.z(), -std::sin(f.base_helix_angle), kUnitTol);
}

TEST(MeshFrameTest, PinionAtOriginGearOnPlusXHasTheTextbookFrame) {
  // External spur pair, positive drive: ê = X, ê⊥ = Y, u = (cos φ, −sin φ), v = (sin φ, cos φ).
  const MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kNone, 1, false);
  const MeshFrame f = CalcMeshFrame(p);
  const double phi = p.operating_pressure_angle;
  EXPECT_MATRIX_NEAR(f.u, Vector3(std::cos(phi), -std::sin(phi), 0.0), kUnitTol);
  EXPECT_MATRIX_NEAR(f.v, Vector3(std::sin(phi), std::cos(phi), 0.0), kUnitTol);
  EXPECT_MATRIX_NEAR(f.eta, f.v, kUnitTol);
  EXPECT_MATRIX_NEAR(f.sigma, Vector3::UnitZ(), kUnitTol);
  EXPECT_MATRIX_NEAR(f.reference_point, Vector3(p.pinion_base_radius / std::cos(phi), 0.0, 0.0),
                     kLengthTol);
}

TEST(MeshFrameTest, FaceOffsetMovesTheReferencePointAxially) {
  MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, true);
  const MeshFrame f0 = CalcMeshFrame(p);
  p.face_offset = 0.025;
  const MeshFrame f1 = CalcMeshFrame(p);
  EXPECT_MATRIX_NEAR(f1.reference_point, f0.reference_point + 0.025 * Vector3::UnitZ(), kLengthTol);
  EXPECT_MATRIX_NEAR(f1.eta, f0.eta, 0.0);
}

GearPairGeometry MakeGeometry(bool internal, HelixHand hand) {
  GearPairGeometry g;
  g.internal = internal;
  g.pinion.base_radius = internal ? 0.031 : 0.042;
  g.gear.base_radius = internal ? 0.094 : 0.071;
  g.operating_pressure_angle = DegToRad(internal ? 21.3 : 23.1);
  g.base_helix_angle = hand == HelixHand::kNone ? 0.0 : DegToRad(internal ? 14.2 : 18.7);
  g.pinion.hand = hand;
  g.spec.pinion_hand = hand;
  return g;
}

TEST(MeshFrameTest, GeometryOverloadPlacesTheGearOnTheLineOfCentres) {
  for (bool internal : {false, true}) {
    for (int s : {1, -1}) {
      const GearPairGeometry geometry = MakeGeometry(internal, HelixHand::kLeft);
      const Vector3 c_i(0.13, -0.21, 0.07);
      const double gamma = 2.31;
      const MeshFrame f = CalcMeshFrame(geometry, c_i, gamma, s);
      const MeshFrame expected =
          CalcMeshFrame(test::MakeMeshPlacement(internal, HelixHand::kLeft, s, true));
      const double a_i = geometry.pinion.base_radius;
      const double a_j = geometry.gear.base_radius;
      const double C =
          (internal ? a_j - a_i : a_i + a_j) / std::cos(geometry.operating_pressure_angle);
      EXPECT_MATRIX_NEAR(f.gear_center, c_i + C * Vector3(std::cos(gamma), std::sin(gamma), 0.0),
                         kLengthTol);
      EXPECT_MATRIX_NEAR(f.eta, expected.eta, kUnitTol);
      EXPECT_MATRIX_NEAR(f.u, expected.u, kUnitTol);
      EXPECT_MATRIX_NEAR(f.reference_point, expected.reference_point, kLengthTol);
      EXPECT_EQ(f.internal, internal);
      EXPECT_EQ(f.drive_sign, s);
    }
  }
}

TEST(MeshFrameTest, GeometryOverloadFallsBackToTheSpecHand) {
  GearPairGeometry geometry = MakeGeometry(false, HelixHand::kRight);
  geometry.pinion.hand = HelixHand::kNone;
  const MeshFrame f = CalcMeshFrame(geometry, Vector3::Zero(), 0.0, 1);
  EXPECT_LT(f.eta.z(), 0.0);  // right hand, positive drive
}

// ---------------------------------------------------------------------------------------------
// Bad input: InvalidInput naming the argument.
TEST(MeshFrameTest, RejectsBadBaseRadii) {
  MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kNone, 1, false);
  p.pinion_base_radius = 0.0;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "pinion_base_radius: must be positive");
  p.pinion_base_radius = -0.04;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "pinion_base_radius");
  p = test::MakeMeshPlacement(false, HelixHand::kNone, 1, false);
  p.gear_base_radius = -1.0;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "gear_base_radius: must be positive");
  p = test::MakeMeshPlacement(true, HelixHand::kNone, 1, false);
  p.gear_base_radius = 0.02;  // ring smaller than its pinion
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "gear_base_radius: an internal gear");
}

TEST(MeshFrameTest, RejectsCoincidentOrTooCloseCentres) {
  MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kNone, 1, true);
  p.gear_center = p.pinion_center + Vector3(0.0, 0.0, 0.3);  // same axis
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput,
                        "gear_center: coincides with pinion_center");
  p.gear_center = p.pinion_center + Vector3(0.1, 0.0, 0.0);  // < a_i + a_j = 0.113
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "gear_center: centre distance .* overlap");
  p = test::MakeMeshPlacement(true, HelixHand::kNone, 1, false);
  p.gear_center = p.pinion_center + Vector3(0.05, 0.0, 0.0);  // < a_j − a_i = 0.063
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "gear_center: centre distance");
}

TEST(MeshFrameTest, RejectsCentresInconsistentWithThePressureAngle) {
  MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kNone, 1, false);
  p.gear_center *= 1.01;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput,
                        "operating_pressure_angle: .* does not match");
}

TEST(MeshFrameTest, RejectsNonFiniteValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.pinion_center.y() = nan;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "pinion_center: must be finite");
  p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.gear_center.x() = inf;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "gear_center: must be finite");
  p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.gear_base_radius = inf;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "gear_base_radius");
  p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.operating_pressure_angle = nan;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "operating_pressure_angle");
  p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.base_helix_angle = nan;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "base_helix_angle");
  p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.face_offset = nan;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "face_offset");
  EXPECT_THROWS_MESSAGE(
      CalcMeshFrame(MakeGeometry(false, HelixHand::kNone), Vector3::Zero(), nan, 1), InvalidInput,
      "line_of_centres_angle");
  GearPairGeometry g = MakeGeometry(false, HelixHand::kNone);
  g.operating_pressure_angle = nan;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(g, Vector3::Zero(), 0.0, 1), InvalidInput,
                        "operating_pressure_angle");
}

TEST(MeshFrameTest, RejectsBadAnglesHandAndDriveSign) {
  MeshPlacement p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.drive_sign = 0;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "drive_sign: must be \\+1 or -1, got 0");
  p.drive_sign = 2;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "drive_sign: .* got 2");
  p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.base_helix_angle = -0.1;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "base_helix_angle: must lie in");
  p = test::MakeMeshPlacement(false, HelixHand::kRight, 1, false);
  p.pinion_hand = HelixHand::kNone;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "pinion_hand: kNone");
  p = test::MakeMeshPlacement(false, HelixHand::kNone, 1, false);
  p.operating_pressure_angle = 0.0;
  EXPECT_THROWS_MESSAGE(CalcMeshFrame(p), InvalidInput, "operating_pressure_angle: must lie in");
  EXPECT_THROWS_MESSAGE(
      CalcMeshFrame(MakeGeometry(false, HelixHand::kNone), Vector3::Zero(), 0.0, -2), InvalidInput,
      "drive_sign");
}

}  // namespace
}  // namespace geardyn
