/// @file
/// @brief The linear (B–S) mesh algebra of spec 01 §3 and §5: the 2×2 stiffness core K2 on the
/// mesh deflections [δ_η, δ_ζ], the 12×12 mesh stiffness Gᵀ K2 G, damping Gᵀ C2 G and load
/// Gᵀ K2 ε, the transmission-error pair ε, B–S's 6×6 K_o (B–S Eq. 41b) with its 6-vector
/// transmission error (Eqs. 41c, 42), and the reduced cores of the model hierarchy.
///
/// Everything follows from the mesh energy (spec 01 §3)
/// \f[ U = ½ ∫ k (δ_η − σ δ_ζ − e)² dℓ = ½ δᵀ K2 δ − δᵀ K2 ε + const, \f]
/// with K = ∫k dℓ, h = ∫kσ dℓ / K, κ = h/b, μ = ∫kσ² dℓ / (K b²), K2 = K [[1, −h], [−h, μb²]]
/// and ε = K2⁻¹ [∫ke dℓ, −∫kσe dℓ]ᵀ; δ = G q_pair (mesh_jacobian.hpp). The generalized force on
/// the pair is −∂U/∂q = −Gᵀ K2 G q + Gᵀ K2 ε.
///
/// **Model levels** (spec 01 §5) differ only in the core; G is the same:
/// * kBlankenshipSingh — K2 above (five coupled DOF, B–S Eq. 41).
/// * kCoupling4Dof — κ = 0 and the μ term dropped: K2 = K diag(1, 0), K_mesh = K Gηᵀ Gη, rank 1
///   (Kiyono et al. 1978, Küçükay 1984).
/// * kTorsional — the same core on the torsional restriction of G (translations and tilts held
///   by rigid supports; only θz columns kept): k on the transverse coordinate
///   x = s(a_i θ_iz ± a_j θ_jz) with k = K cos²ψ_b (Kahraman & Singh 1990), see TorsionalCore.
///
/// The per-mesh kernels use fixed sizes only and do not allocate.
#pragma once

#include <Eigen/Core>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn {

/// 2×6 map from B–S's 6 scaled relative displacements to [δ_η, δ_ζ].
using Matrix2x6 = Eigen::Matrix<double, 2, 6>;

/// Round-off slack in the PSD condition μ ≥ κ² of the core (relative to κ²) [-]: μ computed as
/// κ² + F²/(12 b²) with F → 0 may fall below κ² by a few ulps.
inline constexpr double kCoreRoundoffTol = 64.0 * 2.220446049250313e-16;

/// @brief The B–S stiffness core K2 = K [[1, −h], [−h, μ b²]] (spec 01 §3; B–S Eqs. 18, 19, 26b).
/// @param[in] K mesh stiffness ∫k dℓ ≥ 0 [N/m] (0 when out of contact).
/// @param[in] h load centre along σ, ∫kσ dℓ / K [m].
/// @param[in] mu rotational coupling μ = ∫kσ² dℓ / (K b²) ≥ κ² = (h/b)² [-].
/// @param[in] half_face_width b > 0 [m].
/// @return K2 (2×2) [N/m, N, N·m], symmetric PSD, rank 2 when μ > κ².
/// @throws InvalidInput naming K, h, mu or half_face_width (non-finite, K < 0, b ≤ 0, μ < κ²).
Matrix2 CalcStiffnessCore(double K, double h, double mu, double half_face_width);

/// @brief The mesh stiffness K_mesh = Gᵀ K2 G (12×12) in q_pair = [q_i; q_j] (spec 01 §3).
///
/// Hot kernel: no validation, no allocation; the result is exactly symmetric (upper triangle
/// mirrored).
/// @param[in] G mesh Jacobian (2×12) [-, m].
/// @param[in] K2 any symmetric 2×2 core [N/m, N, N·m] (a stiffness core, or a damping core C2).
/// @return Gᵀ K2 G (12×12) [N/m, N, N·m] (or [N·s/m, …] for a damping core).
Matrix12 CalcMeshStiffness(const Matrix2x12& G, const Matrix2& K2);

/// @brief The mesh load f_mesh = Gᵀ K2 ε (12) on q_pair (spec 01 §3).
/// @param[in] G mesh Jacobian (2×12) [-, m].
/// @param[in] K2 stiffness core (2×2) [N/m, N, N·m].
/// @param[in] epsilon transmission-error pair [ε_η [m], ε_ζ [rad]].
/// @return generalized force (12) [N, N·m].
Vector12 CalcMeshLoad(const Matrix2x12& G, const Matrix2& K2, const Vector2& epsilon);

