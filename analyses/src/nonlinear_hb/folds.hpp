/// @file
/// @brief Folds (sign changes of dΩ/ds) and slow-sweep jump points of a traced HB curve.
#pragma once

#include <limits>
#include <vector>

#include "geardyn/analyses/nonlinear_hb.hpp"

namespace geardyn::internal {

/// A fold located by LocateFold.
struct FoldLocation {
  bool converged = false;  ///< error ≤ fold_tolerance·|omega|.
  double omega = 0.0;      ///< Ω at the fold (vertex of the local parabola Ω(σ)).
  double error = std::numeric_limits<double>::infinity();  ///< Estimated |Ω error|.
  VectorX y;            ///< (x, Ω) of the curve point nearest to the fold (best iterate).
  int evaluations = 0;  ///< Bordered solves (each a Newton solve and one tangent).
};

/// Locates the fold between accepted continuation points y_A = (x_A, Ω_A) (unit scaled tangent
/// t̂_A, oriented along the trace) and y_B, whose tangents have Ω components of opposite sign,
/// to |ΔΩ| ≤ fold_tolerance·|Ω| (fold_location.cpp). `sx`, `so`: the arclength scaling;
/// `residual_tolerance`: the corrector's ‖R‖∞ tolerance.
FoldLocation LocateFold(NhbSolver& solver, const VectorX& ya, const VectorX& ta, const VectorX& yb,
                        double sx, double so, double residual_tolerance, double fold_tolerance,
                        int max_corrector_iterations);

/// Fills curve.folds, curve.jumps and the branch id of every point. `steps[i]` is the scaled
/// arclength from point i−1 to i, `omega_scale` the Ω scaling of the arclength. A fold between
/// points i and i+1 is taken from `located` when it holds one with index i (LocateFold's
/// result, with its error estimate); otherwise it is the Hermite interpolation of Ω(s).
void FindFoldsAndJumps(NhbCurve& curve, const std::vector<double>& steps, double omega_scale,
                       const std::vector<NhbFold>& located = {});

/// Fills curve.jumps from curve.folds and the branch ids of the points (replacing any): a fold
/// with a stable side is a slow-sweep jump; it lands on the stable crossing of its Ω, on a branch
/// other than the two meeting at the fold, nearest in RMS (any segment of the curve).
void FindJumps(NhbCurve& curve);

}  // namespace geardyn::internal
