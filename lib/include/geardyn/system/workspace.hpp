/// @file
/// @brief SystemWorkspace and the assembly kernels that write into it: K(θ), C(θ), f(θ) and the
/// mean (LTI) stiffness of a SystemModel (architecture §3.2; spec 01 §3; B–S Eq. 39, 41).
///
/// **Kernels** (order: model, workspace, inputs; each returns a reference into the workspace and
/// never allocates once the workspace exists):
/// * AssembleStiffness: K(θ) = K0 + Σ_k P_kᵀ G_kᵀ K2_k(θ_k) G_k P_k.
/// * AssembleDamping:   C(θ) = C0 + Σ_k P_kᵀ G_kᵀ C2_k(θ_k) G_k P_k, C2 = (c_m/K) K2 (B–S Eq. 39).
/// * AssembleLoad:      f(θ) = f0 + Σ_l Re(F_l e^{i m_l θ}) + Σ_k P_kᵀ G_kᵀ K2_k(θ_k) ε_k(θ_k)
///   (harmonic loads, EvalTransmissionErrorLoad).
/// * AssembleMeanStiffness: K̄ = K0 + Σ_k P_kᵀ G_kᵀ K̄2_k G_k P_k (θ-mean of K2; LTI analyses).
/// with θ_k = SystemMesh::MeshPhase(θ).
///
/// **Core forms.** LinearMeshCore: as above (mean-LTI cores use their constant means; kTorsional
/// and kCoupling4Dof cores give K2 = diag(c0, 0)). SliceMeshCore: the all-loaded small-motion
/// limit — K2 = Σ_s k_s(θ)[[1, −σ_s], [−σ_s, σ_s²]] (EvalSliceChannels), C2 = (c_m/Σk_s) K2 and
/// ε from the slice separations is NOT included (f uses f0 only): a linearization about
/// "every slice in contact, zero separation", documented for linear analyses of a slice model;
/// nonlinear analyses call the core's force instead. NonlinearMeshCore: contributes nothing
/// here (its force and Jacobian come from NonlinearMeshCore::CalcForces).
///
/// **Storage.** A dense workspace (the default for models with storage_hint() == kDense) holds
/// n×n dense buffers; a sparse one holds CSC matrices with a fixed pattern (K0 ∪ C0 ∪ every
/// mesh block) filled in place. Both kinds of kernel exist; each checks its workspace kind.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Assembly scratch of one SystemModel for one thread (Pinocchio `Data`).
struct SystemWorkspace {
  /// @brief Allocates every buffer for `model` (the only allocation).
  /// @param[in] storage kDense or kSparse buffers (default: the model's storage hint).
  explicit SystemWorkspace(const SystemModel& model);
  SystemWorkspace(const SystemModel& model, StorageKind storage);

  /// True when built from a model with the same id (a copy of the same model).
  bool IsCompatibleWith(const SystemModel& model) const;

  StorageKind storage = StorageKind::kDense;  ///< which buffers below are sized
  std::uint64_t model_id = 0;                 ///< id() of the model the buffers fit
  int num_dofs = 0;                           ///< n

  MatrixX stiffness;              ///< (n×n, dense) K(θ) or K̄ of the last call [N/m, N, N·m]
  MatrixX damping;                ///< (n×n, dense) C(θ) [N·s/m, N·s, N·m·s]
  SparseMatrix stiffness_sparse;  ///< (n×n, sparse) K(θ) or K̄, fixed pattern
  SparseMatrix damping_sparse;    ///< (n×n, sparse) C(θ), fixed pattern
  VectorX load;                   ///< (n) f(θ) [N, N·m]

  std::vector<Matrix12> mesh_stiffness;  ///< per mesh, Gᵀ K2 G of the last call (12×12)
  std::vector<Matrix12> mesh_damping;    ///< per mesh, Gᵀ C2 G of the last call (12×12)
  std::vector<Vector12> mesh_load;       ///< per mesh, Gᵀ K2 ε of the last call (12)
  std::vector<SliceMeshWorkspace> slice_workspaces;  ///< one per slice mesh, in mesh order
  std::vector<int> slice_workspace_of_mesh;          ///< mesh → slice_workspaces index or −1

  // Sparse pattern maps (internal): positions in the CSC value arrays.
  std::vector<std::array<int, 144>> mesh_value_positions;  ///< per mesh (a,b) → value index or −1
  VectorX constant_stiffness_values;                       ///< K0 on the workspace pattern
  VectorX constant_damping_values;                         ///< C0 on the workspace pattern
};

/// @brief K(θ) (dense workspace). No allocation.
/// @param[in] theta system phase [rad], finite.
/// @return ws.stiffness (n×n) [N/m, N, N·m], symmetric PSD.
/// @throws InvalidInput on a non-finite θ or a workspace that does not fit the model / is sparse.
const MatrixX& AssembleStiffness(const SystemModel& model, SystemWorkspace& ws, double theta);
/// @brief K(θ) (sparse workspace). No allocation. @return ws.stiffness_sparse.
const SparseMatrix& AssembleStiffnessSparse(const SystemModel& model, SystemWorkspace& ws,
                                            double theta);
/// @brief K̄ = θ-mean stiffness (dense workspace): K0 + Σ Gᵀ K̄2 G with K̄2 from the exact mean of
/// the stiffness channels (slice cores: mean of their all-loaded channels). @return ws.stiffness.
const MatrixX& AssembleMeanStiffness(const SystemModel& model, SystemWorkspace& ws);
/// @brief K̄ (sparse workspace). @return ws.stiffness_sparse.
const SparseMatrix& AssembleMeanStiffnessSparse(const SystemModel& model, SystemWorkspace& ws);
/// @brief C(θ) (dense workspace). No allocation. @return ws.damping.
const MatrixX& AssembleDamping(const SystemModel& model, SystemWorkspace& ws, double theta);
/// @brief C(θ) (sparse workspace). No allocation. @return ws.damping_sparse.
const SparseMatrix& AssembleDampingSparse(const SystemModel& model, SystemWorkspace& ws,
                                          double theta);
/// @brief f(θ) (either workspace). No allocation. @return ws.load (n) [N, N·m].
const VectorX& AssembleLoad(const SystemModel& model, SystemWorkspace& ws, double theta);
/// @brief θ-mean of f(θ): f0 + Σ Gᵀ mean(K2 ε) (harmonic loads have mean zero), the mean of the
/// product taken by the rectangle rule on `samples_per_period`·P points per mesh period (exact for
/// constant K2 or ε and for trigonometric polynomials of degree < samples/2). @return ws.load.
const VectorX& AssembleMeanLoad(const SystemModel& model, SystemWorkspace& ws,
                                int samples_per_period = 512);

}  // namespace geardyn
