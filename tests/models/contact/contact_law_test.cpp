// Contact laws (contact_law.hpp): closed forms, SI conversion, finite-difference derivatives,
// energy (∫ f_e dδ = E) and the loading–unloading cycle (∮ f dδ = ∫ D dt).
#include "geardyn/models/contact/contact_law.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;
// Central differences of smooth laws at h = 1e-6 relative: O(h²) truncation + 1e-16/h rounding.
constexpr double kFdTol = 1e-7;

ContactLaw LineLaw() {
  ContactLaw law = KimContactLaw();
  law.kind = ContactLawKind::kLine;
  law.contact_modulus = ContactModulusSameMaterial(2.0e11, 0.3);
  return law;
}

const LineContactGeometry kLine{0.012, 0.03, 0.004};  // R1, R2, L [m]

TEST(ContactLawTest, KimValuesConvertExactlyToSi) {
  const ContactLaw law = KimContactLaw();
  // k: N/mm^1.5 → N/m^1.5 multiplies by (1000 mm/m)^1.5; evaluate both unit systems at one point.
  const double delta_mm = 1.3e-3, rate_mm = 40.0;  // δ [mm], δ̇ [mm/s]
  const double f_mm = 39.3e6 * std::pow(delta_mm, 1.5) + 1.0 * rate_mm * std::pow(delta_mm, 0.25);
  const ContactLawValue v = EvalContactLaw(law, delta_mm * 1e-3, rate_mm * 1e-3);
  EXPECT_NEAR(v.force, f_mm, 1e-13 * f_mm);                      // the same force in N
  EXPECT_DOUBLE_EQ(law.stiffness, 39.3e6 * 31622.776601683792);  // 1000^1.5
  EXPECT_DOUBLE_EQ(law.damping, 5623.413251903491);              // 1000^1.25
  std::string why;
  EXPECT_TRUE(law.IsValid(&why)) << why;
}

TEST(ContactLawTest, ClosedFormsOfKimAndLinear) {
  const ContactLaw kim = KimContactLaw();
  const double d = 2e-6, r = 0.03;
  const ContactLawValue v = EvalContactLaw(kim, d, r);
  const double fe = kim.stiffness * std::pow(d, 1.5);
  const double fd = kim.damping * r * std::pow(d, 0.25);
  EXPECT_NEAR(v.force, fe + fd, 1e-14 * v.force);
  EXPECT_NEAR(v.energy, kim.stiffness * std::pow(d, 2.5) / 2.5, 1e-14 * v.energy);
  EXPECT_NEAR(v.dissipation, fd * r, 1e-14 * fd * r);
  const ContactLaw lin = LinearContactLaw(3e8, 120.0);
  const ContactLawValue w = EvalContactLaw(lin, d, r);
  EXPECT_DOUBLE_EQ(w.force, 3e8 * d + 120.0 * r);
  EXPECT_DOUBLE_EQ(w.d_force_d_gap, 3e8);
  EXPECT_DOUBLE_EQ(w.d_force_d_rate, 120.0);
  EXPECT_DOUBLE_EQ(w.energy, 0.5 * 3e8 * d * d);
  // No contact: nothing.
  const ContactLawValue open = EvalContactLaw(kim, -1e-6, 1.0);
  EXPECT_EQ(open.force, 0.0);
  EXPECT_EQ(open.energy, 0.0);
  EXPECT_EQ(open.dissipation, 0.0);
}

TEST(ContactLawTest, LineLawInvertsJohnsonsApproach) {
  const ContactLaw law = LineLaw();
  for (const double force : {1e-3, 1.0, 1e3, 5e4, 1e6}) {
    const double delta = LineContactApproach(force, law.contact_modulus, kLine);
    const ContactLawValue v = EvalContactLaw(law, delta, 0.0, kLine);
    EXPECT_NEAR(v.force, force, 1e-10 * force) << force;
  }
  // Johnson's formula written out: δ = F/(πLE*)[ln(4R1/a) + ln(4R2/a) − 1], a² = 4FR/(πLE*).
  const double f = 2000.0, es = law.contact_modulus, len = kLine.length;
  const double rr = 1.0 / (1.0 / kLine.radius1 + 1.0 / kLine.radius2);
  const double a = std::sqrt(4.0 * f * rr / (kPi * len * es));
  const double delta =
      f / (kPi * len * es) *
      (std::log(4.0 * kLine.radius1 / a) + std::log(4.0 * kLine.radius2 / a) - 1.0);
  EXPECT_NEAR(LineContactApproach(f, es, kLine), delta, 1e-13 * delta);
}

TEST(ContactLawTest, DerivativesMatchFiniteDifferences) {
  const ContactLaw laws[] = {KimContactLaw(), LinearContactLaw(4e8, 300.0), LineLaw()};
  for (const ContactLaw& law : laws) {
    for (const double d : {3e-7, 2e-6, 1.5e-5}) {
      for (const double r : {-0.02, 0.004, 0.05}) {
        const ContactLawValue v = EvalContactLaw(law, d, r, kLine);
        if (v.clamped) continue;
        const double hd = 1e-6 * d,
                     hr = 1e-2 * std::abs(r);  // f is linear in δ̇ (m2 = 1): no truncation
        const double fd_gap = (EvalContactLaw(law, d + hd, r, kLine).force -
                               EvalContactLaw(law, d - hd, r, kLine).force) /
                              (2.0 * hd);
        const double fd_rate = (EvalContactLaw(law, d, r + hr, kLine).force -
                                EvalContactLaw(law, d, r - hr, kLine).force) /
                               (2.0 * hr);
        EXPECT_NEAR(v.d_force_d_gap, fd_gap, kFdTol * std::abs(fd_gap)) << ToString(law.kind);
        EXPECT_NEAR(v.d_force_d_rate, fd_rate, kFdTol * std::abs(fd_rate) + 1e-12)
            << ToString(law.kind);
        // Energy: dE/dδ = f_e = f at δ̇ = 0.
        const double de = (EvalContactLaw(law, d + hd, 0.0, kLine).energy -
                           EvalContactLaw(law, d - hd, 0.0, kLine).energy) /
                          (2.0 * hd);
        const double fe = EvalContactLaw(law, d, 0.0, kLine).force;
        EXPECT_NEAR(de, fe, kFdTol * fe) << ToString(law.kind);
      }
    }
  }
}

TEST(ContactLawTest, LineLawContinuesLinearlyBeyondItsBranch) {
  const ContactLaw law = LineLaw();
  const double a = 1.0 / (kPi * kLine.length * law.contact_modulus);
  const double b = 4.0 * kPi * kLine.length * law.contact_modulus * (kLine.radius1 + kLine.radius2);
  const double gap_lim = 2.0 * a * b * std::exp(-3.0);
  const ContactLawValue below = EvalContactLaw(law, gap_lim * (1 - 1e-9), 0.0, kLine);
  const ContactLawValue above = EvalContactLaw(law, gap_lim * (1 + 1e-9), 0.0, kLine);
  EXPECT_NEAR(below.force, above.force, 1e-7 * above.force);                          // C⁰
  EXPECT_NEAR(below.d_force_d_gap, above.d_force_d_gap, 1e-4 * above.d_force_d_gap);  // C¹
  EXPECT_DOUBLE_EQ(above.d_force_d_gap, 1.0 / a);
}

// A closed loading–unloading cycle δ(t) = δ0 sin²(πt/T) integrated by the trapezoid rule on a
// fine grid: the work ∮ f dδ = ∮ f δ̇ dt equals ∫ D dt (E returns to 0), including the
// separation phase where the damping would pull and f is clamped.
TEST(ContactLawTest, CycleWorkEqualsDissipation) {
  const ContactLaw laws[] = {KimContactLaw(), LinearContactLaw(4e8, 2e4), LineLaw()};
  for (const ContactLaw& base : laws) {
    for (const double period : {1e-3, 1e-6}) {  // slow, and fast enough to clamp
      ContactLaw law = base;
      const double d0 = 4e-6;
      const int n = 200000;
      double work = 0.0, dissipated = 0.0, prev_p = 0.0, prev_d = 0.0;
      bool clamped = false;
      for (int i = 0; i <= n; ++i) {
        const double t = period * i / n;
        const double s = std::sin(kPi * t / period), c = std::cos(kPi * t / period);
        const double delta = d0 * s * s, rate = d0 * 2.0 * s * c * kPi / period;
        const ContactLawValue v = EvalContactLaw(law, delta, rate, kLine);
        clamped = clamped || v.clamped;
        const double p = v.force * rate;
        if (i > 0) {
          work += 0.5 * (p + prev_p) * period / n;
          dissipated += 0.5 * (v.dissipation + prev_d) * period / n;
        }
        prev_p = p;
        prev_d = v.dissipation;
      }
      EXPECT_GT(dissipated, 0.0);
      // Trapezoid error O((T/n)²) of integrands with |δ|^{m3−1}-type kinks at the ends.
      EXPECT_NEAR(work, dissipated, 1e-5 * dissipated) << ToString(law.kind) << " T=" << period;
      if (period < 1e-5) {
        EXPECT_TRUE(clamped) << ToString(law.kind);
      }
    }
  }
}

TEST(ContactLawTest, DissipationNeverNegative) {
  const ContactLaw law = KimContactLaw();
  for (const double d : {1e-8, 1e-6, 1e-5}) {
    for (const double r : {-1e3, -1.0, -1e-3, 0.0, 1e-3, 1.0}) {
      const ContactLawValue v = EvalContactLaw(law, d, r);
      EXPECT_GE(v.dissipation, 0.0) << d << " " << r;
      EXPECT_GE(v.force, 0.0);
    }
  }
}

TEST(ContactLawTest, InvalidLawsAreRejected) {
  std::string why;
  ContactLaw law = KimContactLaw();
  law.stiffness = -1.0;
  EXPECT_FALSE(law.IsValid(&why));
  EXPECT_NE(why.find("stiffness"), std::string::npos);
  law = KimContactLaw();
  law.damping_exponent = 0.5;
  EXPECT_FALSE(law.IsValid(&why));
  EXPECT_NE(why.find("damping_exponent"), std::string::npos);
  law = KimContactLaw();
  law.stiffness_exponent = 0.0;
  EXPECT_FALSE(law.IsValid(&why));
  EXPECT_THROWS_MESSAGE(LinearContactLaw(0.0, 1.0), InvalidInput, "stiffness");
  EXPECT_THROWS_MESSAGE(ContactModulusSameMaterial(2e11, 0.5), InvalidInput, "poisson");
  EXPECT_DOUBLE_EQ(ContactModulusSameMaterial(2e11, 0.3), 2e11 / (2.0 * 0.91));
}

}  // namespace
}  // namespace geardyn
