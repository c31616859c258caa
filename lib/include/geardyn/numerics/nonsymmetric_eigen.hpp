/// @file
/// @brief ARPACK's non-symmetric implicitly restarted Arnoldi (dnaupd/dneupd, regular mode 1,
/// which = "LM") on a matrix-free real operator y = Op x — the largest-|θ| eigenpairs (used by
/// the Floquet ARPACK monodromy). The Fortran prototypes are private to geardyn_core
/// (lib/src/numerics/arpack_fortran.hpp). Calls are serialized by the process-wide ARPACK mutex
/// shared with the symmetric driver: ARPACK keeps the reverse-communication state in Fortran SAVE
/// variables.
#pragma once

#include <functional>
#include <string>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief What one Arnoldi run produced.
struct ArnoldiOutcome {
  bool ok = false;        ///< dnaupd and dneupd returned without error (info ≥ 0)
  int info = 0;           ///< dnaupd info (0 converged, 1 max iterations, 3 no shifts, < 0 error)
  int eupd_info = 0;      ///< dneupd info
  int num_converged = 0;  ///< converged Ritz values (iparam[4])
  int iterations = 0;     ///< implicit restarts (iparam[2])
  long applications = 0;  ///< operator applications
  VectorXc values;        ///< (num_converged) Ritz values θ
  MatrixXc vectors;       ///< (n × num_converged) unit Ritz vectors
  std::string message;    ///< why !ok or not all converged (empty otherwise)
};

/// @brief The nev largest-|θ| eigenpairs of the real n×n operator `apply` (y = Op x, x and y of
/// length n, not overlapping) by dnaupd/dneupd; ncv Arnoldi vectors (nev + 2 ≤ ncv ≤ n), Ritz
/// tolerance tol (relative: ‖r‖ ≤ tol·|θ|), at most max_iterations restarts. A fixed start vector
/// makes the result reproducible. Without ARPACK (GEARDYN_WITH_ARPACK off) ok is false with the
/// message "ARPACK unavailable".
ArnoldiOutcome RunArnoldiLargestMagnitude(const std::function<void(const double*, double*)>& apply,
                                          int n, int nev, int ncv, double tol, int max_iterations);

}  // namespace geardyn
