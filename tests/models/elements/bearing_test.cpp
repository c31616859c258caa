// Tests of bearings (bearing.hpp) and of the rigid-transfer map they use (rigid_transfer.hpp):
// zero force for any common rigid motion of the two bodies, the force and moment of a pure
// translation, a planet on its carrier pin, agreement of the grounded and two-body forms, the
// special coefficient matrices, and error paths.
#include "geardyn/models/elements/bearing.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/elements/rigid_transfer.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// K entries ~ k_b · |r|²: relative products of a few roundings.
constexpr double kAlgebraTol = 1e3 * kEps;

const Vector3 kCenterA(0.05, -0.12, 0.03);   // e.g. a planet
const Vector3 kCenterB(-0.02, 0.04, -0.01);  // e.g. its carrier
const Vector3 kPoint(0.061, -0.108, 0.055);  // the pin / bearing centre

// A full, coupled, symmetric positive-definite K_b with realistic magnitudes: a rotated
// axisymmetric bearing plus translation/tilt coupling terms.
Matrix6 FullBearing() {
  const Vector3 axis = Vector3(0.2, 0.1, 1.0).normalized();
  Matrix6 K = CalcAxisymmetricBearingMatrix(4e8, 1e8, 2e5, 1e3, axis);
  Matrix6 coupling = Matrix6::Zero();  // radial force ↔ tilt moment, |k_c| ≪ √(k_r k_tilt)
  coupling(0, 4) = 1e6;
  coupling(1, 3) = -1e6;
  K += coupling + coupling.transpose();
  return K;
}

Vector12 CommonRigidMotion(const Vector3& t, const Vector3& theta, const Vector3& about) {
  Vector12 q;
  q << t + theta.cross(kCenterA - about), theta, t + theta.cross(kCenterB - about), theta;
  return q;
}

TEST(RigidTransferTest, MapsTheMotionOfTheMaterialPoint) {
  const Vector3 t(1e-4, -2e-4, 3e-5), theta(2e-3, -1e-3, 4e-3);
  Vector6 q;
  q << t, theta;
  const Vector6 u = CalcRigidTransferMap(kPoint, kCenterA) * q;
  EXPECT_MATRIX_NEAR(u.head<3>(), (t + theta.cross(kPoint - kCenterA)).eval(), kAlgebraTol);
  EXPECT_MATRIX_NEAR(u.tail<3>(), theta, 0.0);
  // And it agrees with the exact large-rotation motion to second order in θ.
  const Vector3 exact = t +
                        Eigen::AngleAxisd(theta.norm(), theta.normalized()) * (kPoint - kCenterA) -
                        (kPoint - kCenterA);
  EXPECT_LT((u.head<3>() - exact).norm(), theta.squaredNorm() * (kPoint - kCenterA).norm());
  EXPECT_MATRIX_NEAR(CalcCrossProductMatrix(theta) * t, theta.cross(t), kAlgebraTol);
}

TEST(BearingTest, CommonRigidMotionOfBothBodiesProducesNoForce) {
  ASSERT_GT(Eigen::SelfAdjointEigenSolver<Matrix6>(FullBearing()).eigenvalues().minCoeff(), 0.0);
  const Matrix12 K = CalcBearingMatrix(FullBearing(), kPoint, kCenterA, kCenterB);
  for (const Vector3& about : {Vector3(Vector3::Zero()), kPoint, Vector3(0.7, -0.3, 1.1)}) {
    for (int k = 0; k < 6; ++k) {
      const Vector3 t = k < 3 ? Vector3(Vector3::Unit(k)) : Vector3(Vector3::Zero());
      const Vector3 theta = k < 3 ? Vector3(Vector3::Zero()) : Vector3(Vector3::Unit(k - 3));
      const Vector12 q = CommonRigidMotion(t, theta, about);
      EXPECT_LT((K * q).norm(), kAlgebraTol * K.norm() * q.norm()) << "motion " << k;
    }
  }
  // Hence K is PSD of rank 6 (K_b is definite) with the rigid motions as its null space.
  const Eigen::SelfAdjointEigenSolver<Matrix12> eig(K, Eigen::EigenvaluesOnly);
  const double largest = eig.eigenvalues().maxCoeff();
  EXPECT_GT(eig.eigenvalues().minCoeff(), -kAlgebraTol * largest);
  EXPECT_EQ((eig.eigenvalues().array() > 1e-12 * largest).count(), 6);
  EXPECT_TRUE(K.isApprox(K.transpose(), 0.0));
}

