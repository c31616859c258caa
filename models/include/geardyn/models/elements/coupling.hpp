/// @file
/// @brief Torsional couplings: a torsional spring (or damper) on the relative rotation of two
/// nodes about an axis, and a torsional spring from one node to ground.
///
/// With unit axis a and node coordinates q = [t; θ] (spec 01 §1), the coupling's twist is
/// \f[ δ = a·(θ_A − θ_B) = g [q_A; q_B], \qquad g = [0,\, aᵀ,\, 0,\, −aᵀ] \; (1×12), \f]
/// its energy ½ k δ², hence the element matrix k gᵀg: rank 1, symmetric PSD, acting on the
/// rotations only (a torsionally flexible, laterally and axially free coupling such as a
/// flexible disc or jaw coupling in a torsional model). The torque on A about a is −k δ, on B
/// +k δ. Grounded: δ = a·θ_A and the 6×6 matrix k [0 0; 0 a aᵀ].
///
/// The same matrices with k replaced by the damping coefficient c [N·m·s/rad] are the damping
/// matrices. A coupling that also transmits bending or shear is a bearing between the two
/// bodies (bearing.hpp).
#pragma once

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief k gᵀg (12×12) of a torsional coupling between nodes A and B about `axis`.
/// @param[in] coefficient k ≥ 0 [N·m/rad] (or c ≥ 0 [N·m·s/rad]).
/// @param[in] axis a, unit vector [-].
/// @return the matrix on [q_A; q_B] [N·m/rad].
/// @throws InvalidInput if the coefficient is negative or not finite, or axis is not a unit
///   vector.
Matrix12 CalcTorsionalCouplingMatrix(double coefficient, const Vector3& axis);

/// @brief The 6×6 matrix of a torsional spring (or damper) from a node to ground about `axis`.
/// @param[in] coefficient k ≥ 0 [N·m/rad] (or c ≥ 0 [N·m·s/rad]).
/// @param[in] axis a, unit vector [-].
/// @return k [0 0; 0 a aᵀ] on q_A [N·m/rad].
/// @throws InvalidInput as CalcTorsionalCouplingMatrix.
Matrix6 CalcGroundedTorsionalSpringMatrix(double coefficient, const Vector3& axis);

}  // namespace geardyn
