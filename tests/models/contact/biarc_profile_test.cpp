#include "geardyn/models/contact/biarc_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "geardyn/common/errors.hpp"
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

TEST(BiarcFlankTest, RejectsBadInput) {
  const auto s = test::MakeContactPair(test::KimRigPair());
  EXPECT_THROWS_MESSAGE(BiarcFlank(s.pinion, -1, 0), InvalidInput, "num_biarcs: 0");
  EXPECT_THROWS_MESSAGE(BiarcFlank(s.pinion, 2, 4), InvalidInput, "unwind: must be");
}

}  // namespace
}  // namespace geardyn
