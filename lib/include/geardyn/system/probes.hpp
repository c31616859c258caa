/// @file
/// @brief Output probes shared by every analysis: the dynamic transmission error (DTE) of each
/// mesh, its torsional part, the mesh force pair, and the element (bearing, shaft, coupling)
/// forces, at one state (q, q̇) and system phase θ (issue 4; spec 01 §3; spec 02 outputs).
///
/// **Definitions** (mesh k with pair coordinates q_k = P_k q = [q_i; q_j], Jacobian G_k, phase
/// θ_k = SystemMesh::MeshPhase(θ), transmission-error pair ε_k(θ_k) = (ε_η, ε_ζ)):
/// * mesh deflection δ = G_k q_k = [δ_η [m], δ_ζ [rad]] (δ_η > 0: approach, the teeth compress);
/// * **DTE** (dynamic transmission error along the tooth normal η, relative to the unloaded
///   static transmission error):
///   \f[ \mathrm{DTE}_k = δ_η − ε_η(θ_k) = g_k q − ε_η(θ_k) \quad [\mathrm{m}], \f]
///   g_k = row η of G_k scattered to the system DOFs. It is the elastic approach of the teeth:
///   for the torsional and 4-DOF levels F_η = K(θ)·DTE. Positive = the pinion leads the
///   conjugate position (the teeth are compressed by a driving pinion torque). The transmission
///   error measured by encoders (loaded TE, including ε) is DTE + ε_η = δ_η;
/// * **torsional TE**: the same with only the rotations about the gear axes (the θz columns 5
///   and 11 of G_k; supports held rigid):
///   \f[ \mathrm{TE}_{θ,k} = G_{η,5}\,θ_{z,i} + G_{η,11}\,θ_{z,j} − ε_η(θ_k) \quad [\mathrm{m}],
///   \f] along η, with the sign of the DTE. For an external pair |G_{η,5}| = a_i cos ψ_b and
///   |G_{η,11}| = a_j cos ψ_b (a the base radii, ψ_b the base helix angle), i.e. the usual
///   TE = r_b1 θ_1 − r_b2 θ_2 of Kahraman & Singh (1990) with each θ positive in its own
///   direction of rotation when driven, times cos ψ_b (divide by cos ψ_b for the transverse-plane
///   TE, and by a_j for the angular TE of the gear [rad]). For the torsional level (G has only
///   the θz columns) TE_θ = DTE;
/// * **mesh force pair** F = [F_η [N], M_ζ [N·m]] = ∂U/∂δ (spec 01 §3; F_η > 0 compression):
///   linear cores F = K2(θ_k)(δ − ε) + C2(θ_k) δ̇, with C2 = (c_m/K) K2 (B–S Eq. 39); slice
///   cores the nonlinear slice force (EvalSliceForce, contact loss and back flank included) plus
///   CalcSliceDampingCore δ̇; the force on the pair's coordinates is −G_kᵀ F. Slice cores carry
///   no ε pair: their DTE and TE_θ use ε = 0 (the separations enter the force only).
///   NonlinearMeshCore: the force is not a 2-pair (MeshProbeValues::has_force = false, F = 0);
/// * **element force** f_e = K_e q_e + C_e q̇_e (6 or 12 components, [N, N·m], at each body's
///   reference point in inertial axes, on the element coordinates [q_a; q_b]): the generalized
///   force the bodies exert ON the element, i.e. minus the element's force on the bodies. For a
///   grounded bearing it is the load the bearing carries (and passes to the ground); the
///   equilibrium of a body reads Σ (external + mesh forces on it) = Σ_e f_e on its coordinates.
///
/// **Linear probe operator** (for Floquet/HB/time samples): MakeProbeMatrix gives a sparse P
/// (rows × n) and, per row, which ε channel is subtracted, so that
/// \f[ y(θ) = P q − o(θ), \quad o_r(θ) = ε_{η}(θ_{k(r)}) \text{ or } 0; \f]
/// EvalProbeOffset fills o(θ) without allocation. The harmonics of y follow from those of q and
/// of o (a linear map), which is what harmonic balance needs.
///
/// **Kernels** (EvalMeshProbe, EvalMeshDte, CalcElementForce, EvalProbeOffset) use fixed sizes
/// and the ProbeWorkspace only, and never allocate; EvalProbes is the allocating convenience.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Scratch of the probe kernels for one model and one thread (the slice cores' caches).
struct ProbeWorkspace {
  /// Allocates the slice-core workspaces of `model` (the only allocation).
  explicit ProbeWorkspace(const SystemModel& model);
  /// True when built from a copy of `model` (same id).
  bool IsCompatibleWith(const SystemModel& model) const;

  std::uint64_t model_id = 0;                        ///< id() of the model
  std::vector<SliceMeshWorkspace> slice_workspaces;  ///< one per slice mesh, in mesh order
  std::vector<int> slice_workspace_of_mesh;          ///< mesh → slice_workspaces index or −1
};

