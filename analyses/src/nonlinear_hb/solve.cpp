/// @file
/// @brief SolveNonlinearHarmonicBalance: one Ω, given H or H doubled from 4 until the relative
/// H→2H change of the RMS of u is below the tolerance (each solve starts from the previous
/// solution, zero-padded).
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
  auto solve = [&](int H, VectorX* x, NhbPoint& point) {
    NhbSolver solver(problem, options, H);
    *x = x->size() == 0 ? solver.ContactGuess(omega) : NhbSolver::Resize(*x, n, H);
    Status status;
    double rn = 0.0;
    point.newton_iterations = solver.Newton(*x, omega, &status, &rn);
    newton += point.newton_iterations;
    point.status = status;
    point.residual_norm = rn;
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
  result.summary.counters["newton_iterations"] = newton;
  result.summary.counters["harmonics"] = result.harmonics_used;
  result.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn
