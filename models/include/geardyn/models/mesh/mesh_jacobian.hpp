/// @file
/// @brief The 2×12 mesh Jacobian G of spec 01 §3, [δ_η, δ_ζ]ᵀ = G q_pair, and B–S's scaled
/// relative-displacement map (B–S Eqs. 22, 24, 41d) that K_o of Eq. (41b) acts on.
///
/// q_pair = [q_i; q_j] (12) with q = [x, y, z, θx, θy, θz] of each body's centre in inertial
/// axes [m, rad]; i is the pinion (driver), j the gear.
///
/// **Sign convention** (derived from the geometry of mesh_frame.hpp): η is the outward normal of
/// the pinion's flank at the contact (the pinion pushes the gear along +η for either drive
/// direction, because η's transverse part v flips with the drive sign). The displacement of the
/// pinion's material point at p0 along η is η·t_i + θ_i·(r_i × η), the gear's η·t_j +
/// θ_j·(r_j × η); their difference
/// \f[ δ_η = η·(t_i − t_j) + θ_i·(r_i × η) − θ_j·(r_j × η) \f]
/// is therefore positive for **approach** (tooth compression) and the energy ½K δ_η² gives the
/// force +K δ_η η on the gear. The relative twist about ζ = u is δ_ζ = ζ·(θ_i − θ_j); a contact
/// point at σ along σ̂ = ζ × η approaches by δ_η − σ δ_ζ, because (σ σ̂ × η) = −σ ζ (spec 01 §3).
/// The conjugate rotation that loads nothing is a_i θ_iz = −a_j θ_jz (external) and
/// a_i θ_iz = +a_j θ_jz (internal): δ_η's torsional part is s cos ψ (a_i θ_iz ± a_j θ_jz).
#pragma once

#include <Eigen/Core>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"

namespace geardyn {

/// 6×12 map from a pair's coordinates to B–S's scaled relative displacements.
using Matrix6x12 = Eigen::Matrix<double, 6, 12>;

/// @brief The mesh Jacobian G (2×12) of spec 01 §3.
///
/// Row 0 (δ_η, [m]): [ηᵀ, (r_i × η)ᵀ, −ηᵀ, −(r_j × η)ᵀ]; row 1 (δ_ζ, [rad]): [0, ζᵀ, 0, −ζᵀ].
/// @param[in] frame mesh frame from CalcMeshFrame (η, ζ [-], r_i, r_j [m]).
/// @return G (2×12) [-, m]: δ = G q_pair with δ_η [m] positive for approach, δ_ζ [rad].
Matrix2x12 CalcMeshJacobian(const MeshFrame& frame);

/// @brief B–S's scaled relative displacement δ_BS = T q_pair (6×12) in the mesh frame, in the
/// row order (u, v, w, bθ_u, aθ_v, aθ_w) of K_o (B–S Eqs. 22, 24, 41d, D = diag(1,1,1,b,a,a)).
///
/// With t = t_i − t_j, s = drive_sign = det W and ε = +1 external, −1 internal (the ⊕ of B–S
/// Eq. 22):
/// \f[ δ_{BS} = [u·t,\; v·t,\; w·t,\; −b\,u·(θ_i − θ_j),\; s(a_i v·θ_i + ε a_j v·θ_j),\;
///               s(a_i w·θ_i + ε a_j w·θ_j)]ᵀ \f]
/// The factor s makes the rotation entries pseudo-vector components (positive in the drive
/// direction), and the 4th entry is −b δ_ζ because B–S write the approach along a contact line
/// as δ_η + σ δ_ζ (B–S Eq. 17) where spec 01 §3 writes δ_η − σ δ_ζ. With these, B–S's sign
/// pattern g = (0, c, s, κ, −s, c) of Eq. (41b) holds unchanged (see stiffness_core.hpp,
/// CalcBsDeflectionProjection).
///
/// B–S measure the moment arms by their projection on u (a_p = (R_p − R_G)·u, B–S Eq. 25), so
/// P T equals G exactly only when ψ_b = 0 and p0 lies in the centres' plane: for helical gears
/// G's δ_η row has in addition s sin ψ ((r_i·v) u·θ_i − (r_j·v) u·θ_j) − s cos ψ ((r_i·w) u·θ_i −
/// (r_j·w) u·θ_j), the moment about u of the axial force component acting at the pitch point
/// (arm a tan φ along v) and of the transverse component acting at an axial offset.
/// @param[in] frame mesh frame [m, -].
/// @param[in] half_face_width b > 0 [m].
/// @return T (6×12) [-, m].
/// @throws InvalidInput when half_face_width is not positive and finite.
Matrix6x12 CalcBsRelativeDisplacementMap(const MeshFrame& frame, double half_face_width);

/// @brief B–S's projected-arm mesh Jacobian G_BS = P T (2×12): [δ_η, δ_ζ]ᵀ as B–S's
/// K_o (Eq. 41b) sees them, T = CalcBsRelativeDisplacementMap(frame, b) and
/// P = CalcBsDeflectionProjection(cos ψ, sin ψ, b) with ψ = frame.signed_helix_angle
/// (stiffness_core.hpp), so that (P T)ᵀ K2 (P T) = Tᵀ K_o T.
///
/// Row 1 (δ_ζ) equals G's. Row 0 differs from G's by the θ_u terms above (with s = drive_sign):
/// G − G_BS has row 0 = s (sin ψ r_i·v − cos ψ r_i·w) uᵀ on θ_i and
/// −s (sin ψ r_j·v − cos ψ r_j·w) uᵀ on θ_j, zero for ψ = 0 with p0 in the centres' plane.
/// Rigid motions: G annihilates every rigid motion of the pair, so G_BS q = −(G − G_BS) q, which
/// for a common rotation ω (about any point) is −s (sin ψ C·v − cos ψ C·w) u·ω with
/// C = c_j − c_i. G_BS therefore annihilates common translations, the conjugate rotation and
/// every common rotation with u·ω = 0 (about Z or v, through any point), but for a helical pair
/// not a common rotation about u: its load −s sin ψ (C·v) ω_u (C·w = 0 for centres in one
/// transverse plane) is the moment error of B–S's projected arms.
/// @param[in] frame mesh frame [m, -].
/// @param[in] half_face_width b > 0 [m] (cancels in P T; validated as by the two factors).
/// @return G_BS (2×12) [-, m].
/// @throws InvalidInput when half_face_width is not positive and finite.
Matrix2x12 CalcBsProjectedJacobian(const MeshFrame& frame, double half_face_width);

}  // namespace geardyn
