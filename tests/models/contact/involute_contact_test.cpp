#include "geardyn/models/contact/involute_contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "support/contact_pairs.hpp"
#include "support/no_malloc.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

// Two flanks of the rig's gears near contact, the pinion at the origin, the gear at (C, 0),
// facing each other on the ε = −1 tangent; `open` widens the gap along the line [m].
struct FlankPairSetup {
  InvoluteFlankPose f1, f2;
};

FlankPairSetup MakeFlankPair(std::mt19937* rng, double open = 0.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double r1 = 0.0704769, r2 = 0.0512, c = 0.1295;
  const int eps = -1;
  FlankPairSetup s;
  const Vector2 c1(0.01 * u(*rng), 0.01 * u(*rng));
  const double gamma = 0.3 * u(*rng);
  const Vector2 c2 = c1 + c * Vector2(std::cos(gamma), std::sin(gamma));
  // Tangent point angle t1 = γ + ε α; choose rolls ρ1 near the middle, ρ2 closing the line.
  const double alpha = std::acos((r1 + r2) / c);
  const double length = std::sqrt(c * c - (r1 + r2) * (r1 + r2));
  const double t1 = gamma + eps * alpha;
  const double rho1 = 0.5 * length + 0.2 * length * u(*rng);
  const double rho2 = length - rho1 - open;
  s.f1 = {c1, r1, t1 - eps * rho1 / r1, eps, 0.0, 0.06, 0.005};
  s.f2 = {c2, r2, t1 + kPi - eps * rho2 / r2, eps, 0.0, 0.06, 0.005};
  return s;
}

using PoseVector = Eigen::Matrix<double, 6, 1>;

PoseVector Pack(const InvoluteFlankPose& a, const InvoluteFlankPose& b) {
  PoseVector p;
  p << a.center, a.base_angle, b.center, b.base_angle;
  return p;
}
void Unpack(const PoseVector& p, InvoluteFlankPose* a, InvoluteFlankPose* b) {
  a->center = p.head<2>();
  a->base_angle = p(2);
  b->center = p.segment<2>(3);
  b->base_angle = p(5);
}

// The contact points lie on their flanks, the normals are the flanks' outward normals (opposite),
// and P2 − P1 = −δ n.
TEST(InvoluteContactTest, PointsAndNormalsLieOnTheFlanks) {
  std::mt19937 rng(7);
  for (int k = 0; k < 50; ++k) {
    const FlankPairSetup s = MakeFlankPair(&rng, 1e-4 * (k % 5 - 2));
    const FlankContact c = CalcInvoluteContact(s.f1, s.f2);
    ASSERT_TRUE(c.found);
    EXPECT_TRUE(c.valid);
    EXPECT_LT((InvolutePoint(s.f1, c.roll1) - c.point1).norm(), 1e-15);
    EXPECT_LT((InvolutePoint(s.f2, c.roll2) - c.point2).norm(), 1e-15);
    EXPECT_LT((InvoluteNormal(s.f1, c.roll1) - c.normal).norm(), 1e-14);
    EXPECT_LT((InvoluteNormal(s.f2, c.roll2) + c.normal).norm(), 1e-14);
    EXPECT_LT((c.point2 - c.point1 + c.penetration * c.normal).norm(), 1e-15);
    EXPECT_NEAR(c.penetration, 1e-4 * (2 - k % 5), 1e-15);
  }
}

// Independent truth for a gap: the smallest distance between the two flank curves, found by a
// nested golden-section search over both roll parameters, equals −δ.
TEST(InvoluteContactTest, GapEqualsTheMinimumDistanceBetweenTheFlanks) {
  std::mt19937 rng(11);
  for (int k = 0; k < 10; ++k) {
    const double open = 2e-5 * (k + 1);
    const FlankPairSetup s = MakeFlankPair(&rng, open);
    const FlankContact c = CalcInvoluteContact(s.f1, s.f2);
    auto golden = [](auto f, double a, double b) {
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
      for (int it = 0; it < 120; ++it) {
        if (f1 < f2) {
          b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
        } else {
          a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
        }
      }
      return f(0.5 * (a + b));
    };
    auto dist_to_2 = [&](double rho1) {
      const Vector2 p = InvolutePoint(s.f1, rho1);
      return golden([&](double rho2) { return (InvolutePoint(s.f2, rho2) - p).norm(); },
                    c.roll2 - 5e-3, c.roll2 + 5e-3);
    };
    const double dmin = golden(dist_to_2, c.roll1 - 5e-3, c.roll1 + 5e-3);
    EXPECT_NEAR(dmin, -c.penetration, 1e-10) << "open " << open;
  }
}

