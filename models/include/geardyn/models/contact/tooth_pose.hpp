/// @file
/// @brief The effective base circle of a deflected tooth: the exact map from a gear's planar pose
/// and a tooth's rigid-body deflection (rotation about its root pivot, translation of a bushing)
/// to the pose of the base circle whose involutes are the deflected tooth's flanks (spec 03).
///
/// A tooth is a rigid body. Rotating it by ψ about the pivot p and translating it by τ moves
/// every point x to p + R(ψ)(x − p) + τ; an involute of the base circle (c, r_b) leaving it at
/// β becomes the involute of the MOVED circle (c′, r_b) leaving it at β + ψ. So a deflected
/// flank is still exact involute, of
/// \f[ c′ = p + R(ψ)(c − p) + τ = c + (r_p + τ_r)\,e(a) − r_p\,e(a + ψ) + τ_t\,e′(a),
///     \qquad φ′ = φ + ψ, \f]
/// with the pivot p = c + r_p e(a) on the tooth's centre line a = φ + γ_body (world angle),
/// r_p the pivot radius and τ = τ_r e(a) + τ_t e′(a) given in the tooth's undeflected radial /
/// tangential axes (Kim's type B bushing; type A has τ = 0, rigid teeth ψ = 0 as well).
/// The flank poses of the deflected tooth follow from MakeFlankPose(geometry, c′, φ′ + γ_body, ε).
#pragma once

#include <Eigen/Core>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief Rigid-body deflection of one tooth relative to its gear (spec 03 type A / type B).
struct ToothDeflection {
  double rotation = 0.0;    ///< ψ, rotation about the root pivot, counter-clockwise [rad]
  double radial = 0.0;      ///< τ_r, translation along the undeflected centre line [m]
  double tangential = 0.0;  ///< τ_t, translation along e′(a) (counter-clockwise) [m]
};

/// @brief The effective base circle of a tooth and its derivatives.
struct EffectiveBaseCircle {
  Vector2 center = Vector2::Zero();  ///< c′ [m]
  double angle = 0.0;                ///< φ′ = φ + ψ, the tooth body's angle [rad]
  /// ∂(c′x, c′y, φ′)/∂(cx, cy, φ, ψ, τ_r, τ_t) (3×6) [-, m, rad/m …], in closed form.
  Eigen::Matrix<double, 3, 6> jacobian = Eigen::Matrix<double, 3, 6>::Zero();
};

/// @brief The exact map of the @file from (gear centre, gear angle, tooth, deflection) to c′, φ′.
/// @param[in] gear_center c, centre of the gear's base circle [m].
/// @param[in] gear_angle φ, the gear's rotation (counter-clockwise) [rad].
/// @param[in] tooth_angle γ_body, the tooth's centre line in the gear's body frame [rad].
/// @param[in] pivot_radius r_p ≥ 0, radius of the root pivot on the centre line [m].
/// @param[in] deflection ψ [rad], τ_r, τ_t [m].
EffectiveBaseCircle CalcEffectiveBaseCircle(const Vector2& gear_center, double gear_angle,
                                            double tooth_angle, double pivot_radius,
                                            const ToothDeflection& deflection);

}  // namespace geardyn