/// @brief Probe outputs of one mesh at one state (see the file comment for the definitions).
struct MeshProbeValues {
  double dte = 0.0;                              ///< δ_η − ε_η [m]
  double torsional_te = 0.0;                     ///< θz part of δ_η minus ε_η [m]
  Vector2 deflection = Vector2::Zero();          ///< δ = G q_pair [m, rad]
  Vector2 transmission_error = Vector2::Zero();  ///< ε(θ_k) [m, rad] (0 for slice/nonlinear)
  Vector2 force = Vector2::Zero();               ///< F = [F_η [N], M_ζ [N·m]]
  bool has_force = true;  ///< false for a NonlinearMeshCore (force is not a 2-pair)
};

/// @brief δ = G_k q_k of mesh k [m, rad] (fixed coordinates count as 0). No allocation.
/// @param[in] q (num_dofs) coordinates [m, rad].
/// @throws InvalidInput if k is out of range or q has the wrong size.
Vector2 CalcMeshDeflection(const SystemModel& model, MeshIndex k,
                           const Eigen::Ref<const VectorX>& q);

/// @brief All probe values of mesh k at phase θ. No allocation.
/// @param[in] theta system phase [rad], finite.
/// @param[in] q (num_dofs) coordinates [m, rad].
/// @param[in] qdot (num_dofs) velocities [m/s, rad/s], or size 0 for none (no damping force).
/// @throws InvalidInput on a bad size, index, θ, or a workspace of another model.
MeshProbeValues EvalMeshProbe(const SystemModel& model, ProbeWorkspace& ws, MeshIndex k,
                              double theta, const Eigen::Ref<const VectorX>& q,
                              const Eigen::Ref<const VectorX>& qdot);

/// @brief DTE of every mesh: dte(k) = δ_η,k − ε_η,k(θ_k) [m]. No allocation.
/// @param[out] dte (num_meshes) sized by the caller.
/// @throws InvalidInput on a bad size or θ.
void EvalMeshDte(const SystemModel& model, double theta, const Eigen::Ref<const VectorX>& q,
                 Eigen::Ref<VectorX> dte);

/// @brief Element force f_e = K_e q_e (+ C_e q̇_e) on its 6 or 12 coordinates [N, N·m]. No
/// allocation.
/// @param[in] qdot (num_dofs) velocities, or size 0 for none.
/// @param[out] force (6 or 12 = element coordinates) sized by the caller.
/// @throws InvalidInput on a bad size or index.
void CalcElementForce(const SystemModel& model, ElementIndex e, const Eigen::Ref<const VectorX>& q,
                      const Eigen::Ref<const VectorX>& qdot, Eigen::Ref<VectorX> force);

/// @brief What a row of a ProbeMatrix measures.
enum class ProbeKind {
  kMeshDte,          ///< DTE_k [m]
  kMeshTorsionalTe,  ///< TE_θ,k [m]
  kMeshLoadedTe,     ///< δ_η,k = DTE_k + ε_η,k [m] (the encoder-measured loaded TE)
};
/// "dte", "torsional_te", "loaded_te".
const char* ToString(ProbeKind kind);

/// @brief A linear probe operator y(θ) = P q − o(θ) (see the file comment).
struct ProbeMatrix {
  SparseMatrix P;                  ///< (rows × num_dofs) [-, m]
  std::vector<std::string> names;  ///< per row "<kind>:<mesh>", e.g. "dte:pinion-wheel"
  std::vector<ProbeKind> kinds;    ///< per row
  std::vector<int> meshes;         ///< per row, the mesh index
  /// Per row, true when o_r(θ) = ε_η of its mesh (linear cores with a transmission error).
  std::vector<bool> has_offset;
  /// Number of rows.
  int rows() const { return static_cast<int>(names.size()); }
};

/// @brief The probe operator with one row per (mesh, kind), mesh-major (all kinds of mesh 0,
/// then mesh 1, …).
/// @param[in] kinds the rows per mesh (default: DTE only).
ProbeMatrix MakeProbeMatrix(const SystemModel& model,
                            const std::vector<ProbeKind>& kinds = {ProbeKind::kMeshDte});

/// @brief o(θ) of a ProbeMatrix (ε_η of each row's mesh at its phase, or 0). No allocation.
/// @param[out] offset (probes.rows()) sized by the caller [m].
void EvalProbeOffset(const SystemModel& model, const ProbeMatrix& probes, double theta,
                     Eigen::Ref<VectorX> offset);

/// @brief Every probe at one state (allocating convenience).
struct ProbeValues {
  std::vector<MeshProbeValues> meshes;  ///< per mesh, in model order
  std::vector<VectorX> element_forces;  ///< per element, f_e (6 or 12) [N, N·m]
};

/// @brief EvalMeshProbe of every mesh and CalcElementForce of every element.
/// @param[in] qdot (num_dofs) or size 0 (default) for a static state.
ProbeValues EvalProbes(const SystemModel& model, double theta, const Eigen::Ref<const VectorX>& q,
                       const Eigen::Ref<const VectorX>& qdot = VectorX());

}  // namespace geardyn
