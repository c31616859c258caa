#include "geardyn/models/contact/biarc_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/contact/tip_corner_contact.hpp"
#include "support/contact_pairs.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

// The biarc's deviation from the involute falls as h³ (position and tangent interpolated): the
// observed order between successive halvings of the segment length is ≈ 3.
TEST(BiarcFlankTest, DeviationFallsAtThirdOrder) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  std::vector<double> dev;
  for (int n : {4, 8, 16, 32}) dev.push_back(BiarcFlank(s.pinion, -1, n).max_deviation());
  RecordProperty("deviations", ::testing::PrintToString(dev));
  for (size_t k = 1; k < dev.size(); ++k) {
    const double order = std::log2(dev[k - 1] / dev[k]);
    EXPECT_GT(order, 2.7) << "N = " << (4 << k);
    EXPECT_LT(order, 3.5) << "N = " << (4 << k);  // pre-asymptotic 3.4 at N = 4
  }
  EXPECT_LT(dev[2], 1e-7);  // 16 biarcs: below 0.1 µm on the rig's flank
  // The arcs join with continuous tangents: consecutive arcs share the end point.
  const BiarcFlank f(s.pinion, 1, 5);
  for (size_t k = 1; k < f.arcs().size(); ++k) {
    const FlankArc &p = f.arcs()[k - 1], &q = f.arcs()[k];
    EXPECT_LT((p.center + p.radius * p.end - (q.center + q.radius * q.start)).norm(), 1e-15);
    EXPECT_LT(std::abs(p.end.x() * q.start.y() - p.end.y() * q.start.x()), 1e-12);
  }
}

// Biarc contact δ lies within the two flanks' deviations of the exact kernel's δ, over a mesh
// cycle of the rig's rigid pair at small penetrations; its gradient with respect to the poses
// matches central differences.
TEST(BiarcFlankTest, ContactWithinTheDeviationOfTheExactOne) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  for (int n : {3, 8}) {
    const BiarcFlank a(s.pinion, -1, n), b(s.gear, -1, n);
    const double tol = a.max_deviation() + b.max_deviation() + 1e-12;
    int checked = 0;
    for (int k = 0; k < 40; ++k) {
      // Place two flanks in contact on the ε = −1 tangent with penetration δ0.
      const double r1 = s.pinion.base_radius, r2 = s.gear.base_radius, c = 0.150;
      const double alpha = std::acos((r1 + r2) / c),
                   length = std::sqrt(c * c - (r1 + r2) * (r1 + r2));
      const double rho1 = s.pinion.form_roll() + 1e-4 +
                          (s.pinion.corner_roll() - s.pinion.form_roll() - 2e-4) * k / 39.0;
      const double delta0 = 5e-6 * ((k % 3) - 1);
      const double rho2 = length - rho1 + delta0;
      InvoluteFlankPose pa = MakeFlankPose(s.pinion, Vector2::Zero(), 0.0, -1);
      InvoluteFlankPose pb = MakeFlankPose(s.gear, Vector2(c, 0.0), 0.0, -1);
      pa.base_angle = -alpha + rho1 / r1;
      pb.base_angle = -alpha + kPi + rho2 / r2;
      const FlankContact exact = CalcInvoluteContact(pa, pb);
      if (!exact.valid) continue;
      const FlankContact arc = CalcBiarcContact(a, pa, b, pb);
      ASSERT_TRUE(arc.found);
      EXPECT_NEAR(arc.penetration, exact.penetration, tol) << "N " << n << " k " << k;
      EXPECT_NEAR(arc.roll1, exact.roll1, 1e-3);
      ++checked;
      if (k == 17) {
        for (int i = 0; i < 6; ++i) {
          const double h = 1e-8;
          auto eval = [&](double step) {
            InvoluteFlankPose x = pa, y = pb;
            double* v[6] = {&x.center.x(), &x.center.y(), &x.base_angle,
                            &y.center.x(), &y.center.y(), &y.base_angle};
            *v[i] += step;
            return CalcBiarcContact(a, x, b, y).penetration;
          };
          EXPECT_NEAR((eval(h) - eval(-h)) / (2 * h), arc.d_penetration(i), 1e-6) << i;
        }
      }
    }
    EXPECT_GT(checked, 20);  // rolls outside the gear's flank are skipped
  }
}

// Two flanks of the rig placed near contact, with a random misalignment so the contact leaves the
// line of action; rho1 beyond ρ_t drives the pinion's tip corner into the gear's flank.
struct PlacedFlanks {
  InvoluteFlankPose a, b;
};
PlacedFlanks Place(const ToothFlankGeometry& ga, const ToothFlankGeometry& gb, double rho1,
                   double delta0, double tilt) {
  const double r1 = ga.base_radius, r2 = gb.base_radius, c = 0.150;
  const double alpha = std::acos((r1 + r2) / c), length = std::sqrt(c * c - (r1 + r2) * (r1 + r2));
  PlacedFlanks p{MakeFlankPose(ga, Vector2::Zero(), 0.0, -1),
                 MakeFlankPose(gb, Vector2(c, 0.0), 0.0, -1)};
  p.a.base_angle = -alpha + rho1 / r1 + tilt;
  p.b.base_angle = -alpha + kPi + (length - rho1 + delta0) / r2;
  return p;
}

