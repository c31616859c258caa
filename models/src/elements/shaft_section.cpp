// Circular shaft sections, materials and shear coefficients (see shaft_section.hpp).
#include "geardyn/models/elements/shaft_section.hpp"

#include <cmath>

#include "elements/element_checks.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn {
namespace {

void CheckSection(const CircularSection& section) {
  internal::CheckPositive(section.outer_diameter, "outer_diameter", "m");
  internal::CheckNonNegative(section.inner_diameter, "inner_diameter", "m");
  GEARDYN_THROW_UNLESS(section.inner_diameter < section.outer_diameter,
                       "inner_diameter: must be smaller than outer_diameter = "
                           << section.outer_diameter << " m, got " << section.inner_diameter
                           << " m");
}

void CheckPoissonRatio(double poisson_ratio) {
  GEARDYN_THROW_UNLESS(std::isfinite(poisson_ratio) && poisson_ratio > -1.0 && poisson_ratio <= 0.5,
                       "poisson_ratio: must lie in (-1, 0.5], got " << poisson_ratio);
}

}  // namespace

ShaftMaterial ShaftMaterial::FromPoissonRatio(double youngs_modulus, double poisson_ratio,
                                              double density) {
  internal::CheckPositive(youngs_modulus, "youngs_modulus", "Pa");
  CheckPoissonRatio(poisson_ratio);
  internal::CheckPositive(density, "density", "kg/m^3");
  return ShaftMaterial{.youngs_modulus = youngs_modulus,
                       .shear_modulus = youngs_modulus / (2.0 * (1.0 + poisson_ratio)),
                       .density = density};
}

CircularSectionProperties CalcCircularSectionProperties(const CircularSection& section) {
  CheckSection(section);
  const double d_o = section.outer_diameter;
  const double d_i = section.inner_diameter;
  // Factored forms avoid the cancellation of D_o² − D_i² for thin tubes.
  const double diff2 = (d_o - d_i) * (d_o + d_i);  // D_o² − D_i²
  const double diff4 = diff2 * (d_o * d_o + d_i * d_i);
  CircularSectionProperties p;
  p.area = kPi / 4.0 * diff2;
  p.second_moment = kPi / 64.0 * diff4;
  p.polar_moment = kPi / 32.0 * diff4;
  return p;
}

double CalcShearCoefficient(const CircularSection& section, double poisson_ratio,
                            ShearCoefficientFormula formula) {
  CheckSection(section);
  CheckPoissonRatio(poisson_ratio);
  const double nu = poisson_ratio;
  switch (formula) {
    case ShearCoefficientFormula::kCowper: {
      // Cowper (1966), Table 1, hollow circle, m = D_i/D_o.
      const double m = section.inner_diameter / section.outer_diameter;
      const double m2 = m * m;
      const double p = (1.0 + m2) * (1.0 + m2);
      return 6.0 * (1.0 + nu) * p / ((7.0 + 6.0 * nu) * p + (20.0 + 12.0 * nu) * m2);
    }
    case ShearCoefficientFormula::kHutchinson: {
      // Hutchinson (2001), hollow circle, radii a (outer) and b (inner); scaled by a = 1.
      const double b = section.inner_diameter / section.outer_diameter;
      const double b2 = b * b;
      const double b4 = b2 * b2;
      const double s = 1.0 + b2;
      const double numerator = 6.0 * s * s * (1.0 + nu) * (1.0 + nu);
      const double denominator = (7.0 + 34.0 * b2 + 7.0 * b4) +
                                 nu * (12.0 + 48.0 * b2 + 12.0 * b4) +
                                 nu * nu * (4.0 + 16.0 * b2 + 4.0 * b4);
      return numerator / denominator;
    }
  }
  GEARDYN_DEMAND(false);  // every enumerator is handled above
  return 0.0;
}

}  // namespace geardyn
