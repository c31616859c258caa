/// @file
/// @brief Internal: the pieces of ComputeModes (geardyn/analyses/modal.hpp), one file per method
/// path — dense.cpp, arpack.cpp (undamped eigenpairs), damped.cpp (damping classification and the
/// state-space problem), classification.cpp (energy fractions, labels, multiplicities).
#pragma once

#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/numerics/symmetric_eigen.hpp"
#include "geardyn/system/system_model.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::internal {

/// @brief The mean (LTI) matrices of a model, assembled once for the modal analysis.
struct MeanSystem {
  SparseMatrix K;  ///< (n×n) K̄ = K0 + Σ Gᵀ K̄2 G [N/m, N, N·m]
  SparseMatrix M;  ///< (n×n) mass [kg, kg·m, kg·m²]
  SparseMatrix C;  ///< (n×n) C̄ = C0 + Σ (c_m/K̄_k) Gᵀ K̄2 G [N·s/m, …] (B–S Eq. 39 on K̄2)
  std::vector<Matrix12> mesh_stiffness;  ///< per mesh, Gᵀ K̄2 G (12×12)
  bool has_damping = false;              ///< C has a non-zero entry
};

/// @brief Assembles K̄, M, C̄ and the per-mesh K̄ blocks (sparse workspace kernels).
MeanSystem AssembleMeanSystem(const SystemModel& model, std::vector<std::string>* warnings);

/// @brief All eigenpairs of the dense pencil; keeps the `num_modes` lowest (or nearest
/// options.shift) when num_modes > 0.
GeneralizedEigenResult SolveModesDense(const MeanSystem& sys, const ModalOptions& options,
                                       bool compute_vectors);

/// @brief The num_modes lowest (or nearest options.shift) eigenpairs by ARPACK shift-invert.
GeneralizedEigenResult SolveModesArpack(const MeanSystem& sys, const ModalOptions& options,
                                        int num_modes, bool compute_vectors);

/// @brief Writes damping_kind, rayleigh_alpha/beta into `result` and a warning for
/// non-proportional damping. `shapes` (n × m, M-normalized; may be empty) and the eigenvalues
/// serve the subspace test of large systems (see damped.cpp).
void ClassifyDamping(const MeanSystem& sys, const ModalOptions& options, const MatrixX& shapes,
                     const VectorX& eigenvalues, ModalResult* result);

/// @brief Dense state-space damped modes (see the file comment of modal.hpp).
/// @param[in] spectrum_scale s [rad²/s²] (ω_s = √s balances the state matrix).
/// @param[in] num_rigid_body_modes r: at most 2r eigenvalues with |λ| ≤ 1e-6·ω_s become 0.
std::vector<DampedMode> ComputeDampedModes(const MeanSystem& sys, double spectrum_scale,
                                           int num_rigid_body_modes, Summary* summary);

/// @brief The damped modes of a proportionally damped system from the undamped modes and their
/// modal damping ratios (exact when damping_kind ≠ kNonProportional).
std::vector<DampedMode> DampedModesFromModalRatios(const VectorX& eigenvalues,
                                                   const VectorX& modal_damping_ratios);

/// @brief A DampedMode from a complex eigenvalue λ (Im λ ≥ 0) [1/s].
DampedMode MakeDampedMode(std::complex<double> lambda);

/// @brief Kinetic (per DofKind, per body) and strain (per mesh, element, "other") energy
/// fractions and labels of the M-normalized `shapes`, written into `result`.
void ClassifyModes(const SystemModel& model, const MeanSystem& sys, const MatrixX& shapes,
                   const VectorX& eigenvalues, ModalResult* result);

/// @brief Groups of consecutive modes whose frequencies agree within rel_tol.
std::vector<std::vector<int>> GroupMultiplicities(const VectorX& frequencies_hz, double rel_tol);

}  // namespace geardyn::internal
