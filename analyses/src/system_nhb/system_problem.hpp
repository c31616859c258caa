/// @file
/// @brief The SystemNhbProblem of a model whose meshes may run at several frequencies: the
/// builder behind MakeSystemNhbProblem (system_nonlinear_hb.hpp) without its one-frequency check,
/// for the quasi-periodic nonlinear harmonic balance (nonlinear_quasi_periodic_hb.hpp). The
/// linear part (M, C̄, K̄, the reduction T) is LTI and the law's phases θ_k = r_k θ + φ_k carry
/// each mesh's own frequency, so nothing in it needs one common period.
#pragma once

#include "geardyn/analyses/system_nonlinear_hb.hpp"

namespace geardyn::internal {

/// @brief Row `channel` (0: δ_η, 1: δ_ζ) of a mesh's G scattered to the system's `dofs` DOFs
/// (fixed coordinates dropped): u = P q for that coordinate.
VectorX ScatteredMeshRow(const SystemMesh& mesh, int channel, int dofs);

/// @brief MakeSystemNhbProblem without CheckSingleMeshFrequency (the law is a MeshForceLaw).
/// @throws InvalidInput on a NonlinearMeshCore, no meshes, or harmonic loads of order ≠ 1.
SystemNhbProblem BuildSystemNhbProblem(const SystemModel& model);

}  // namespace geardyn::internal