/// @brief The transmission-error pair ε = K2⁻¹ [∫ke dℓ, −∫kσe dℓ]ᵀ (spec 01 §3).
///
/// When K2 has rank ≤ 1 (the reduced cores K diag(1, 0), a point load μ = κ², an empty mesh) ε
/// is the solution with ε_ζ = 0 that satisfies the normal-force equation exactly: the reduced
/// cores give ε = [∫ke/K, 0], an empty mesh 0, and for consistent integrals the load K2 ε equals
/// the pseudo-inverse's. A uniform separation e gives ε = [e, 0] for every core.
/// @param[in] K2 stiffness core (2×2), symmetric PSD [N/m, N, N·m].
/// @param[in] k_e_integral ∫k e dℓ [N].
/// @param[in] k_sigma_e_integral ∫k σ e dℓ [N·m].
/// @return [ε_η [m], ε_ζ [rad]].
/// @throws InvalidInput naming K2 (non-finite, not symmetric, negative diagonal) or an integral
///   (non-finite).
Vector2 CalcTransmissionErrorPair(const Matrix2& K2, double k_e_integral,
                                  double k_sigma_e_integral);

/// @brief The damping core C2 = (c_m / K) K2 (B–S Eq. 39: energy-equivalent viscous damper of
/// the same shape as the stiffness). Zero when K = K2(0,0) = 0 (no contact).
/// @param[in] K2 stiffness core (2×2) [N/m, N, N·m].
/// @param[in] c_m mesh damping coefficient along η, ≥ 0 [N·s/m].
/// @return C2 (2×2) [N·s/m, N·s, N·m·s].
/// @throws InvalidInput naming c_m (negative or non-finite) or K2 (K2(0,0) < 0 or non-finite).
Matrix2 CalcDampingCore(const Matrix2& K2, double c_m);

/// @brief The mesh damping C_mesh = Gᵀ C2 G with C2 = (c_m / K) K2 (12×12, B–S Eq. 39).
/// @param[in] G mesh Jacobian (2×12) [-, m].
/// @param[in] K2 stiffness core (2×2) [N/m, N, N·m].
/// @param[in] c_m mesh damping coefficient along η, ≥ 0 [N·s/m].
/// @return C_mesh (12×12) [N·s/m, N·s, N·m·s].
/// @throws InvalidInput as CalcDampingCore.
Matrix12 CalcMeshDamping(const Matrix2x12& G, const Matrix2& K2, double c_m);

/// @brief c_m = 2 ζ_m √(K m_e) from a damping ratio of the mesh mode (spec 01 §3).
/// @param[in] damping_ratio ζ_m ≥ 0 [-].
/// @param[in] K mesh stiffness ≥ 0 [N/m].
/// @param[in] equivalent_mass m_e > 0 of the mesh mode along η [kg].
/// @return c_m [N·s/m].
/// @throws InvalidInput naming the argument that is negative or non-finite.
double CalcMeshDampingCoefficient(double damping_ratio, double K, double equivalent_mass);

// MeshCoreLevel (the levels of spec 01 §5 that share G, see the file comment),
// ToString(MeshCoreLevel) and CalcLevelJacobian live in geardyn/system/mesh_core.hpp (lib), so
// that analyses can read a core's level without depending on geardyn::models.

/// @brief The 2×2 core of a level from the same data (K, h, μ, b); every input is validated for
/// every level (CalcStiffnessCore), so bad data never hides behind a reduced level.
/// @param[in] level model level.
/// @param[in] K mesh stiffness ≥ 0 [N/m].
/// @param[in] h load centre along σ [m].
/// @param[in] mu rotational coupling ≥ κ² [-].
/// @param[in] half_face_width b > 0 [m].
/// @return K2 (kBlankenshipSingh) or K diag(1, 0) (kCoupling4Dof, kTorsional) [N/m, N, N·m].
/// @throws InvalidInput as CalcStiffnessCore.
Matrix2 CalcLevelCore(MeshCoreLevel level, double K, double h, double mu, double half_face_width);

