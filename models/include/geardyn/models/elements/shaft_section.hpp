/// @file
/// @brief Solid or hollow circular shaft sections and shaft materials: area, second and polar
/// moments of area, and the Timoshenko shear coefficient κ (Cowper 1966, Hutchinson 2001).
///
/// **Section properties** (exact for a circular ring of outer/inner diameters D_o, D_i):
/// \f[ A = \tfrac{π}{4}(D_o^2 − D_i^2), \quad I = \tfrac{π}{64}(D_o^4 − D_i^4), \quad
/// J_p = 2I = \tfrac{π}{32}(D_o^4 − D_i^4), \f]
/// where I is the same about every diameter and J_p is also the Saint-Venant torsion constant
/// (no warping for circular sections).
///
/// **Shear coefficient** κ (the shear stiffness is κGA), m = D_i/D_o, ν Poisson's ratio:
/// * Cowper, "The shear coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966)
///   335–340, Table 1, hollow circle:
///   \f[ κ = \frac{6(1+ν)(1+m^2)^2}{(7+6ν)(1+m^2)^2 + (20+12ν)m^2} \f]
///   (solid: 6(1+ν)/(7+6ν); thin tube: 2(1+ν)/(4+3ν)). The default, as in most FE codes.
/// * Hutchinson, "Shear coefficients for Timoshenko beam theory", J. Appl. Mech. 68 (2001)
///   87–92, hollow circle with radii a = D_o/2, b = D_i/2:
///   \f[ κ = \frac{6(a^2+b^2)^2(1+ν)^2}{7a^4+34a^2b^2+7b^4 + ν(12a^4+48a^2b^2+12b^4) +
///   ν^2(4a^4+16a^2b^2+4b^4)} \f]
///   (solid: 6(1+ν)²/(7+12ν+4ν²), the value that best matches exact elastodynamic
///   frequencies of solid circular rods according to Hutchinson and to Stephen's discussion,
///   J. Appl. Mech. 68 (2001) 959).
#pragma once

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief Geometry of a solid (inner_diameter = 0) or hollow circular section.
struct CircularSection {
  double outer_diameter = 0.0;  ///< D_o > 0 [m]
  double inner_diameter = 0.0;  ///< 0 ≤ D_i < D_o [m]; 0 for a solid shaft
};

/// @brief Area and moments of a circular section.
struct CircularSectionProperties {
  double area = 0.0;           ///< A [m²]
  double second_moment = 0.0;  ///< I about any diameter [m⁴]
  double polar_moment = 0.0;   ///< J_p = 2I, polar moment and torsion constant [m⁴]
};

/// @brief Isotropic, linear-elastic shaft material.
struct ShaftMaterial {
  double youngs_modulus = 0.0;  ///< E > 0 [Pa]
  double shear_modulus = 0.0;   ///< G > 0 [Pa]
  double density = 0.0;         ///< ρ > 0 [kg/m³]

  /// @brief Material from E, ν and ρ, with G = E / (2(1 + ν)).
  /// @param[in] youngs_modulus E > 0 [Pa].
  /// @param[in] poisson_ratio ν in (−1, 0.5] [-].
  /// @param[in] density ρ > 0 [kg/m³].
  /// @throws InvalidInput if an argument is out of its range or not finite.
  static ShaftMaterial FromPoissonRatio(double youngs_modulus, double poisson_ratio,
                                        double density);

  /// @brief ν = E/(2G) − 1 [-] (not validated; see CalcShearCoefficient).
  double PoissonRatio() const { return youngs_modulus / (2.0 * shear_modulus) - 1.0; }
};

/// @brief Which published formula gives the shear coefficient κ of a circular section.
enum class ShearCoefficientFormula {
  kCowper,      ///< Cowper (1966), Table 1
  kHutchinson,  ///< Hutchinson (2001)
};

/// @brief A, I and J_p of a circular section (see the @file formulas).
/// @param[in] section D_o > 0, 0 ≤ D_i < D_o [m].
/// @return the section's properties [m², m⁴].
/// @throws InvalidInput naming the diameter if D_o is not positive and finite, D_i is negative
///   or not finite, or D_i ≥ D_o.
CircularSectionProperties CalcCircularSectionProperties(const CircularSection& section);

/// @brief The Timoshenko shear coefficient κ of a circular section.
/// @param[in] section D_o, D_i [m].
/// @param[in] poisson_ratio ν in (−1, 0.5] [-].
/// @param[in] formula kCowper (default) or kHutchinson.
/// @return κ [-] (≈ 0.89 for a solid steel shaft, ≈ 0.53 for a thin steel tube with Cowper).
/// @throws InvalidInput for an invalid section or ν outside (−1, 0.5].
double CalcShearCoefficient(const CircularSection& section, double poisson_ratio,
                            ShearCoefficientFormula formula = ShearCoefficientFormula::kCowper);

}  // namespace geardyn
