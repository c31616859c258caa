// Tests of circular shaft sections, materials and shear coefficients (shaft_section.hpp):
// closed-form area and moments, the thin-tube limit, Cowper's and Hutchinson's κ against their
// published special values, and error paths.
#include "geardyn/models/elements/shaft_section.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(ShaftSectionTest, SolidAndHollowPropertiesMatchClosedForms) {
  const CircularSectionProperties solid = CalcCircularSectionProperties({.outer_diameter = 0.04});
  EXPECT_NEAR(solid.area, kPi * 0.04 * 0.04 / 4, 10 * kEps * solid.area);
  EXPECT_NEAR(solid.second_moment, kPi * std::pow(0.04, 4) / 64, 10 * kEps * solid.second_moment);
  EXPECT_DOUBLE_EQ(solid.polar_moment, 2 * solid.second_moment);
  const CircularSectionProperties hollow =
      CalcCircularSectionProperties({.outer_diameter = 0.06, .inner_diameter = 0.045});
  EXPECT_NEAR(hollow.area, kPi * (0.06 * 0.06 - 0.045 * 0.045) / 4, 10 * kEps * hollow.area);
  EXPECT_NEAR(hollow.second_moment, kPi * (std::pow(0.06, 4) - std::pow(0.045, 4)) / 64,
              10 * kEps * hollow.second_moment);
  EXPECT_DOUBLE_EQ(hollow.polar_moment, 2 * hollow.second_moment);
}

TEST(ShaftSectionTest, ThinTubeKeepsFullRelativeAccuracy) {
  // Wall t = 1e-9 D: A = π D_m t and I = π D_m³ t / 8 (D_m mean diameter) to O(t²); the
  // factored formulas keep ~1e-15 relative accuracy where D_o² − D_i² would lose 9 digits.
  const double d_o = 0.1, t = 1e-10, d_i = d_o - 2 * t, d_m = d_o - t;
  const CircularSectionProperties p =
      CalcCircularSectionProperties({.outer_diameter = d_o, .inner_diameter = d_i});
  EXPECT_NEAR(p.area / (kPi * d_m * t), 1.0, 1e-6);  // d_i itself is rounded to ~1e-17/1e-10
  EXPECT_NEAR(p.second_moment / (kPi * d_m * d_m * d_m * t / 8), 1.0, 1e-6);
}

TEST(ShaftSectionTest, CowperCoefficientMatchesItsPublishedSpecialCases) {
  for (double nu : {0.0, 0.25, 0.3, 0.5}) {
    // Solid circle: 6(1+ν)/(7+6ν) (Cowper 1966, Table 1).
    EXPECT_NEAR(CalcShearCoefficient({.outer_diameter = 0.05}, nu), 6 * (1 + nu) / (7 + 6 * nu),
                4 * kEps);
    // Thin-walled round tube (m → 1): 2(1+ν)/(4+3ν) (Cowper 1966, Table 1).
    EXPECT_NEAR(
        CalcShearCoefficient({.outer_diameter = 0.05, .inner_diameter = 0.05 * (1 - 1e-9)}, nu),
        2 * (1 + nu) / (4 + 3 * nu), 1e-8);
  }
  EXPECT_NEAR(CalcShearCoefficient({.outer_diameter = 1.0}, 0.3), 0.886, 5e-4);  // ≈ 0.886
}

TEST(ShaftSectionTest, HutchinsonCoefficientMatchesTheSolidValueAndCowperAtZeroPoisson) {
  for (double nu : {0.0, 0.3, 0.45}) {
    // Solid circle: 6(1+ν)²/(7+12ν+4ν²) (Hutchinson 2001; Stephen's discussion 2001).
    EXPECT_NEAR(
        CalcShearCoefficient({.outer_diameter = 0.05}, nu, ShearCoefficientFormula::kHutchinson),
        6 * (1 + nu) * (1 + nu) / (7 + 12 * nu + 4 * nu * nu), 4 * kEps);
  }
  // At ν = 0 both formulas reduce to 6(1+m²)²/(7(1+m²)² + 20m²) for every hollow section.
  for (double m : {0.0, 0.3, 0.7, 0.95}) {
    const CircularSection s{.outer_diameter = 0.08, .inner_diameter = 0.08 * m};
    EXPECT_NEAR(CalcShearCoefficient(s, 0.0, ShearCoefficientFormula::kHutchinson),
                CalcShearCoefficient(s, 0.0, ShearCoefficientFormula::kCowper), 4 * kEps);
  }
  // κ decreases from the solid shaft to the thin tube.
  const double solid =
      CalcShearCoefficient({.outer_diameter = 0.08}, 0.3, ShearCoefficientFormula::kHutchinson);
  const double tube = CalcShearCoefficient({.outer_diameter = 0.08, .inner_diameter = 0.075}, 0.3,
                                           ShearCoefficientFormula::kHutchinson);
  EXPECT_LT(tube, solid);
}

TEST(ShaftSectionTest, MaterialFromPoissonRatio) {
  const ShaftMaterial steel = ShaftMaterial::FromPoissonRatio(2.1e11, 0.3, 7850.0);
  EXPECT_DOUBLE_EQ(steel.youngs_modulus, 2.1e11);
  EXPECT_NEAR(steel.shear_modulus, 2.1e11 / 2.6, 1e-15 * 2.1e11);
  EXPECT_DOUBLE_EQ(steel.density, 7850.0);
  EXPECT_NEAR(steel.PoissonRatio(), 0.3, 10 * kEps);
}

TEST(ShaftSectionTest, InvalidInputsThrowNamingTheArgument) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROWS_MESSAGE(CalcCircularSectionProperties({.outer_diameter = 0.0}), InvalidInput,
                        "^outer_diameter: must be positive and finite, got 0 m");
  EXPECT_THROWS_MESSAGE(CalcCircularSectionProperties({.outer_diameter = inf}), InvalidInput,
                        "^outer_diameter: .* got inf m");
  EXPECT_THROWS_MESSAGE(
      CalcCircularSectionProperties({.outer_diameter = 0.05, .inner_diameter = nan}), InvalidInput,
      "^inner_diameter: must be non-negative and finite, got nan m");
  EXPECT_THROWS_MESSAGE(
      CalcCircularSectionProperties({.outer_diameter = 0.05, .inner_diameter = 0.07}), InvalidInput,
      "^inner_diameter: must be smaller than outer_diameter = 0.05 m, got 0.07 m");
  EXPECT_THROWS_MESSAGE(CalcShearCoefficient({.outer_diameter = 0.05}, 0.6), InvalidInput,
                        "^poisson_ratio: must lie in \\(-1, 0.5\\], got 0.6");
  EXPECT_THROWS_MESSAGE(CalcShearCoefficient({.outer_diameter = 0.05}, -1.0), InvalidInput,
                        "^poisson_ratio: .* got -1");
  EXPECT_THROWS_MESSAGE(ShaftMaterial::FromPoissonRatio(-2e11, 0.3, 7850.0), InvalidInput,
                        "^youngs_modulus: must be positive and finite, got -2e\\+11 Pa");
  EXPECT_THROWS_MESSAGE(ShaftMaterial::FromPoissonRatio(2e11, nan, 7850.0), InvalidInput,
                        "^poisson_ratio: .* got nan");
  EXPECT_THROWS_MESSAGE(ShaftMaterial::FromPoissonRatio(2e11, 0.3, 0.0), InvalidInput,
                        "^density: must be positive and finite, got 0 kg/m\\^3");
}

}  // namespace
}  // namespace geardyn
