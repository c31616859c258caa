#include "geardyn/models/contact/tip_corner_contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/models/contact/mesh_kinematics.hpp"
#include "support/contact_pairs.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

// A pinion tooth whose tip corner is pushed past the end of the path of contact: the rig's pair
// with the pinion turned on so that its flank's involute point lies beyond ρ_t.
struct CornerSetup {
  InvoluteFlankPose a, b;  // corner tooth's flank (pinion), mate flank (gear)
  double rho_a;
};

CornerSetup MakeCorner(double rho_a, double extra_roll, double open) {
  // Pinion (r_b1) at the origin, gear at (C, 0), ε = −1 tangent; set the involute point at
  // ρ1 = ρ_t + extra_roll on the pinion and ρ2 = L − ρ1 − open on the gear.
  const double r1 = 0.0704769, r2 = 0.0704769, c = 0.150;
  const double ra = 0.078;
  ToothFlankGeometry g;
  g.teeth = 50;
  g.base_radius = r1;
  g.tip_radius = ra;
  g.form_radius = r1;
  g.tip_corner_radius = rho_a;
  const int eps = -1;
  const double alpha = std::acos((r1 + r2) / c);
  const double length = std::sqrt(c * c - (r1 + r2) * (r1 + r2));
  const double t1 = eps * alpha;
  const double rho1 = g.corner_roll() + extra_roll;
  const double rho2 = length - rho1 - open;
  CornerSetup s;
  s.rho_a = rho_a;
  s.a = MakeFlankPose(g, Vector2::Zero(), 0.0, eps);
  s.a.base_angle = t1 - eps * rho1 / r1;
  s.b = MakeFlankPose(g, Vector2(c, 0.0), 0.0, eps);
  s.b.base_angle = t1 + kPi - eps * rho2 / r2;
  return s;
}

// Independent truth: for a sharp corner (ρ_a = 0) the penetration is minus the distance from the
// corner point P_A(ρ_t) to the mate's flank curve (golden-section search over its roll), and
// with ρ_a > 0 the corner circle's distance is that of its centre minus ρ_a.
TEST(TipCornerContactTest, PenetrationIsTheDistanceToTheMateFlank) {
  for (double rho_a : {0.0, 0.3e-3}) {
    for (double extra : {0.2e-3, 0.6e-3}) {
      const CornerSetup s = MakeCorner(rho_a, extra, 30e-6);
      const FlankContact c = CalcTipCornerContact(s.a, s.rho_a, s.b);
      ASSERT_TRUE(c.found);
      EXPECT_TRUE(c.valid);
      const double rho_t = s.a.roll_max;
      const Vector2 q = InvolutePoint(s.a, rho_t) - s.rho_a * InvoluteNormal(s.a, rho_t);
      auto dist = [&](double sigma) { return (InvolutePoint(s.b, sigma) - q).norm(); };
      double lo = c.roll2 - 5e-3, hi = c.roll2 + 5e-3;
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int it = 0; it < 150; ++it) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        (dist(x1) < dist(x2) ? hi : lo) = dist(x1) < dist(x2) ? x2 : x1;
      }
      EXPECT_NEAR(c.penetration, s.rho_a - dist(0.5 * (lo + hi)), 1e-11);
      EXPECT_NEAR(c.roll2, 0.5 * (lo + hi), 1e-6);
    }
  }
}

// Continuous hand-over: as the involute point passes the flank's end ρ_t, the corner contact's δ
// and normal continue the flank–flank ones (equal at the boundary, both for ρ_a = 0 and > 0).
TEST(TipCornerContactTest, HandOverFromTheInvoluteIsContinuous) {
  for (double rho_a : {0.0, 0.3e-3}) {
    const CornerSetup s = MakeCorner(rho_a, 0.0, 20e-6);
    const FlankContact flank = CalcInvoluteContact(s.a, s.b);
    const FlankContact corner = CalcTipCornerContact(s.a, s.rho_a, s.b);
    EXPECT_NEAR(flank.penetration, corner.penetration, 1e-12);
    EXPECT_LT((flank.normal - corner.normal).norm(), 1e-9);
    EXPECT_NEAR(flank.roll2, corner.roll2, 1e-9);
    // Just beyond: the involute is no longer valid, the corner is; δ moves by O(step²)-small
    // amounts away from the boundary (the corner follows the flank's tangent).
    const CornerSetup beyond = MakeCorner(rho_a, 1e-6, 20e-6);
    EXPECT_FALSE(CalcInvoluteContact(beyond.a, beyond.b).valid);
    const FlankContact c2 = CalcTipCornerContact(beyond.a, beyond.rho_a, beyond.b);
    EXPECT_TRUE(c2.valid);
    EXPECT_NEAR(c2.penetration, corner.penetration, 1e-8);
  }
}