// The rolls the contact core passes to the lookup: the exact kernel's, or ρ_t and the corner
// kernel's mate roll beyond a flank's end (contact_mesh_core.cpp).
std::pair<double, double> LookupRolls(const PlacedFlanks& p, const ToothFlankGeometry& ga,
                                      const ToothFlankGeometry& gb) {
  const FlankContact t = CalcInvoluteContact(p.a, p.b);
  if (t.roll1 > p.a.roll_max) {
    return {p.a.roll_max, CalcTipCornerContact(p.a, ga.tip_corner_radius, p.b).roll2};
  }
  if (t.roll2 > p.b.roll_max) {
    return {CalcTipCornerContact(p.b, gb.tip_corner_radius, p.a).roll2, p.b.roll_max};
  }
  return {t.roll1, t.roll2};
}

// The O(1) lookup finds the same contact as the all-pairs search (the reference), flank–flank and
// tip corners (sharp and rounded), for coarse and fine fits: identical δ, corner flag and gradient.
TEST(BiarcFlankTest, LookupNearTheRollsEqualsTheAllPairsSearch) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double rho_a : {0.0, 0.3e-3}) {
    ToothFlankGeometry ga = s.pinion, gb = s.gear;
    ga.tip_corner_radius = gb.tip_corner_radius = rho_a;
    for (const int n : {1, 2, 4, 16}) {
      const BiarcFlank a(ga, -1, n), b(gb, -1, n);
      int compared = 0, corners = 0;
      for (int k = 0; k < 400; ++k) {
        const double rho1 = ga.form_roll() + (ga.tip_roll() + 1e-3 - ga.form_roll()) * u(rng);
        const PlacedFlanks p = Place(ga, gb, rho1, 2e-5 * (u(rng) - 0.3), 2e-4 * (u(rng) - 0.5));
        const auto [ra, rb] = LookupRolls(p, ga, gb);
        const FlankContact all = CalcBiarcContact(a, p.a, b, p.b);
        const FlankContact near = CalcBiarcContactNear(a, p.a, ra, b, p.b, rb);
        ASSERT_EQ(near.found, all.found) << "N " << n << " k " << k;
        if (!all.found) continue;
        ++compared;
        corners += all.corner != 0;
        EXPECT_EQ(near.corner, all.corner);
        EXPECT_EQ(near.penetration, all.penetration) << "N " << n << " k " << k;
        EXPECT_EQ(near.d_penetration, all.d_penetration);
      }
      EXPECT_GT(compared, 250) << "N " << n;
      EXPECT_GT(corners, 10) << "N " << n << " rho_a " << rho_a;
    }
  }
}

// Every gradient of the lookup's contact (δ, both rolls, the point) against central differences of
// the poses, on flank–flank and tip-corner contacts.
TEST(BiarcFlankTest, GradientsMatchFiniteDifferences) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  ToothFlankGeometry ga = s.pinion, gb = s.gear;
  ga.tip_corner_radius = gb.tip_corner_radius = 0.2e-3;
  const BiarcFlank a(ga, -1, 5), b(gb, -1, 5);
  int corners = 0, flanks = 0;
  for (const double frac : {0.1, 0.35, 0.62, 0.9, 0.998, 1.02}) {
    const double rho1 = ga.form_roll() + (ga.tip_roll() - ga.form_roll()) * frac;
    const PlacedFlanks p = Place(ga, gb, rho1, 4e-6, 3e-5);
    const auto [ra, rb] = LookupRolls(p, ga, gb);
    const FlankContact c = CalcBiarcContactNear(a, p.a, ra, b, p.b, rb);
    ASSERT_TRUE(c.found) << frac;
    (c.corner ? corners : flanks)++;
    for (int i = 0; i < 6; ++i) {
      const double h = i % 3 == 2 ? 1e-9 : 1e-10;
      // The rolls by value: clang 14 cannot capture a structured binding (P1091, clang 16).
      auto eval = [&, roll_a = ra, roll_b = rb](double step) {
        PlacedFlanks q = p;
        double* v[6] = {&q.a.center.x(), &q.a.center.y(), &q.a.base_angle,
                        &q.b.center.x(), &q.b.center.y(), &q.b.base_angle};
        *v[i] += step;
        return CalcBiarcContactNear(a, q.a, roll_a, b, q.b, roll_b);
      };
      const FlankContact cp = eval(h), cm = eval(-h);
      ASSERT_EQ(cp.corner, c.corner);
      ASSERT_EQ(cm.corner, c.corner);
      const double tol = i % 3 == 2 ? 1e-7 : 1e-5;  // per rad: lengths of ≈ 0.1 m
      EXPECT_NEAR((cp.penetration - cm.penetration) / (2 * h), c.d_penetration(i), tol) << i;
      EXPECT_NEAR((cp.roll1 - cm.roll1) / (2 * h), c.d_roll1(i), 1e3 * tol) << frac << " " << i;
      EXPECT_NEAR((cp.roll2 - cm.roll2) / (2 * h), c.d_roll2(i), 1e3 * tol) << frac << " " << i;
      const Vector2 dp = (cp.point - cm.point) / (2 * h);
      EXPECT_NEAR(dp.x(), c.d_point(0, i), 1e3 * tol) << frac << " " << i;
      EXPECT_NEAR(dp.y(), c.d_point(1, i), 1e3 * tol) << frac << " " << i;
    }
  }
  EXPECT_GT(corners, 0);
  EXPECT_GT(flanks, 0);
}

TEST(BiarcFlankTest, RejectsBadInput) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  EXPECT_THROWS_MESSAGE(BiarcFlank(s.pinion, -1, 0), InvalidInput, "num_biarcs: 0");
  EXPECT_THROWS_MESSAGE(BiarcFlank(s.pinion, 2, 4), InvalidInput, "unwind: must be");
}

}  // namespace
}  // namespace geardyn
