/// @file
/// @brief The tangent (geometric) stiffness of a preloaded involute mesh (issue 19; Cardona &
/// Granville's "second order derivatives of constraints … tangent vibration frequencies"): the
/// second-order term of the exact mesh approach under the static mesh force, to be added to K̄
/// when eigenfrequencies are wanted about the loaded operating point.
///
/// **Derivation** (transverse plane; derived here, proved against the exact involute geometry by
/// mesh_preload_stiffness_test.cpp). The line of action is the common tangent of the two base
/// circles, m·x = h with unit normal m = ±u; the tangency conditions give m·d = const for
/// d = c_j − c_i (the transverse centre offset). An involute meets every tangent of its base
/// circle at right angles, so along that line the transverse approach of the two flanks is
/// \f[ δ_t(d, φ_i, φ_j) = −d·n(ψ) + Kψ + a_i φ_i ∓ a_j φ_j + \text{const},\quad n = v, \f]
/// ψ the angle of m, K a constant. Since ∂n/∂ψ = −m, d·m is constant, and the involute makes the
/// gradient ∂δ_t/∂d exactly −n (B–S's first-order η row), K = −d·m and, with dψ = −m·dd / (n·d),
/// \f[ \frac{∂^2 δ_t}{∂d\,∂d} = −\frac{m m^T}{L_s},\qquad L_s = (c_j − c_i)·v = (T_j − T_i)·v, \f]
/// L_s the signed length of the line of action between the tangent points T_i = c_i + a_i u and
/// T_j (mesh_frame.hpp): +C sin φ external (the mesh force acts like a compressed strut between
/// the base circles: the relative shift of the centres across the line turns the force, −F/L as
/// for a column), −C sin φ internal (T_j lies behind T_i: the turn stiffens, +F/L). The rotations
/// enter δ_t linearly (the involute's base-circle rolling), so they have no second-order term, and
/// a rack (L → ∞, its flank plane keeps its direction) has none at all.
///
/// **The matrix.** A helical mesh's normal approach is δ_η = cos ψ_b δ_t + (axial terms, linear),
/// so the static normal force F̄_η [N] (> 0 compression) contributes the energy ½ F̄_η qᵀ ∇²δ_η q:
/// \f[ K_g = κ\, b b^T,\quad κ = −\frac{F̄_η \cos ψ_b}{L_s},\quad
///     b = [−u;\ 0;\ u;\ 0] \ (\text{12 coordinates } [t_i, θ_i, t_j, θ_j]). \f]
/// K_g is symmetric, of rank one, negative semi-definite for an external mesh under compression
/// (every eigenvalue of K̄ + K_g at most that of K̄) and positive semi-definite for an internal one;
/// it leaves the pair's rigid translations and rotations about the axis without energy (b acts on
/// the relative translation only).
///
/// **Not included.** The second-order terms of the tilts (θx, θy) and of the axial shift of a
/// helical pair: a tilt turns the contact lines, a second-order effect of size F̄_η times a lever
/// arm against tilt supports of 10⁶–10⁸ N·m/rad (≤ 10⁻³ relative in the built-in scenes'
/// numbers); and the change of the load's own point of application along the path of contact (the
/// mean force is taken at the reference point, as K̄ is).
#pragma once

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"

namespace geardyn {

/// @brief κ [N/m] of the @file: −F̄_η cos ψ_b / L_s, 0 for a rack.
/// @param[in] frame the mesh frame (centres, v, ψ_b, internal/rack flags).
/// @param[in] normal_force F̄_η [N], the static mesh force (> 0 compresses the teeth).
/// @throws InvalidInput on a non-finite force.
double CalcMeshPreloadCoefficient(const MeshFrame& frame, double normal_force);

/// @brief K_g = κ b bᵀ (12×12) on [q_i; q_j] [N/m] (see the @file).
/// @throws InvalidInput as CalcMeshPreloadCoefficient.
Matrix12 CalcMeshPreloadStiffness(const MeshFrame& frame, double normal_force);

}  // namespace geardyn
