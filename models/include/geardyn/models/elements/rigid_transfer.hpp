/// @file
/// @brief The rigid-transfer map: the small displacement of a material point of a rigid body
/// (or the relative displacement of two bodies at a common point) from the bodies' 6-DOF
/// reference-node coordinates.
///
/// Convention (spec 01 §1): a body's coordinates q = [t; θ] = [x, y, z, θx, θy, θz] are the
/// small translation [m] and rotation [rad] of its reference node c, in axes parallel to the
/// inertial ones. The material point of the body at p moves by
/// \f[ u_p = t + θ × (p − c) = t − [r]_× θ, \qquad r = p − c, \f]
/// and rotates by θ. [r]_× is the cross-product matrix ([r]_× v = r × v). Every element that
/// acts away from its bodies' reference nodes (bearings on a carrier pin, a gear whose bore sits
/// on a shaft node) uses this map, and by virtual work the force f and moment m applied at p
/// act on the body as the generalized force Tᵀ [f; m] = [f; m + r × f].
#pragma once

#include <Eigen/Core>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// 6×12 map from a pair's coordinates [q_A; q_B] to a 6-vector (same type as in
/// mesh/mesh_jacobian.hpp; redeclaring an alias to the same type is allowed).
using Matrix6x12 = Eigen::Matrix<double, 6, 12>;

/// @brief The cross-product matrix [v]_×, with [v]_× w = v × w.
/// @param[in] v any 3-vector.
/// @return the skew-symmetric 3×3 matrix [[0, −v_z, v_y], [v_z, 0, −v_x], [−v_y, v_x, 0]].
Matrix3 CalcCrossProductMatrix(const Vector3& v);

/// @brief Rigid-transfer map of one body: [u_p; θ] = T q.
///
/// \f[ T = \begin{bmatrix} I & −[p − c]_× \\ 0 & I \end{bmatrix} \f]
/// @param[in] point p, the material point [m] (inertial axes).
/// @param[in] center c, the body's reference node [m].
/// @return T (6×6) [-, m].
/// @throws InvalidInput if point or center is not finite.
Matrix6 CalcRigidTransferMap(const Vector3& point, const Vector3& center);

/// @brief Relative rigid-transfer map of two bodies at a common point p:
/// [u_p^A − u_p^B; θ_A − θ_B] = T [q_A; q_B].
///
/// \f[ T = \begin{bmatrix} I & −[p − c_A]_× & −I & [p − c_B]_× \\ 0 & I & 0 & −I
/// \end{bmatrix} \f]
/// A common rigid motion of A and B (same small translation and rotation of the pair about any
/// point) is mapped to zero.
/// @param[in] point p [m].
/// @param[in] center_a c_A, reference node of body A [m].
/// @param[in] center_b c_B, reference node of body B [m].
/// @return T (6×12) [-, m].
/// @throws InvalidInput if a point is not finite.
Matrix6x12 CalcRelativeTransferMap(const Vector3& point, const Vector3& center_a,
                                   const Vector3& center_b);

}  // namespace geardyn
