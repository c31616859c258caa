#include "geardyn/models/contact/tooth_flank.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/common/errors.hpp"
#include "support/contact_pairs.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

// Every flank point satisfies |P − c|² = r_b² + ρ² (the generating line is tangent to the base
// circle), its tangent dP/dρ has length ρ/r_b and is normal to n (central differences), and n
// points out of the tooth (away from its centre line).
TEST(ToothFlankTest, InvoluteInvariants) {
  const auto s = test::MakeContactPair(test::UnequalSpurPair());
  for (int eps : {-1, 1}) {
    const double gamma = 0.7;
    const InvoluteFlankPose f = MakeFlankPose(s.pinion, Vector2(0.01, 0.02), gamma, eps);
    for (double rho : {0.001, 0.005, 0.01, 0.015}) {
      const Vector2 p = InvolutePoint(f, rho) - f.center;
      EXPECT_NEAR(p.squaredNorm(), f.base_radius * f.base_radius + rho * rho, 1e-17);
      const double h = 1e-7;
      const Vector2 tangent = (InvolutePoint(f, rho + h) - InvolutePoint(f, rho - h)) / (2 * h);
      EXPECT_NEAR(tangent.norm(), rho / f.base_radius, 1e-8);
      const Vector2 n = InvoluteNormal(f, rho);
      EXPECT_NEAR(n.dot(tangent), 0.0, 1e-8);
      // Outward: moving along n increases the angular distance from the centre line.
      const Vector2 q = p + 1e-6 * n;
      const double before = std::abs(std::remainder(std::atan2(p.y(), p.x()) - gamma, 2 * kPi));
      const double after = std::abs(std::remainder(std::atan2(q.y(), q.x()) - gamma, 2 * kPi));
      EXPECT_GT(after, before);
    }
  }
}

// ψ_b reproduces the tooth thicknesses of gear_geometry: the arc between the two flanks of one
// tooth at the reference radius is s_t, at the tip radius s_at.
TEST(ToothFlankTest, HalfAngleGivesTheToothThicknesses) {
  for (const GearPairSpec& spec : {test::UnequalSpurPair(), test::HelicalPair()}) {
    const auto s = test::MakeContactPair(spec);
    for (const auto* member : {&s.pair.pinion, &s.pair.gear}) {
      const ToothFlankGeometry g = MakeToothFlankGeometry(s.pair, *member);
      const InvoluteFlankPose left = MakeFlankPose(g, Vector2::Zero(), 0.0, 1);
      const InvoluteFlankPose right = MakeFlankPose(g, Vector2::Zero(), 0.0, -1);
      auto arc = [&](double radius) {
        const double rho = std::sqrt(radius * radius - g.base_radius * g.base_radius);
        const Vector2 a = InvolutePoint(left, rho), b = InvolutePoint(right, rho);
        return radius * (std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()));
      };
      EXPECT_NEAR(arc(member->reference_radius), member->tooth_thickness_transverse, 1e-12);
      EXPECT_NEAR(arc(member->tip_radius), member->tip_thickness_transverse, 1e-9);
    }
  }
}

TEST(ToothFlankTest, RejectsBadInput) {
  const auto s = test::MakeContactPair(test::UnequalSpurPair());
  EXPECT_THROWS_MESSAGE(MakeToothFlankGeometry(s.pair, s.pair.pinion, 0.0, -1e-4), InvalidInput,
                        "tip_corner_radius: must be finite and >= 0");
  EXPECT_THROWS_MESSAGE(MakeToothFlankGeometry(s.pair, s.pair.pinion, 0.0, 5e-3), InvalidInput,
                        "tip_corner_radius: .* half the tip thickness");
  EXPECT_THROWS_MESSAGE(MakeToothFlankGeometry(s.pair, s.pair.pinion, 1.0), InvalidInput,
                        "form_radius: ");
  GearGeometry ring = s.pair.gear;
  ring.kind = GearKind::kInternal;
  EXPECT_THROWS_MESSAGE(MakeToothFlankGeometry(s.pair, ring), InvalidInput, "member.kind");
}

}  // namespace
}  // namespace geardyn