TEST(TipCornerContactTest, DerivativesMatchFiniteDifferences) {
  for (double rho_a : {0.0, 0.3e-3}) {
    const CornerSetup s = MakeCorner(rho_a, 0.4e-3, 10e-6);
    const FlankContact c = CalcTipCornerContact(s.a, s.rho_a, s.b);
    for (int i = 0; i < 6; ++i) {
      const double h = 1e-7;
      auto eval = [&](double step) {
        InvoluteFlankPose a = s.a, b = s.b;
        double* v[6] = {&a.center.x(), &a.center.y(), &a.base_angle,
                        &b.center.x(), &b.center.y(), &b.base_angle};
        *v[i] += step;
        return CalcTipCornerContact(a, s.rho_a, b);
      };
      const FlankContact cp = eval(h), cm = eval(-h);
      EXPECT_NEAR((cp.penetration - cm.penetration) / (2 * h), c.d_penetration(i), 1e-8) << i;
      EXPECT_NEAR((cp.roll2 - cm.roll2) / (2 * h), c.d_roll2(i), 1e-7) << i;
      EXPECT_LT(((cp.point - cm.point) / (2 * h) - c.d_point.col(i)).norm(), 1e-7) << i;
    }
  }
}

// Through the mesh kinematics: a pinion tooth turned on beyond the end of its path (the pair of
// cycle 0 after the end of contact, pinion advanced) gets a corner contact, and the swapped form
// for a gear tip at the start of the path; the gradients still match central differences.
TEST(TipCornerContactTest, MeshKinematicsFallsBackToTheCorner) {
  const auto s = test::MakeContactPair(test::KimRigPair(150.0));
  ToothFlankGeometry pinion = s.pinion, gear = s.gear;
  pinion.tip_corner_radius = 0.2e-3;
  gear.tip_corner_radius = 0.2e-3;
  const ContactMeshKinematics kin(s.pair, s.frame, pinion, gear, 1);
  const double pbt = s.pair.transverse_base_pitch;
  const double x_end = s.pair.path_end_from_pinion_tangent - s.pair.pitch_point_from_pinion_tangent;
  const double x_start =
      s.pair.path_start_from_pinion_tangent - s.pair.pitch_point_from_pinion_tangent;
  // Pinion tip: cycle 0 at x slightly beyond the pinion's flank end; the pinion leads by 30 µm.
  for (int which : {1, 2}) {
    const double x = which == 1 ? x_end + 0.1e-3 : x_start - 0.1e-3;
    const double theta = 2 * kPi * x / pbt;
    Vector12 q = Vector12::Zero();
    q(5) = 30e-6 / s.pair.pinion.base_radius;
    const SliceToothContact c = kin.EvalToothPair(q, theta, 0, 0, 0, FlankSide::kDrive);
    ASSERT_TRUE(c.transverse.found);
    EXPECT_EQ(c.transverse.corner, which);
    EXPECT_TRUE(c.transverse.valid);
    EXPECT_GT(c.penetration, 0.0);
    EXPECT_LT(c.penetration, 30e-6);
    for (int i : {0, 1, 5, 6, 7, 11}) {
      const double h = 1e-8;
      Vector12 qp = q, qm = q;
      qp(i) += h;
      qm(i) -= h;
      const double fd = (kin.EvalToothPair(qp, theta, 0, 0, 0, FlankSide::kDrive).penetration -
                         kin.EvalToothPair(qm, theta, 0, 0, 0, FlankSide::kDrive).penetration) /
                        (2 * h);
      EXPECT_NEAR(fd, c.d_penetration(i), 1e-6 * (1.0 + std::abs(c.d_penetration(i)))) << i;
    }
  }
}

}  // namespace
}  // namespace geardyn
