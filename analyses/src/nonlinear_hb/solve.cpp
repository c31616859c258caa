/// @file
/// @brief SolveNonlinearHarmonicBalance: one Ω, given H or H doubled from 4 until the relative
/// H→2H change of the RMS of u is below the tolerance (each solve starts from the previous
/// solution, zero-padded).
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn {

NhbSolveResult SolveNonlinearHarmonicBalance(const NhbProblem& problem, double omega,
                                             const NhbOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  GEARDYN_THROW_UNLESS(problem.IsValid(&why), "nonlinear HB problem: " << why);
  GEARDYN_THROW_UNLESS(options.IsValid(&why), "nonlinear HB options: " << why);
  GEARDYN_THROW_UNLESS(std::isfinite(omega) && omega > 0,
                       "omega: must be positive and finite, got " << omega);
  const int n = problem.law->num_coordinates();
  NhbSolveResult result;
  long newton = 0;
  long restarts = 0;
  double jacobian_rcond = 1.0;  // of the last successful solve
  auto solve = [&](int H, VectorX* x, NhbPoint& point) {
    NhbSolver solver(problem, options, H);
    const bool fresh = x->size() == 0;
    *x = fresh ? solver.ContactGuess(omega) : NhbSolver::Resize(*x, n, H);
    Status status;
    double rn = 0.0;
    point.newton_iterations = solver.Newton(*x, omega, &status, &rn);
    newton += point.newton_iterations;
    if (fresh && status != Status::kSuccess) {
      // Issue 16: past the contact branch's fold (B&K oscillator, F_m = 0.1, F_a = 0.03, ζ =
      // 0.05 at Ω = 0.9: the contact answer's amplitude 0.14 exceeds the mean deflection) the
      // contact guess lies next to grazing, where damped Newton, the dogleg and the homotopy all
      // stall (830 iterations, kNotConverged) although a contact-loss orbit exists. Restart from
      // the contact guess with its alternating part scaled (the guesses of the branch search,
      // branch_search.cpp): the first that converges is the answer; none → the first status.
      const VectorX guess = solver.ContactGuess(omega);
      for (const double scale : {3.0, 0.3, 8.0}) {
        VectorX trial = guess;
        trial.tail(trial.size() - n) *= scale;
        Status trial_status;
        double trial_rn = 0.0;
        const int used = solver.Newton(trial, omega, &trial_status, &trial_rn);
        newton += used;
        point.newton_iterations += used;
        ++restarts;
        if (trial_status == Status::kSuccess) {
          *x = trial;
          status = trial_status;
          rn = trial_rn;
          break;
        }
      }
    }
    point.status = status;
    point.residual_norm = rn;
    if (status == Status::kSuccess) {
      // Issue 16: a singular Jacobian at the solution means a non-unique periodic solution
      // (ζ = 0 with a harmonic kΩ on a natural frequency of the contact-linearised system, e.g.
      // Ω = ω_n/3: any amount of the free vibration can be added) or a fold. Newton converges to
      // one of them without noticing; the summary warns (the linear HB reports kNumericalIssue).
      VectorX r;
      MatrixX J;
      solver.Evaluate(*x, omega, &r, &J, nullptr);
      // Eigen's rcond() runs Hager's estimator through solves with the factors: with an exactly
      // zero pivot those solves give inf/NaN and it returned 0.16 for the Jacobian at Ω = ω_n/3,
      // ζ = 0 (two zero pivots). The smallest over the largest pivot catches that (it never
      // exceeds 1/cond of U).
      if (J.allFinite()) {
        const Eigen::PartialPivLU<MatrixX> lu(J);
        const VectorX pivots = lu.matrixLU().diagonal().cwiseAbs();
        const double top = pivots.maxCoeff();
        const double pivot_ratio = top > 0.0 ? pivots.minCoeff() / top : 0.0;
        const double estimate = lu.rcond();
        jacobian_rcond = estimate >= 0.0 ? std::min(estimate, pivot_ratio) : 0.0;  // NaN → 0
      } else {
        jacobian_rcond = 0.0;
      }
    }
    solver.Describe(*x, omega, point);
    if (options.stability != NhbStabilityMethod::kNone && status == Status::kSuccess) {
      point.max_multiplier = solver.MaxMultiplier(*x, omega);
      point.stable = NhbVerdict(point.max_multiplier, options.stability_margin);
    } else if (status != Status::kSuccess) {
      point.stable = FloquetVerdict::kUndetermined;  // no verdict on a failed solve
    }
  };
  VectorX x;
  if (options.harmonics > 0) {
    solve(options.harmonics, &x, result.point);
    result.harmonics_used = options.harmonics;
    result.summary.error_estimate = result.point.error_estimate;
  } else {
    int H = 4;
    NhbPoint previous;
    solve(H, &x, previous);
    result.summary.status = Status::kToleranceNotMet;
    while (previous.status == Status::kSuccess && 2 * H <= options.max_harmonics) {
      NhbPoint next;
      solve(2 * H, &x, next);
      H *= 2;
      const double change = (next.rms - previous.rms).norm() / std::max(next.rms.norm(), 1e-300);
      previous = next;
      result.summary.error_estimate = change;
      if (next.status == Status::kSuccess && change <= options.harmonic_tolerance) {
        result.summary.status = Status::kSuccess;
        break;
      }
    }
    result.point = previous;
    result.harmonics_used = H;
    if (result.summary.status != Status::kSuccess && previous.status == Status::kSuccess) {
      result.summary.message = "H→2H RMS change above harmonic_tolerance at max_harmonics";
    }
  }
  if (result.point.status != Status::kSuccess) {
    result.summary.status = result.point.status;
    result.summary.message =
        "Newton did not converge (‖R‖∞ = " + std::to_string(result.point.residual_norm) + ")";
  }
  if (result.point.condensation_rcond < kNhbIllConditioned) {
    std::ostringstream w;
    w << std::setprecision(3)
      << "nonlinear HB: ill-conditioned condensation at Omega = " << result.point.omega
      << " rad/s (estimated 1/cond " << result.point.condensation_rcond
      << " of D_k or P D_k^-1 P^T): an undamped linear resonance? Expect lost digits";
    result.summary.warnings.push_back(w.str());
  }
  if (result.point.status == Status::kSuccess && !(jacobian_rcond >= kNhbIllConditioned)) {
    std::ostringstream w;
    w << std::setprecision(3)
      << "nonlinear HB: singular Jacobian at the solution at Omega = " << result.point.omega
      << " (estimated 1/cond " << jacobian_rcond
      << "): the periodic solution is not unique (zero damping with a harmonic k*Omega on a "
         "natural frequency, or a fold); this is one of them — add damping or check nearby "
         "frequencies";
    result.summary.warnings.push_back(w.str());
  }
  result.summary.counters["newton_iterations"] = newton;
  if (restarts > 0) result.summary.counters["newton_restarts"] = restarts;
  result.summary.counters["harmonics"] = result.harmonics_used;
  result.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn
