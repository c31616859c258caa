// Input checks shared by the element library (models/elements): each throws InvalidInput whose
// message names the argument, its value, its unit and the bound (architecture §3.7).
#pragma once

#include <string_view>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn::internal {

/// Relative tolerance on |‖axis‖ − 1| for an argument documented as a unit vector.
inline constexpr double kUnitAxisTolerance = 1e-9;

/// Throws unless `value` is finite and > 0.
void CheckPositive(double value, std::string_view name, std::string_view unit);

/// Throws unless `value` is finite and ≥ 0.
void CheckNonNegative(double value, std::string_view name, std::string_view unit);

/// Throws unless every component of `v` is finite.
void CheckFinite(const Vector3& v, std::string_view name, std::string_view unit);

/// Throws unless `axis` is finite and |‖axis‖ − 1| ≤ kUnitAxisTolerance.
void CheckUnitAxis(const Vector3& axis, std::string_view name);

/// Throws unless `matrix` is finite, symmetric (to 1e-12 relative) and positive semi-definite
/// (`definite` = false) or positive definite (`definite` = true). The definiteness test is made
/// on the Jacobi-scaled matrix D^{-1/2} A D^{-1/2} (D = its positive diagonal), so it does not
/// depend on the units of the rows (N/m next to N·m/rad).
void CheckSymmetricSemiDefinite(const Matrix3& matrix, bool definite, std::string_view name,
                                std::string_view unit);
void CheckSymmetricSemiDefinite(const Matrix6& matrix, bool definite, std::string_view name,
                                std::string_view unit);

}  // namespace geardyn::internal
