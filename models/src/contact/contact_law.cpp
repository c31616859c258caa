// Normal contact force laws (contact_law.hpp): Kim Eq. (12), linear, Johnson line contact.
#include "geardyn/models/contact/contact_law.hpp"

#include <gsl/gsl_sf_lambert.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "geardyn/common/check.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kE = std::numbers::e;

struct Elastic {
  double force = 0.0;   // f_e [N]
  double slope = 0.0;   // df_e/dδ [N/m]
  double energy = 0.0;  // ∫₀^δ f_e [J]
};

Elastic PowerLaw(double k, double m1, double gap) {
  const double p = std::pow(gap, m1);
  return {k * p, k * m1 * p / gap, k * p * gap / (m1 + 1.0)};
}

// Johnson's line contact δ = A F (ln(B/F) − 1) inverted with W₋₁ (contact_law.hpp), continued
// linearly beyond v = 2.
Elastic LineLaw(double modulus, const LineContactGeometry& g, double gap) {
  const double a = 1.0 / (kPi * g.length * modulus);
  const double b = 4.0 * kPi * g.length * modulus * (g.radius1 + g.radius2);
  const double d = gap / (a * b);
  const double d_lim = 2.0 * std::exp(-3.0);
  if (d <= d_lim) {
    const double v = -gsl_sf_lambert_Wm1(-kE * d);  // v ≥ 2 here
    const double f = b * std::exp(-1.0 - v);
    return {f, 1.0 / (a * (v - 1.0)), 0.5 * a * f * f * (v - 0.5)};
  }
  const double f_lim = b * std::exp(-3.0);
  const double gap_lim = 2.0 * a * f_lim;
  const double e_lim = 0.75 * a * f_lim * f_lim;
  const double s = gap - gap_lim;
  return {f_lim + s / a, 1.0 / a, e_lim + f_lim * s + 0.5 * s * s / a};
}

}  // namespace

const char* ToString(ContactLawKind kind) {
  switch (kind) {
    case ContactLawKind::kKim:
      return "kim";
    case ContactLawKind::kLinear:
      return "linear";
    case ContactLawKind::kLine:
      return "line";
  }
  return "kim";
}

bool ContactLaw::IsValid(std::string* why) const {
  std::ostringstream s;
  const auto fail = [&](const char* field, double value, const char* bound) {
    s << field << ": must be " << bound << ", got " << value;
    if (why != nullptr) *why = s.str();
    return false;
  };
  const auto finite = [](double v) { return std::isfinite(v); };
  if (kind != ContactLawKind::kLine && !(finite(stiffness) && stiffness > 0.0)) {
    return fail("stiffness", stiffness, "finite and > 0 [N/m^m1]");
  }
  if (kind == ContactLawKind::kLine && !(finite(contact_modulus) && contact_modulus > 0.0)) {
    return fail("contact_modulus", contact_modulus, "finite and > 0 [Pa]");
  }
  if (!(finite(stiffness_exponent) && stiffness_exponent > 0.0)) {
    return fail("stiffness_exponent", stiffness_exponent, "finite and > 0");
  }
  if (!(finite(damping) && damping >= 0.0)) return fail("damping", damping, "finite and >= 0");
  if (!(finite(damping_exponent) && damping_exponent >= 1.0)) {
    return fail("damping_exponent", damping_exponent,
                "finite and >= 1 (below 1 the damping force has an unbounded derivative at "
                "zero penetration rate)");
  }
  if (!(finite(indentation_exponent) && indentation_exponent >= 0.0)) {
    return fail("indentation_exponent", indentation_exponent, "finite and >= 0");
  }
  if (kind == ContactLawKind::kLinear &&
      (stiffness_exponent != 1.0 || damping_exponent != 1.0 || indentation_exponent != 0.0)) {
    return fail("stiffness_exponent", stiffness_exponent,
                "1 with damping_exponent 1 and indentation_exponent 0 for the linear law");
  }
  return true;
}

ContactLaw KimContactLaw() {
  ContactLaw law;
  law.kind = ContactLawKind::kKim;
  // Table 2: k = 39.3e6 N/mm^1.5 → ·1000^1.5; c = 1.0 N·s/mm^(m2+m3) → ·1000^1.25.
  law.stiffness = 39.3e6 * std::pow(1000.0, 1.5);
  law.stiffness_exponent = 1.5;
  law.damping = 1.0 * std::pow(1000.0, 1.25);
  law.damping_exponent = 1.0;
  law.indentation_exponent = 0.25;
  return law;
}

ContactLaw LinearContactLaw(double stiffness, double damping) {
  ContactLaw law;
  law.kind = ContactLawKind::kLinear;
  law.stiffness = stiffness;
  law.damping = damping;
  std::string why;
  GEARDYN_THROW_UNLESS(law.IsValid(&why), why);
  return law;
}

double ContactModulusSameMaterial(double young_modulus, double poisson) {
  GEARDYN_THROW_UNLESS(std::isfinite(young_modulus) && young_modulus > 0.0,
                       "young_modulus: must be finite and > 0 [Pa], got " << young_modulus);
  GEARDYN_THROW_UNLESS(poisson >= 0.0 && poisson < 0.5,
                       "poisson: must be in [0, 0.5), got " << poisson);
  return young_modulus / (2.0 * (1.0 - poisson * poisson));
}

ContactLawValue EvalContactLaw(const ContactLaw& law, double gap, double gap_rate,
                               const LineContactGeometry& line) {
  ContactLawValue out;
  if (!std::isfinite(gap) || !std::isfinite(gap_rate)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan, nan, false};
  }
  if (gap <= 0.0) return out;
  const Elastic e = law.kind == ContactLawKind::kLine
                        ? LineLaw(law.contact_modulus, line, gap)
                        : PowerLaw(law.stiffness, law.stiffness_exponent, gap);
  // f_d = c sign(δ̇)|δ̇|^m2 δ^m3.
  const double m2 = law.damping_exponent;
  const double m3 = law.indentation_exponent;
  const double rate_abs = std::abs(gap_rate);
  const double rate_pow = std::pow(rate_abs, m2);  // |δ̇|^m2
  const double gap_pow = std::pow(gap, m3);        // δ^m3
  const double sign = gap_rate > 0.0 ? 1.0 : (gap_rate < 0.0 ? -1.0 : 0.0);
  const double f_d = law.damping * sign * rate_pow * gap_pow;
  out.energy = e.energy;
  const double f = e.force + f_d;
  if (f < 0.0) {  // no adhesion: the spring's release is lost while separating
    out.clamped = true;
    out.dissipation = -e.force * gap_rate;
    return out;
  }
  out.force = f;
  out.d_force_d_gap = e.slope + (m3 == 0.0 ? 0.0 : f_d * m3 / gap);
  // ∂/∂δ̇ of sign(δ̇)|δ̇|^m2 = m2 |δ̇|^(m2−1) (m2 ≥ 1; 1 at δ̇ = 0 when m2 = 1).
  const double d_rate = m2 == 1.0 ? 1.0 : m2 * std::pow(rate_abs, m2 - 1.0);
  out.d_force_d_rate = law.damping * d_rate * gap_pow;
  out.dissipation = f_d * gap_rate;
  return out;
}

double LineContactApproach(double force, double contact_modulus, const LineContactGeometry& line) {
  if (force <= 0.0) return 0.0;
  const double a = 1.0 / (kPi * line.length * contact_modulus);
  const double b = 4.0 * kPi * line.length * contact_modulus * (line.radius1 + line.radius2);
  return a * force * (std::log(b / force) - 1.0);
}

}  // namespace geardyn
