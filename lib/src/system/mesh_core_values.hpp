/// @file
/// @brief (internal) The linearized 2×2 stiffness, damping and load pair of one mesh core at a
/// mesh phase — the one place that says how each core form enters the linear system (workspace
/// kernels, harmonic expansion, step structure). See workspace.hpp "Core forms".
#pragma once

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn::internal {

/// What EvalMeshCoreValues computes (bit flags).
enum MeshValueWant { kWantStiffness = 1, kWantDamping = 2, kWantLoad = 4, kWantAll = 7 };

/// The 2×2 stiffness K2 [N/m, N, N·m], damping C2 [N·s/m, …] and load pair K2 ε [N, N·m] of a
/// mesh at its own phase.
struct MeshCoreValues {
  Matrix2 stiffness = Matrix2::Zero();
  Matrix2 damping = Matrix2::Zero();
  Vector2 load = Vector2::Zero();
};

/// @brief The values of `core` at mesh phase `phase` [rad]; `c_m` the resolved damping
/// coefficient [N·s/m]; `slice_ws` the core's workspace (slice cores only, else may be null).
/// LinearMeshCore: EvalStiffnessCore / EvalDampingCore / EvalTransmissionErrorLoad. SliceMeshCore:
/// the all-loaded limit K2 = EvalSliceChannels, C2 = (c_m/K) K2, no load. NonlinearMeshCore: zero.
/// No allocation.
MeshCoreValues EvalMeshCoreValues(const MeshCore& core, double c_m, SliceMeshWorkspace* slice_ws,
                                  double phase, int want);

}  // namespace geardyn::internal
