/// @file
/// @brief Folds (sign changes of dΩ/ds) and slow-sweep jump points of a traced HB curve.
#pragma once

#include <vector>

#include "geardyn/analyses/nonlinear_hb.hpp"

namespace geardyn::internal {

/// Fills curve.folds, curve.jumps and the branch id of every point. `steps[i]` is the scaled
/// arclength from point i−1 to i, `omega_scale` the Ω scaling of the arclength.
void FindFoldsAndJumps(NhbCurve& curve, const std::vector<double>& steps, double omega_scale);

}  // namespace geardyn::internal
