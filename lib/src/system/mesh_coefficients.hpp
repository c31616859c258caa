/// @file
/// @brief (internal) The θ-coefficients that a mesh core's linear operator and load depend on,
/// and their step breakpoints (system_steps.cpp, system_harmonics.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "geardyn/system/mesh_core.hpp"

namespace geardyn::internal {

/// @brief The coefficients the core's K2 and C2 depend on (`with_load`: also those of K2 ε).
/// Mean-LTI linear cores have none for K2 and C2; nonlinear cores none at all.
std::vector<const Coefficient*> MeshOperatorCoefficients(const MeshCore& core, bool with_load);

/// @brief P_k of the core (1 for a nonlinear core).
std::int64_t MeshCorePeriod(const MeshCore& core);

/// @brief True when every coefficient is constant or piecewise constant (Classify ≤
/// kPiecewiseConstant).
bool AllStepwise(const std::vector<const Coefficient*>& coefs);

/// @brief Every breakpoint of the piecewise-constant coefficients, repeated over the period
/// 2π·period_meshes (mesh phase), unsorted. Needs AllStepwise(coefs).
std::vector<double> RawBreakpoints(const std::vector<const Coefficient*>& coefs,
                                   std::int64_t period_meshes);

/// @brief The union of the coefficients' breakpoints repeated over the period 2π·period_meshes
/// (mesh phase), plus 0, sorted, merged within merge_tol·period. Needs AllStepwise(coefs).
std::vector<double> UnionBreakpoints(const std::vector<const Coefficient*>& coefs,
                                     std::int64_t period_meshes, double merge_tol);

/// @brief Sorts `points` (all in [0, period)), adds 0 and merges points closer than tol·period
/// (also to the wrap-around point `period`).
std::vector<double> SortAndMerge(std::vector<double> points, double period, double tol);

}  // namespace geardyn::internal
