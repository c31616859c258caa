// Tests of torsional couplings and grounded torsional springs (coupling.hpp): the torque of a
// relative twist, no load for common rotations or rotations about other axes, and error paths.
#include "geardyn/models/elements/coupling.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn {
namespace {

constexpr double kTol = 100 * std::numeric_limits<double>::epsilon();
const Vector3 kAxis = Vector3(0.2, -0.5, 0.84).normalized();

TEST(CouplingTest, RelativeTwistGivesOpposedTorquesAboutTheAxis) {
  const double k = 3.5e4;  // [N·m/rad]
  const Matrix12 K = CalcTorsionalCouplingMatrix(k, kAxis);
  Vector12 q = Vector12::Zero();
  q.segment<3>(3) = 2e-3 * kAxis;   // A twisted by 2 mrad
  q.segment<3>(9) = -1e-3 * kAxis;  // B by −1 mrad
  const Vector12 f = K * q;         // elastic torques are −f
  EXPECT_MATRIX_NEAR(f.segment<3>(3), (k * 3e-3 * kAxis).eval(), kTol);
  EXPECT_MATRIX_NEAR(f.segment<3>(9), (-k * 3e-3 * kAxis).eval(), kTol);
  EXPECT_EQ(f.segment<3>(0).norm() + f.segment<3>(6).norm(), 0.0);
}

TEST(CouplingTest, CommonRotationTranslationsAndOtherAxesAreFree) {
  const Matrix12 K = CalcTorsionalCouplingMatrix(3.5e4, kAxis);
  const Vector3 other = kAxis.cross(Vector3(1, 0, 0)).normalized();  // ⟂ axis
  Vector12 common, translations, bending;
  common << Vector3::Zero(), 0.3 * kAxis + 0.1 * other, Vector3::Zero(), 0.3 * kAxis + 0.1 * other;
  translations << Vector3(1, 2, 3), Vector3::Zero(), Vector3(-1, 0, 4), Vector3::Zero();
  bending << Vector3::Zero(), other, Vector3::Zero(), -2 * other;
  for (const Vector12& q : {common, translations, bending}) {
    EXPECT_LT((K * q).norm(), kTol * K.norm() * q.norm());
  }
  // Symmetric, PSD, rank 1.
  const Eigen::SelfAdjointEigenSolver<Matrix12> eig(K, Eigen::EigenvaluesOnly);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -kTol * K.norm());
  EXPECT_EQ((eig.eigenvalues().array() > kTol * K.norm()).count(), 1);
  EXPECT_NEAR(eig.eigenvalues().maxCoeff(), 2 * 3.5e4, kTol * 3.5e4);  // k |g|², |g|² = 2
}

TEST(CouplingTest, GroundedSpringActsOnTheRotationAboutTheAxisOnly) {
  const double k = 1.2e3;
  const Matrix6 K = CalcGroundedTorsionalSpringMatrix(k, kAxis);
  Vector6 q;
  q << Vector3(1, 1, 1), 5e-3 * kAxis;
  EXPECT_MATRIX_NEAR((K * q).tail<3>().eval(), (k * 5e-3 * kAxis).eval(), kTol);
  EXPECT_EQ((K * q).head<3>().norm(), 0.0);
  // It is the A-block of a coupling to a node that does not move.
  EXPECT_MATRIX_NEAR(K, (CalcTorsionalCouplingMatrix(k, kAxis).topLeftCorner<6, 6>().eval()), kTol);
  // About Z it is the single entry K(5, 5) = k.
  Matrix6 expected = Matrix6::Zero();
  expected(5, 5) = k;
  EXPECT_MATRIX_NEAR(CalcGroundedTorsionalSpringMatrix(k, Vector3::UnitZ()), expected, 0.0);
}

TEST(CouplingTest, InvalidInputsThrowNamingTheArgument) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROWS_MESSAGE(CalcTorsionalCouplingMatrix(-1.0, kAxis), InvalidInput,
                        "^coefficient: must be non-negative and finite, got -1 N\\*m/rad");
  EXPECT_THROWS_MESSAGE(CalcGroundedTorsionalSpringMatrix(nan, kAxis), InvalidInput,
                        "^coefficient: .* got nan");
  EXPECT_THROWS_MESSAGE(CalcTorsionalCouplingMatrix(1.0, Vector3::Zero()), InvalidInput,
                        "^axis: must be a unit vector, got \\(0, 0, 0\\) with norm 0");
  EXPECT_THROWS_MESSAGE(CalcGroundedTorsionalSpringMatrix(1.0, Vector3(0, 3, 4)), InvalidInput,
                        "^axis: .* with norm 5");
  EXPECT_NO_THROW(CalcTorsionalCouplingMatrix(0.0, kAxis));  // an undamped coupling's C
}

}  // namespace
}  // namespace geardyn
