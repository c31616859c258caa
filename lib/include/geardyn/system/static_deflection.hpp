/// @file
/// @brief The static operating point of a SystemModel under its mean load: mean deflection,
/// mean mesh deflections and forces, element (bearing) forces, and the contact-opening check
/// (issue 4; spec 01 §3 sign convention F_η > 0 = compression).
///
/// Solves K̄ q̄ = f̄ with K̄ = AssembleMeanStiffness and f̄ = AssembleMeanLoad. When K̄ is singular
/// (rigid-body modes, e.g. a free gear train), the solution is the minimum-norm one in the
/// complement of the null space N of K̄; the part of f̄ along N (a torque the supports cannot
/// react: the train would accelerate) is reported in the summary as a warning and removed.
/// Dense symmetric eigen-decomposition of K̄ (O(n³)): meant for systems up to a few thousand DOF.
#pragma once

#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/common/summary.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Options of SolveStaticDeflection.
struct StaticDeflectionOptions {
  /// Rigid-body criterion τ of rigid_modes.hpp (eigenvalues of the unit-diagonal K̃ ≤ τ) [-].
  double null_tol = kRigidNullTol;
  /// Relative size ‖N ᵀ f̄‖/‖f̄‖ above which the load is reported as not balanced [-].
  double balance_tol = 1e-8;
  /// Samples per mesh period for the mean transmission-error load (AssembleMeanLoad).
  int samples_per_period = 512;
  /// False (with the field, value and bound in `why`) on a bad value.
  bool IsValid(std::string* why) const;
};

/// @brief Mean state of one mesh.
struct MeshStaticState {
  std::string name;
  double delta_eta = 0.0;   ///< δ̄_η = row η of G q̄ [m] (approach; > 0 compresses the teeth)
  double delta_zeta = 0.0;  ///< δ̄_ζ [rad]
  double force_eta = 0.0;  ///< F̄_η [N] (linear cores: mean of K2(δ − ε), row η; > 0: contact)
  double moment_zeta = 0.0;   ///< M̄_ζ [N·m]
  bool contact_open = false;  ///< true when F̄_η ≤ 0: the mean load would open the contact
};

/// @brief Result of SolveStaticDeflection.
struct StaticDeflectionResult {
  VectorX deflection;                   ///< q̄ (n) [m, rad], orthogonal to the null space of K̄
  VectorX load;                         ///< f̄ (n) [N, N·m] as assembled (before balancing)
  std::vector<MeshStaticState> meshes;  ///< one per mesh, in model order
  std::vector<VectorX> element_forces;  ///< per element, K_e q̄_e (6 or 12) [N, N·m] on its coords
  int num_rigid_modes = 0;              ///< dim N
  /// ‖Nᵀ f̄‖ measured in the coordinates scaled by √diag(K̄) (so that m and rad mix) [√(N·m)-like];
  /// 0 when balanced. The summary warns when it exceeds balance_tol·‖f̄‖ in the same scaling.
  double unbalanced_load = 0.0;
  Summary summary;  ///< warnings: unbalanced load, open contacts
};

/// @brief The static operating point (see the file comment).
/// @throws InvalidInput when options are invalid.
StaticDeflectionResult SolveStaticDeflection(const SystemModel& model,
                                             const StaticDeflectionOptions& options = {});

}  // namespace geardyn
