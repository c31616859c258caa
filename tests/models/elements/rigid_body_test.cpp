// Tests of the rigid-body mass matrix (rigid_body.hpp): kinetic energies of translations and
// rotations about the reference node against the parallel-axis theorem, the coupling terms
// of an offset centre of mass against the velocity of the centre of mass, and error paths.
#include "geardyn/models/elements/rigid_body.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kAlgebraTol = 100 * kEps;

// A planet carrier: heavy, with its centre of mass off the reference node and a tilted axis.
RigidBodyInertia OffsetCarrier() {
  return RigidBodyInertia{.mass = 12.5,
                          .polar_inertia = 0.21,
                          .diametral_inertia = 0.13,
                          .axis = Vector3(0.1, -0.2, 0.97).normalized(),
                          .com_offset = Vector3(0.012, -0.031, 0.045)};
}

double KineticEnergy(const Matrix6& M, const Vector3& v, const Vector3& w) {
  Vector6 q_dot;
  q_dot << v, w;
  return 0.5 * q_dot.dot(M * q_dot);
}

TEST(RigidBodyTest, CentredBodyIsDiagonalInItsAxes) {
  const RigidBodyInertia gear{.mass = 3.2, .polar_inertia = 0.011, .diametral_inertia = 0.006};
  Vector6 diag;
  diag << 3.2, 3.2, 3.2, 0.006, 0.006, 0.011;
  EXPECT_MATRIX_NEAR(CalcRigidBodyMassMatrix(gear), Matrix6(diag.asDiagonal()), kAlgebraTol);
}

TEST(RigidBodyTest, AxisymmetricTensorHasJAlongTheAxisAndIdAcross) {
  const RigidBodyInertia body = OffsetCarrier();
  const Matrix3 I_g = CalcAxisymmetricInertiaTensor(body);
  const Vector3 a = body.axis;
  const Vector3 n = a.cross(Vector3(1, 2, 3)).normalized();  // any diameter
  EXPECT_NEAR(a.dot(I_g * a), body.polar_inertia, 1e-15);
  EXPECT_NEAR(n.dot(I_g * n), body.diametral_inertia, 1e-15);
  EXPECT_NEAR(n.dot(I_g * a), 0.0, 1e-15);
}

TEST(RigidBodyTest, TranslationKineticEnergyIsHalfMV2) {
  const RigidBodyInertia body = OffsetCarrier();
  const Matrix6 M = CalcRigidBodyMassMatrix(body);
  const Vector3 v(0.3, -1.7, 0.9);
  EXPECT_NEAR(KineticEnergy(M, v, Vector3::Zero()), 0.5 * body.mass * v.squaredNorm(),
              kAlgebraTol * body.mass * v.squaredNorm());
}

TEST(RigidBodyTest, RotationAboutReferenceNodeUsesParallelAxisTheorem) {
  // T = ½ ωᵀ (I_G + m(|r|² I − r rᵀ)) ω for a rotation about the reference node.
  const RigidBodyInertia body = OffsetCarrier();
  const Matrix6 M = CalcRigidBodyMassMatrix(body);
  const Vector3& r = body.com_offset;
  const Matrix3 I_ref = CalcAxisymmetricInertiaTensor(body) +
                        body.mass * (r.squaredNorm() * Matrix3::Identity() - r * r.transpose());
  for (const Vector3& w :
       {Vector3(1, 0, 0), Vector3(0, 1, 0), Vector3(0, 0, 1), Vector3(0.4, -2.2, 1.3)}) {
    const double expected = 0.5 * w.dot(I_ref * w);
    EXPECT_NEAR(KineticEnergy(M, Vector3::Zero(), w), expected, kAlgebraTol * expected);
  }
  EXPECT_MATRIX_NEAR((M.bottomRightCorner<3, 3>().eval()), I_ref, kAlgebraTol);
}

TEST(RigidBodyTest, CouplingTermsFollowFromTheVelocityOfTheCentreOfMass) {
  // König: T = ½ m |v + ω × r|² + ½ ωᵀ I_G ω for any (v, ω).
  const RigidBodyInertia body = OffsetCarrier();
  const Matrix6 M = CalcRigidBodyMassMatrix(body);
  const Matrix3 I_g = CalcAxisymmetricInertiaTensor(body);
  const std::vector<std::pair<Vector3, Vector3>> motions = {
      {Vector3(1, 0, 0), Vector3(0, 0, 1)},
      {Vector3(0.2, 0.5, -0.3), Vector3(-1.1, 0.4, 0.8)},
      {Vector3(-2, 1, 0.5), Vector3(0.3, 0.3, -0.3)}};
  for (const auto& [v, w] : motions) {
    const Vector3 v_g = v + w.cross(body.com_offset);
    const double expected = 0.5 * body.mass * v_g.squaredNorm() + 0.5 * w.dot(I_g * w);
    EXPECT_NEAR(KineticEnergy(M, v, w), expected, kAlgebraTol * (1.0 + expected));
  }
  // A rotation about the centre of mass (reference node moving with ω × (c − G) = −ω × r)
  // carries only the central inertia.
  const Vector3 w(0.7, -0.2, 0.4);
  EXPECT_NEAR(KineticEnergy(M, -w.cross(body.com_offset), w), 0.5 * w.dot(I_g * w), kAlgebraTol);
}

TEST(RigidBodyTest, MassMatrixIsSymmetricPositiveDefinite) {
  const Matrix6 M = CalcRigidBodyMassMatrix(OffsetCarrier());
  EXPECT_TRUE(M.isApprox(M.transpose(), 0.0));
  EXPECT_EQ(Eigen::LLT<Matrix6>(M).info(), Eigen::Success);
}

TEST(RigidBodyTest, GeneralTensorOverloadAgreesWithTheAxisymmetricOne) {
  const RigidBodyInertia body = OffsetCarrier();
  EXPECT_MATRIX_NEAR(
      CalcRigidBodyMassMatrix(body.mass, CalcAxisymmetricInertiaTensor(body), body.com_offset),
      CalcRigidBodyMassMatrix(body), kAlgebraTol);
}

TEST(RigidBodyTest, InvalidInputsThrowNamingTheArgument) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    std::function<void(RigidBodyInertia&)> mutate;
    std::string regex;
  };
  const std::vector<Case> cases = {
      {[](RigidBodyInertia& b) { b.mass = 0.0; }, "^mass: must be positive and finite, got 0 kg"},
      {[&](RigidBodyInertia& b) { b.mass = nan; }, "^mass: .* got nan kg"},
      {[](RigidBodyInertia& b) { b.polar_inertia = -0.1; },
       "^polar_inertia: must be positive and finite, got -0.1 kg\\*m\\^2"},
      {[](RigidBodyInertia& b) { b.diametral_inertia = 0.0; }, "^diametral_inertia: .* got 0"},
      {[](RigidBodyInertia& b) { b.axis = Vector3::Zero(); },
       "^axis: must be a unit vector, got \\(0, 0, 0\\) with norm 0"},
      {[](RigidBodyInertia& b) { b.axis = Vector3(1, 1, 0); }, "^axis: .* with norm 1.414"},
      {[&](RigidBodyInertia& b) { b.axis = Vector3(nan, 0, 1); }, "^axis: must be a unit vector"},
      {[&](RigidBodyInertia& b) { b.com_offset.y() = nan; },
       "^com_offset: must be finite, got \\(0.012, nan, 0.045\\) m"},
  };
  for (const Case& c : cases) {
    RigidBodyInertia body = OffsetCarrier();
    c.mutate(body);
    SCOPED_TRACE(c.regex);
    EXPECT_THROWS_MESSAGE(CalcRigidBodyMassMatrix(body), InvalidInput, c.regex);
  }
  EXPECT_THROWS_MESSAGE(CalcRigidBodyMassMatrix(1.0, -Matrix3::Identity(), Vector3::Zero()),
                        InvalidInput, "^inertia_at_com: must be positive definite");
  Matrix3 asymmetric = Matrix3::Identity();
  asymmetric(0, 1) = 0.1;
  EXPECT_THROWS_MESSAGE(CalcRigidBodyMassMatrix(1.0, asymmetric, Vector3::Zero()), InvalidInput,
                        "^inertia_at_com: must be symmetric");
}

}  // namespace
}  // namespace geardyn
