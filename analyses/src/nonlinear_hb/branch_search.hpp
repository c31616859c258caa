/// @file
/// @brief Branch search of the nonlinear HB continuation (issue 13): solutions off the traced
/// curve from other initial guesses, traced as extra segments (NhbContinuationOptions::
/// branch_search).
#pragma once

#include "geardyn/analyses/nonlinear_hb.hpp"

namespace geardyn::internal {

/// Where a branch trace starts (a converged solution) and how it ended.
struct BranchStart {
  VectorX x;            ///< solution at omega (n(2H+1))
  double omega = 0.0;   ///< [Ω units]
  bool closed = false;  ///< out: the trace came back to a fold it had located (an isola)
};

/// The pseudo-arclength continuation with H harmonics (continuation.cpp). Without `from`: from
/// the contact guess at c.omega_start to c.omega_end. With `from`: from (from->x, from->omega)
/// towards c.omega_end, stopping where the trace leaves the range on the c.omega_start side or
/// closes a loop (from->closed, not a failure).
NhbCurve TraceWithHarmonics(const NhbProblem& problem, const NhbOptions& options,
                            const NhbContinuationOptions& c, int H, BranchStart* from);

/// The branch search on a traced curve (see NhbContinuationOptions::branch_search): appends
/// every branch found as a new segment (both directions from its solution, joined in arclength
/// order), renumbers the branches and re-finds the jumps over all segments; counters
/// "branch_search_solves" and "branches_found"; a segment whose trace failed keeps its points
/// and adds a warning.
void SearchBranches(const NhbProblem& problem, const NhbOptions& options,
                    const NhbContinuationOptions& c, NhbCurve& curve);

}  // namespace geardyn::internal