/// @brief The torsional SDOF mesh (Kahraman & Singh 1990): stiffness k on the transverse
/// line-of-action coordinate x = pinion_arm θ_iz + gear_arm θ_jz (x > 0: approach).
struct TorsionalCore {
  double k = 0.0;           ///< K cos²ψ_b, stiffness along the transverse line of action [N/m]
  double pinion_arm = 0.0;  ///< s a_i [m]
  double gear_arm = 0.0;    ///< s a_j (external) or −s a_j (internal) [m]
};

/// @brief The torsional SDOF core from G and K: with cos ψ_b = |η_xy| = ‖G(0, 0:2)_xy‖,
/// k = K cos²ψ_b and the arms G(0,5)/cos ψ_b, G(0,11)/cos ψ_b. k x² equals the θz block of the
/// kTorsional level's K_mesh.
/// @param[in] G mesh Jacobian (2×12) [-, m].
/// @param[in] K mesh stiffness ≥ 0 [N/m].
/// @return the SDOF core.
/// @throws InvalidInput naming K (negative or non-finite) or G (no transverse normal).
TorsionalCore CalcTorsionalCore(const Matrix2x12& G, double K);

/// @brief The torsional core as a 12×12 stiffness on q_pair: k a aᵀ on (θ_iz, θ_jz).
/// @param[in] core torsional SDOF core.
/// @return K_mesh (12×12) [N·m], non-zero only at rows/columns 5 and 11.
Matrix12 CalcTorsionalMeshStiffness(const TorsionalCore& core);

/// @brief B–S's 6×6 mesh stiffness K_o (B–S Eq. 41b) in the scaled relative coordinates of
/// CalcBsRelativeDisplacementMap (row order u, v, w, bθ_u, aθ_v, aθ_w):
/// \f[ K_o = K [g gᵀ + (μ − κ²) e_4 e_4ᵀ],\quad g = (0, c, s, κ, −s, c). \f]
/// Pass c = cos ψ, s = sin ψ of the signed helix angle MeshFrame::signed_helix_angle; then
/// K_o = Pᵀ K2 P with P = CalcBsDeflectionProjection(c, s, b) and K2 = CalcStiffnessCore(K, κb,
/// μ, b), and Tᵀ K_o T = (P T)ᵀ K2 (P T) with T = CalcBsRelativeDisplacementMap.
/// @param[in] K mesh stiffness ≥ 0 [N/m].
/// @param[in] kappa κ = h/b [-].
/// @param[in] mu μ ≥ κ² [-].
/// @param[in] cos_psi_b c = cos ψ > 0 [-].
/// @param[in] sin_psi_b s = sin ψ (signed) [-], c² + s² = 1.
/// @return K_o (6×6) [N/m].
/// @throws InvalidInput naming K, kappa, mu, cos_psi_b or sin_psi_b.
Matrix6 CalcBsKo(double K, double kappa, double mu, double cos_psi_b, double sin_psi_b);

/// @brief P (2×6) with [δ_η, δ_ζ] = P δ_BS: rows g₀ = (0, c, s, 0, −s, c) and −e₄ᵀ/b.
/// @param[in] cos_psi_b c [-]. @param[in] sin_psi_b s (signed) [-].
/// @param[in] half_face_width b > 0 [m].
/// @return P (2×6) [-, 1/m].
/// @throws InvalidInput naming half_face_width (b ≤ 0 or non-finite).
Matrix2x6 CalcBsDeflectionProjection(double cos_psi_b, double sin_psi_b, double half_face_width);

/// @brief B–S's 6-vector transmission error (B–S Eqs. 41c, 42) for the pair ε of spec 01 §3:
/// δ̃ = (0, ε_η / c, 0, −b ε_ζ, 0, 0). In the scalar-TE case (ε_ζ = 0) only the line-of-action
/// entry is non-zero (Eq. 42): the normal error ε_η seen along the transverse line of action
/// (B–S Eq. 20). K_o δ̃ = Pᵀ K2 ε, so Tᵀ K_o δ̃ is the B–S mesh load.
/// @param[in] epsilon [ε_η [m], ε_ζ [rad]].
/// @param[in] half_face_width b > 0 [m].
/// @param[in] cos_psi_b c = cos ψ_b > 0 [-].
/// @return δ̃ (6) [m].
/// @throws InvalidInput naming half_face_width or cos_psi_b.
Vector6 CalcBsTransmissionError(const Vector2& epsilon, double half_face_width, double cos_psi_b);

}  // namespace geardyn