TEST(BearingTest, TranslationOfAGivesForceAndMomentAboutItsCentre) {
  // K_b without translation/rotation coupling: force K_b t at p, moment (p − c_A) × force on A.
  const Matrix6 K_b =
      CalcAxisymmetricBearingMatrix(4e8, 1e8, 2e5, 3e2, Vector3(0.3, -0.4, 0.866).normalized());
  const Matrix12 K = CalcBearingMatrix(K_b, kPoint, kCenterA, kCenterB);
  const Vector3 t(2e-5, -1e-5, 4e-6);
  Vector12 q = Vector12::Zero();
  q.head<3>() = t;
  const Vector12 f =
      K * q;  // elastic force is −f; K q is the force the bodies exert on the bearing
  const Vector3 force = K_b.topLeftCorner<3, 3>() * t;
  EXPECT_MATRIX_NEAR(f.segment<3>(0), force, kAlgebraTol);
  EXPECT_MATRIX_NEAR(f.segment<3>(3), (kPoint - kCenterA).cross(force).eval(), kAlgebraTol);
  EXPECT_MATRIX_NEAR(f.segment<3>(6), (-force).eval(), kAlgebraTol);
  EXPECT_MATRIX_NEAR(f.segment<3>(9), (-(kPoint - kCenterB).cross(force)).eval(), kAlgebraTol);
}

TEST(BearingTest, PlanetFollowsItsCarrierPin) {
  // Carrier B rotates by θ about its centre; the planet A stays put: the pin point moved by
  // θ × (p − c_B), so the bearing pulls the planet along that displacement (elastic force on A
  // is +K_b (θ × (p − c_B)) at p); if the planet follows the pin with the same rotation, nothing
  // is loaded.
  const Matrix6 K_b =
      CalcDiagonalBearingMatrix((Vector6() << 3e8, 3e8, 1e8, 1e4, 1e4, 0).finished());
  const Vector3 planet_center = kPoint;  // planet's bearing at its own centre (the pin)
  const Matrix12 K = CalcBearingMatrix(K_b, kPoint, planet_center, kCenterB);
  const Vector3 theta(0.0, 0.0, 1e-3);
  Vector12 q = Vector12::Zero();
  q.segment<3>(9) = theta;
  const Vector12 elastic = -K * q;
  const Vector3 pin_motion = theta.cross(kPoint - kCenterB);
  EXPECT_MATRIX_NEAR(elastic.head<3>(), (K_b.topLeftCorner<3, 3>() * pin_motion).eval(),
                     kAlgebraTol);
  Vector12 follow = q;
  follow.head<3>() = pin_motion;
  follow.segment<3>(3) = theta;
  EXPECT_LT((K * follow).norm(), kAlgebraTol * K.norm() * follow.norm());
}

TEST(BearingTest, GroundedBearingIsTheABlockOfTheTwoBodyBearing) {
  const Matrix6 K_b = FullBearing();
  const Matrix12 K = CalcBearingMatrix(K_b, kPoint, kCenterA, kCenterB);
  EXPECT_MATRIX_NEAR(CalcGroundedBearingMatrix(K_b, kPoint, kCenterA),
                     (K.topLeftCorner<6, 6>().eval()), kAlgebraTol);
  EXPECT_MATRIX_NEAR(CalcGroundedBearingMatrix(K_b, kPoint, kCenterB),
                     (K.bottomRightCorner<6, 6>().eval()), kAlgebraTol);
  // At the reference node itself the transfer is the identity: K = K_b.
  EXPECT_MATRIX_NEAR(CalcGroundedBearingMatrix(K_b, kCenterA, kCenterA), K_b, kAlgebraTol);
}

