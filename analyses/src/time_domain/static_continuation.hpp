/// @file
/// @brief The static equilibrium with the flanks-apart continuation (internal to the time-domain
/// analyses; implemented in quasi_static.cpp, time_response.hpp SimulateQuasiStatic "Flanks
/// apart"): SolveStatic (Newton), and where its tangent is singular the Levenberg–Marquardt
/// continuation that walks the flanks into contact, or accepts free play under no mesh load.
#pragma once

#include "td_system.hpp"

namespace geardyn::internal {

/// As SolveStatic; on its failure the continuation from the same start (then from rest). The
/// message of a failure says "flanks apart" when no contact carries the load.
TdStatic SolveStaticWithContinuation(const TdSystem& sys, TdWorkspace& ws, double theta0,
                                     const VectorX* start = nullptr);

}  // namespace geardyn::internal
