/// @file
/// @brief The 6×6 mass matrix of a rigid body (a gear, a planet carrier, a flywheel) in the
/// coordinates q = [t; θ] = [x, y, z, θx, θy, θz] of its reference node (spec 01 §1).
///
/// **Derivation.** Let r be the offset of the centre of mass from the reference node c. For
/// small motions the velocity of the centre of mass is v_G = ṫ + θ̇ × r = ṫ − [r]_× θ̇, and the
/// kinetic energy is T = ½ m |v_G|² + ½ θ̇ᵀ I_G θ̇ (König), so T = ½ q̇ᵀ M q̇ with
/// \f[ M = \begin{bmatrix} m I & −m [r]_× \\ m [r]_× & I_G + m [r]_×ᵀ[r]_× \end{bmatrix},
/// \qquad [r]_×ᵀ[r]_× = |r|² I − r rᵀ, \f]
/// where the lower-right block is the parallel-axis (Huygens–Steiner) inertia about c. With
/// r = 0 (the usual gear: centre of mass on the reference node) M = diag(m, m, m, I_G).
///
/// For an axisymmetric body with unit axis a, polar inertia J about a and diametral inertia
/// I_d about any axis ⟂ a through the centre of mass: I_G = J a aᵀ + I_d (I − a aᵀ).
///
/// The gyroscopic matrix of a spinning body (Ω J [a]_× on the rotations) is not part of the
/// mass matrix; it belongs to the rotor-dynamics terms of the assembly.
#pragma once

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief Inertia data of an axisymmetric rigid body (plain aggregate; validated on use).
struct RigidBodyInertia {
  double mass = 0.0;               ///< m > 0 [kg]
  double polar_inertia = 0.0;      ///< J > 0, about the axis through the centre of mass [kg·m²]
  double diametral_inertia = 0.0;  ///< I_d > 0, about a diameter through the centre of mass [kg·m²]
  Vector3 axis = Vector3::UnitZ();       ///< a, unit vector along the body's axis [-]
  Vector3 com_offset = Vector3::Zero();  ///< r = centre of mass − reference node [m]
};

/// @brief Inertia tensor about the centre of mass of an axisymmetric body,
/// I_G = J a aᵀ + I_d (I − a aᵀ).
/// @param[in] body inertia data (com_offset is not used).
/// @return I_G (3×3) [kg·m²], symmetric positive definite.
/// @throws InvalidInput if J or I_d is not positive and finite or axis is not a unit vector.
Matrix3 CalcAxisymmetricInertiaTensor(const RigidBodyInertia& body);

/// @brief Mass matrix (6×6) of an axisymmetric rigid body about its reference node.
/// @param[in] body m [kg], J, I_d [kg·m²], axis [-], com_offset [m].
/// @return M (6×6) [kg, kg·m, kg·m²], symmetric positive definite (see the @file derivation).
/// @throws InvalidInput naming the field if m, J or I_d is not positive and finite, axis is
///   not a unit vector, or com_offset is not finite.
Matrix6 CalcRigidBodyMassMatrix(const RigidBodyInertia& body);

/// @brief Mass matrix (6×6) of a general rigid body about its reference node.
/// @param[in] mass m > 0 [kg].
/// @param[in] inertia_at_com I_G (3×3), inertia tensor about the centre of mass in inertial
///   axes, symmetric positive definite [kg·m²].
/// @param[in] com_offset r = centre of mass − reference node [m].
/// @return M (6×6) [kg, kg·m, kg·m²].
/// @throws InvalidInput if m is not positive and finite, I_G is not symmetric positive
///   definite, or r is not finite.
Matrix6 CalcRigidBodyMassMatrix(double mass, const Matrix3& inertia_at_com,
                                const Vector3& com_offset);

}  // namespace geardyn
