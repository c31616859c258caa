/// @file
/// @brief Bearings: a 6×6 stiffness (or damping) K_b acting at a point p on the relative motion
/// of a body and ground, or of two bodies, mapped to the bodies' reference-node coordinates.
///
/// **Relative displacement at the bearing.** With the rigid-transfer map of rigid_transfer.hpp,
/// the bearing deflection is
/// \f[ δ = \begin{bmatrix} (t_A + θ_A × (p − c_A)) − (t_B + θ_B × (p − c_B)) \\ θ_A − θ_B
/// \end{bmatrix} = T \begin{bmatrix} q_A \\ q_B \end{bmatrix} \f]
/// (B absent for a bearing to ground). The energy ½ δᵀ K_b δ gives the 12×12 (or 6×6) element
/// matrix TᵀK_bT. The same map serves the damping C_b (dissipation ½ δ̇ᵀ C_b δ̇).
///
/// **Sign of the forces.** K = TᵀK_bT is the stiffness: the bearing's elastic generalized force
/// on the bodies is −K q. For a pure translation t of A (and K_b without translation/rotation
/// coupling) this is −K_b t on A at p, i.e. the force −K_b t and the moment (p − c_A) × (−K_b t)
/// about c_A, and the opposite on B.
///
/// **A planet on its carrier.** Take A = the planet (c_A its centre), B = the carrier (c_B its
/// centre) and p = the pin's centre: the carrier-side point then moves with the carrier's
/// translation and rotation, t_B + θ_B × (p − c_B). In an epicyclic drive p rotates with the
/// carrier's nominal angle, so K is evaluated at the current p (its θ*-dependence is the
/// caller's).
///
/// K_b is given in inertial axes, in the row order [x, y, z, θx, θy, θz] of the relative
/// displacement [N/m, N/rad; N·m/m, N·m/rad]. CalcDiagonalBearingMatrix and
/// CalcAxisymmetricBearingMatrix build the common special cases.
#pragma once

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief K_b = diag(k) for a bearing whose six directions are uncoupled in inertial axes.
/// @param[in] diagonal [k_x, k_y, k_z, k_θx, k_θy, k_θz] ≥ 0 [N/m, N·m/rad] (or damping
///   [N·s/m, N·m·s/rad]).
/// @return K_b (6×6).
/// @throws InvalidInput if an entry is negative or not finite.
Matrix6 CalcDiagonalBearingMatrix(const Vector6& diagonal);

/// @brief K_b of a rolling/journal bearing that is isotropic about its axis a:
/// \f[ K_b = \begin{bmatrix} k_r (I − a aᵀ) + k_a a aᵀ & 0 \\ 0 & k_{tilt} (I − a aᵀ) +
/// k_{tor} a aᵀ \end{bmatrix} \f]
/// @param[in] radial k_r ≥ 0 [N/m] (per radial direction).
/// @param[in] axial k_a ≥ 0 [N/m].
/// @param[in] tilt k_tilt ≥ 0 [N·m/rad] (per tilt direction).
/// @param[in] torsional k_tor ≥ 0 [N·m/rad] (usually 0: a bearing does not hold the rotation).
/// @param[in] axis a, unit vector along the bearing's axis [-].
/// @return K_b (6×6), symmetric PSD.
/// @throws InvalidInput if a coefficient is negative or not finite, or axis is not a unit
///   vector.
Matrix6 CalcAxisymmetricBearingMatrix(double radial, double axial, double tilt, double torsional,
                                      const Vector3& axis);

/// @brief TᵀK_bT (6×6) of a bearing between body A and ground at point p.
/// @param[in] coefficients K_b (6×6) in inertial axes, symmetric PSD [N/m, N·m/rad] (or the
///   damping C_b [N·s/m, N·m·s/rad]).
/// @param[in] point p, where the bearing acts [m].
/// @param[in] center c_A, the body's reference node [m].
/// @return the body's 6×6 stiffness (or damping) [N/m, N/rad, N·m/rad] on q_A.
/// @throws InvalidInput if K_b is not finite, symmetric and PSD, or a point is not finite.
Matrix6 CalcGroundedBearingMatrix(const Matrix6& coefficients, const Vector3& point,
                                  const Vector3& center);

/// @brief TᵀK_bT (12×12) of a bearing between bodies A and B acting at point p.
/// @param[in] coefficients K_b (6×6) in inertial axes, symmetric PSD (or C_b).
/// @param[in] point p, where the bearing acts [m].
/// @param[in] center_a c_A, reference node of body A [m].
/// @param[in] center_b c_B, reference node of body B [m].
/// @return the 12×12 stiffness (or damping) on [q_A; q_B]; it is symmetric PSD and vanishes
///   on every common rigid motion of A and B.
/// @throws InvalidInput if K_b is not finite, symmetric and PSD, or a point is not finite.
Matrix12 CalcBearingMatrix(const Matrix6& coefficients, const Vector3& point,
                           const Vector3& center_a, const Vector3& center_b);

}  // namespace geardyn
