/// @file
/// @brief Internal: the shared data behind SystemModel and the fact-finding shared by
/// SystemBuilder::Build() and SystemModel::Restrict().
#pragma once

#include <cstdint>
#include <vector>

#include "geardyn/system/system_model.hpp"

namespace geardyn {

struct SystemModel::Data {
  std::uint64_t id = 0;
  DofMap dof_map;
  SparseMatrix mass;
  SparseMatrix stiffness0;
  SparseMatrix damping0;
  VectorX load0;
  std::vector<SystemMesh> meshes;
  std::vector<SystemElement> elements;
  std::vector<SystemLoad> loads;
  std::vector<SystemHarmonicLoad> harmonic_loads;
  double rayleigh_alpha = 0.0;
  double rayleigh_beta = 0.0;
  double modal_zeta = 0.0;
  TimeDependence time_dependence = TimeDependence::kConstant;
  std::int64_t period_meshes = 1;
  std::vector<std::vector<int>> blocks;
};

namespace internal {

/// A fresh model id (never 0).
std::uint64_t NextModelId();

/// Sets time_dependence, period_meshes and blocks from the other fields. The blocks use the
/// coupling pattern of M, K0, C0 and every mesh (entries below a relative 1e-12 count as zero).
void ComputeFacts(SystemModel::Data& data);

/// The 2×2 stiffness pattern of a core: which of (η row, ζ row, cross term) are not identically
/// negligible; nonlinear cores report `all_coordinates`.
struct CorePattern {
  bool eta = false;
  bool zeta = false;
  bool cross = false;
  bool all_coordinates = false;
};
CorePattern CalcCorePattern(const MeshCore& core);

/// K̄2 of a core (see SystemMesh::mean_core_stiffness).
Matrix2 CalcMeanCoreStiffness(const MeshCore& core);

}  // namespace internal
}  // namespace geardyn