TEST(BearingTest, AxisymmetricBearingIsIsotropicAboutItsAxis) {
  const Vector3 axis = Vector3(0.3, -0.4, 0.866).normalized();
  const Matrix6 K = CalcAxisymmetricBearingMatrix(4e8, 1e8, 2e5, 3e2, axis);
  const Vector3 radial = axis.cross(Vector3(1, 0, 0)).normalized();
  const Vector3 radial2 = axis.cross(radial);
  EXPECT_NEAR(axis.dot(K.topLeftCorner<3, 3>() * axis), 1e8, 1e8 * kAlgebraTol);
  EXPECT_NEAR(radial.dot(K.topLeftCorner<3, 3>() * radial), 4e8, 4e8 * kAlgebraTol);
  EXPECT_NEAR(radial2.dot(K.topLeftCorner<3, 3>() * radial2), 4e8, 4e8 * kAlgebraTol);
  EXPECT_NEAR(radial.dot(K.bottomRightCorner<3, 3>() * radial), 2e5, 2e5 * kAlgebraTol);
  EXPECT_NEAR(axis.dot(K.bottomRightCorner<3, 3>() * axis), 3e2, 2e5 * kAlgebraTol);
  EXPECT_EQ((K.topRightCorner<3, 3>().norm()), 0.0);
  // Along Z it is the diagonal bearing.
  EXPECT_MATRIX_NEAR(
      CalcAxisymmetricBearingMatrix(4e8, 1e8, 2e5, 3e2, Vector3::UnitZ()),
      CalcDiagonalBearingMatrix((Vector6() << 4e8, 4e8, 1e8, 2e5, 2e5, 3e2).finished()),
      kAlgebraTol);
}

TEST(BearingTest, InvalidInputsThrowNamingTheArgument) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Matrix6 asymmetric = FullBearing();
  asymmetric(0, 1) += 1e6;
  EXPECT_THROWS_MESSAGE(CalcBearingMatrix(asymmetric, kPoint, kCenterA, kCenterB), InvalidInput,
                        "^coefficients: must be symmetric");
  Matrix6 indefinite = FullBearing();
  indefinite(4, 4) = -1e3;
  EXPECT_THROWS_MESSAGE(CalcGroundedBearingMatrix(indefinite, kPoint, kCenterA), InvalidInput,
                        "^coefficients: must be positive semi-definite");
  Matrix6 not_finite = FullBearing();
  not_finite(2, 2) = nan;
  EXPECT_THROWS_MESSAGE(CalcBearingMatrix(not_finite, kPoint, kCenterA, kCenterB), InvalidInput,
                        "^coefficients: must be finite");
  EXPECT_THROWS_MESSAGE(CalcBearingMatrix(FullBearing(), Vector3(0, nan, 0), kCenterA, kCenterB),
                        InvalidInput, "^point: must be finite");
  EXPECT_THROWS_MESSAGE(CalcBearingMatrix(FullBearing(), kPoint, kCenterA, Vector3(nan, 0, 0)),
                        InvalidInput, "^center_b: must be finite");
  EXPECT_THROWS_MESSAGE(CalcDiagonalBearingMatrix((Vector6() << 1, 1, -1, 1, 1, 1).finished()),
                        InvalidInput,
                        "^diagonal\\(2\\): must be non-negative and finite, got -1 N/m");
  EXPECT_THROWS_MESSAGE(CalcAxisymmetricBearingMatrix(-1.0, 1, 1, 0, Vector3::UnitZ()),
                        InvalidInput, "^radial: must be non-negative and finite, got -1 N/m");
  EXPECT_THROWS_MESSAGE(CalcAxisymmetricBearingMatrix(1, 1, nan, 0, Vector3::UnitZ()), InvalidInput,
                        "^tilt: .* got nan N\\*m/rad");
  EXPECT_THROWS_MESSAGE(CalcAxisymmetricBearingMatrix(1, 1, 1, 0, Vector3(0, 0, 0.5)), InvalidInput,
                        "^axis: must be a unit vector, got \\(0, 0, 0.5\\)");
  // A PSD but singular K_b (no torsional or tilt stiffness) is accepted.
  EXPECT_NO_THROW(
      CalcBearingMatrix(CalcDiagonalBearingMatrix((Vector6() << 1e8, 1e8, 1e8, 0, 0, 0).finished()),
                        kPoint, kCenterA, kCenterB));
}

}  // namespace
}  // namespace geardyn
