#include "geardyn/models/contact/tooth_pose.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "geardyn/models/contact/tooth_flank.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

// Moving every point of a tooth's flank rigidly (rotation ψ about the pivot, translation τ)
// gives exactly the flank of the effective base circle: the deflected flank is still an involute.
TEST(ToothPoseTest, RigidlyMovedFlankIsTheInvoluteOfTheMovedBaseCircle) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  const Vector2 c(0.02, -0.01);
  const double phi = 0.4, gamma = 1.1, rp = 0.068;
  const ToothDeflection d{2e-3, 3e-5, -4e-5};
  const EffectiveBaseCircle e = CalcEffectiveBaseCircle(c, phi, gamma, rp, d);
  const double a = phi + gamma;
  const Vector2 pivot = c + rp * Vector2(std::cos(a), std::sin(a));
  const Eigen::Rotation2Dd rot(d.rotation);
  const Vector2 tau = d.radial * Vector2(std::cos(a), std::sin(a)) +
                      d.tangential * Vector2(-std::sin(a), std::cos(a));
  for (int eps : {-1, 1}) {
    const InvoluteFlankPose rigid = MakeFlankPose(s.pinion, c, phi + gamma, eps);
    const InvoluteFlankPose moved = MakeFlankPose(s.pinion, e.center, e.angle + gamma, eps);
    for (double rho : {0.0, 0.005, 0.01, 0.02}) {
      const Vector2 p = pivot + rot * (InvolutePoint(rigid, rho) - pivot) + tau;
      EXPECT_LT((InvolutePoint(moved, rho) - p).norm(), 1e-16);
    }
  }
}

TEST(ToothPoseTest, JacobianMatchesFiniteDifferences) {
  const Vector2 c(0.02, -0.01);
  Eigen::Matrix<double, 6, 1> x;
  x << c, 0.4, 2e-3, 3e-5, -4e-5;
  auto eval = [&](const Eigen::Matrix<double, 6, 1>& v) {
    const EffectiveBaseCircle e =
        CalcEffectiveBaseCircle(v.head<2>(), v(2), 1.1, 0.068, {v(3), v(4), v(5)});
    return Vector3(e.center.x(), e.center.y(), e.angle);
  };
  const EffectiveBaseCircle e = CalcEffectiveBaseCircle(c, 0.4, 1.1, 0.068, {2e-3, 3e-5, -4e-5});
  for (int i = 0; i < 6; ++i) {
    Eigen::Matrix<double, 6, 1> xp = x, xm = x;
    const double h = 1e-7;
    xp(i) += h;
    xm(i) -= h;
    const Vector3 fd = (eval(xp) - eval(xm)) / (2 * h);
    EXPECT_LT((fd - e.jacobian.col(i)).norm(), 1e-9) << i;
  }
}

}  // namespace
}  // namespace geardyn
