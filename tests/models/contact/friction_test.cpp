// Regularised friction (friction.hpp): limits, dissipation sign, derivatives.
#include "geardyn/models/contact/friction.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace geardyn {
namespace {

TEST(FrictionTest, TendsToCoulombAwayFromZeroSpeed) {
  const double mu = 0.08, fn = 1500.0, eps = kDefaultFrictionSpeed;
  // Coulomb: |f_t| = μ f_n opposing v_s (Kim Eq. 13); tanh is within 2e^{−2v/ε} of the sign.
  EXPECT_NEAR(EvalFriction(mu, fn, 0.5, eps).force, -mu * fn, 2.0 * std::exp(-100.0) * mu * fn);
  EXPECT_NEAR(EvalFriction(mu, fn, -0.5, eps).force, mu * fn, 1e-12);
  EXPECT_EQ(EvalFriction(mu, fn, 0.0, eps).force, 0.0);
}

TEST(FrictionTest, DissipatesAndDerivativesMatchFiniteDifferences) {
  const double mu = 0.1, eps = 0.01;
  for (const double fn : {0.0, 10.0, 2e3}) {
    for (const double v : {-0.3, -0.004, 0.0, 0.002, 0.7}) {
      const FrictionValue f = EvalFriction(mu, fn, v, eps);
      EXPECT_GE(f.dissipation, 0.0);
      EXPECT_DOUBLE_EQ(f.dissipation, -f.force * v);
      const double h = 1e-7;
      const double dv =
          (EvalFriction(mu, fn, v + h, eps).force - EvalFriction(mu, fn, v - h, eps).force) /
          (2 * h);
      const double dn =
          (EvalFriction(mu, fn + 1.0, v, eps).force - EvalFriction(mu, fn - 1.0, v, eps).force) /
          2.0;
      EXPECT_NEAR(f.d_force_d_speed, dv, 1e-6 * std::abs(dv) + 1e-9);
      EXPECT_NEAR(f.d_force_d_normal, dn, 1e-9);
    }
  }
}

}  // namespace
}  // namespace geardyn