// Closed-form derivatives of δ, ρ1, ρ2 and the point against central differences.
TEST(InvoluteContactTest, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(3);
  for (int k = 0; k < 20; ++k) {
    FlankPairSetup s = MakeFlankPair(&rng, 3e-5 * (k % 3 - 1));
    const FlankContact c = CalcInvoluteContact(s.f1, s.f2);
    const PoseVector p0 = Pack(s.f1, s.f2);
    const double h = 1e-7;
    for (int i = 0; i < 6; ++i) {
      PoseVector pp = p0, pm = p0;
      pp(i) += h;
      pm(i) -= h;
      InvoluteFlankPose a = s.f1, b = s.f2;
      Unpack(pp, &a, &b);
      const FlankContact cp = CalcInvoluteContact(a, b);
      Unpack(pm, &a, &b);
      const FlankContact cm = CalcInvoluteContact(a, b);
      // h = 1e-7 on lengths of 0.1 m: round-off ~1e-9, truncation ~h² |f'''| ~1e-12.
      constexpr double kTol = 1e-8;
      EXPECT_NEAR((cp.penetration - cm.penetration) / (2 * h), c.d_penetration(i), kTol) << i;
      EXPECT_NEAR((cp.roll1 - cm.roll1) / (2 * h), c.d_roll1(i), kTol) << i;
      EXPECT_NEAR((cp.roll2 - cm.roll2) / (2 * h), c.d_roll2(i), kTol) << i;
      EXPECT_LT(((cp.point - cm.point) / (2 * h) - c.d_point.col(i)).norm(), kTol) << i;
    }
  }
}

// Rates: the approach rate is the time derivative of δ along the pose path (central
// differences), and at the pitch point of a pair turning at the nominal ratio the sliding speed
// is zero (pure rolling); elsewhere it is ω1 ρ1 − ω2 ρ2 (rolling speeds of the two flanks).
TEST(InvoluteContactTest, ApproachAndSlidingRates) {
  std::mt19937 rng(5);
  for (int k = 0; k < 10; ++k) {
    FlankPairSetup s = MakeFlankPair(&rng, 0.0);
    const FlankContact c = CalcInvoluteContact(s.f1, s.f2);
    const Vector3 rate1(0.3, -0.2, 12.0), rate2(-0.1, 0.4, -7.0);
    const ContactRates r = CalcContactRates(c, s.f1.center, rate1, s.f2.center, rate2);
    const double h = 1e-7;
    InvoluteFlankPose a = s.f1, b = s.f2;
    auto at = [&](double t) {
      a.center = s.f1.center + t * rate1.head<2>();
      a.base_angle = s.f1.base_angle + t * rate1.z();
      b.center = s.f2.center + t * rate2.head<2>();
      b.base_angle = s.f2.base_angle + t * rate2.z();
      return CalcInvoluteContact(a, b).penetration;
    };
    EXPECT_NEAR(r.approach, (at(h) - at(-h)) / (2 * h), 1e-7);
    // Nominal rotation ω1 = 100 rad/s, ω2 = −ω1 r1/r2: rolling speeds ω1 ρ1 and |ω2| ρ2.
    const double w1 = 100.0, w2 = -w1 * s.f1.base_radius / s.f2.base_radius;
    const ContactRates rr =
        CalcContactRates(c, s.f1.center, Vector3(0, 0, w1), s.f2.center, Vector3(0, 0, w2));
    EXPECT_NEAR(rr.approach, 0.0, 1e-12);
    EXPECT_NEAR(std::abs(rr.sliding), std::abs(w1 * c.roll1 - std::abs(w2) * c.roll2), 1e-10);
  }
}

TEST(InvoluteContactTest, NoContactForOppositeSensesOrOverlappingBaseCircles) {
  std::mt19937 rng(1);
  FlankPairSetup s = MakeFlankPair(&rng);
  InvoluteFlankPose f2 = s.f2;
  f2.unwind = -f2.unwind;
  EXPECT_FALSE(CalcInvoluteContact(s.f1, f2).found);
  f2 = s.f2;
  f2.center = s.f1.center + Vector2(0.1, 0.0);  // C < r1 + r2
  EXPECT_FALSE(CalcInvoluteContact(s.f1, f2).found);
  f2.center = Vector2(NAN, 0.0);
  EXPECT_FALSE(CalcInvoluteContact(s.f1, f2).found);
  // A roll outside [ρ_F, ρ_a] or a wrong tooth (|δ| > max_depth) is found but not valid.
  f2 = s.f2;
  f2.roll_max = 1e-3;
  EXPECT_FALSE(CalcInvoluteContact(s.f1, f2).valid);
  f2 = s.f2;
  f2.base_angle += 2 * kPi / 50;  // the next tooth: δ shifted by a base pitch
  const FlankContact c = CalcInvoluteContact(s.f1, f2);
  EXPECT_TRUE(c.found);
  EXPECT_FALSE(c.valid);
}

TEST(InvoluteContactTest, KernelDoesNotAllocate) {
  std::mt19937 rng(2);
  const FlankPairSetup s = MakeFlankPair(&rng);
  double sum = 0.0;
  const long n = test::CountAllocations([&] {
    for (int k = 0; k < 100; ++k) {
      InvoluteFlankPose a = s.f1;
      a.base_angle += 1e-6 * k;
      sum += CalcInvoluteContact(a, s.f2).penetration;
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace geardyn
