/// @file
/// @brief The mean (LTI) matrices M, C̄, K̄ of a system model: exactly the pencil ComputeModes
/// solves (modal.hpp), for users who check geardyn with their own tools (`geardyn matrices`, the
/// Python package's `system_matrices`).
#pragma once

#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// The mean system M q̈ + C̄ q̇ + K̄ q = f̄ (spec 01 "LTI equations"), sparse, symmetric.
struct MeanSystemMatrices {
  SparseMatrix mass;  ///< (n×n) M [kg, kg·m, kg·m²]
  SparseMatrix damping;  ///< (n×n) C̄ = C0 + Σ (c_m/K̄_k) Gᵀ K̄2 G [N·s/m, N·s, N·m·s] (B–S Eq. 39)
  SparseMatrix stiffness;  ///< (n×n) K̄ = K0 + Σ Gᵀ K̄2 G [N/m, N, N·m]
  /// What the mean leaves out (slice cores linearized all-loaded, nonlinear cores absent).
  std::vector<std::string> warnings;
};

/// @brief M, C̄ and K̄ of `model`, assembled as ComputeModes assembles them.
MeanSystemMatrices AssembleMeanSystemMatrices(const SystemModel& model);

}  // namespace geardyn
