/// @file
/// @brief Pseudo-arclength continuation of the nonlinear HB in Ω (Keller): predictor along the
/// unit tangent t̂ in scaled variables (x/x_scale, Ω/omega_scale), corrector Newton on
/// [R(x, Ω); t̂ᵀ(ŷ − ŷ_pred)] = 0 with the bordered Jacobian [J R_Ω; t̂_x/x_scale t̂_Ω/Ω_scale];
/// the new tangent solves the same bordered matrix with right-hand side [0; 1] (so it keeps
/// the orientation). Step control: cut by half on corrector failure or a tangent turn above
/// max_tangent_angle (curvature), ×1.5 after ≤ 2 corrector iterations, ×0.7 after ≥ 5.
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/common/check.hpp"
#include "nonlinear_hb/folds.hpp"

namespace geardyn {
namespace {

NhbCurve TraceWithHarmonics(const NhbProblem& problem, const NhbOptions& options,
                            const NhbContinuationOptions& c, int H) {
  NhbCurve curve;
  curve.harmonics_used = H;
  NhbSolver solver(problem, options, H);
  const int n = problem.law->num_coordinates();
  const int m = solver.num_unknowns();
  (void)n;
  const double direction = c.omega_end > c.omega_start ? 1.0 : -1.0;
  double omega = c.omega_start;
  VectorX x = solver.ContactGuess(omega);
  Status status;
  double rn = 0.0;
  long newton = solver.Newton(x, omega, &status, &rn);
  if (status != Status::kSuccess) {
    curve.summary.status = status;
    curve.summary.message = "no solution at omega_start (Newton ‖R‖∞ = " + std::to_string(rn) + ")";
    return curve;
  }
  const double sx = c.x_scale > 0 ? c.x_scale : std::max(x.norm(), 1e-12);
  const double so = c.omega_scale > 0 ? c.omega_scale : std::abs(c.omega_end - c.omega_start);
  // Force scale of the Newton tolerance: as in NhbSolver::Newton.
  VectorX R(m), dR(m), rhs(m + 1), z(m + 1);
  MatrixX J(m, m), B(m + 1, m + 1);
  Eigen::PartialPivLU<MatrixX> lu(m + 1);

  // Bordered matrix at (x, Ω) with the last row from the scaled tangent t.
  auto assemble = [&](const VectorX& xx, double om, const VectorX& t) {
    solver.Evaluate(xx, om, &R, &J, &dR);
    B.topLeftCorner(m, m) = J;
    B.topRightCorner(m, 1) = dR;
    B.bottomLeftCorner(1, m) = t.head(m).transpose() / sx;
    B(m, m) = t[m] / so;
  };
  // Unit tangent (scaled) from the factorised bordered matrix.
  auto tangent = [&]() {
    rhs.setZero();
    rhs[m] = 1.0;
    z = lu.solve(rhs);
    VectorX t(m + 1);
    t.head(m) = z.head(m) / sx;
    t[m] = z[m] / so;
    return VectorX(t / t.norm());
  };

  VectorX t = VectorX::Zero(m + 1);
  t[m] = direction;
  assemble(x, omega, t);
  lu.compute(B);
  t = tangent();

  auto record = [&](const VectorX& xx, double om, int iterations, double residual) {
    NhbPoint point;
    solver.Describe(xx, om, point);
    point.newton_iterations = iterations;
    point.residual_norm = residual;
    point.tangent_omega = t[m];
    if (options.stability != NhbStabilityMethod::kNone) {
      point.max_multiplier = solver.MaxMultiplier(xx, om);
      point.stable = point.max_multiplier < 1.0 + options.stability_margin;
    }
    curve.points.push_back(std::move(point));
    if (c.progress) c.progress(static_cast<int>(curve.points.size()), om);
  };
  record(x, omega, static_cast<int>(newton), rn);
  std::vector<double> steps{0.0};

  double ds = c.initial_step;
  const double tol_scale = options.newton_tolerance;
  VectorX xp(m), xc(m);
  long rejected = 0;
  while (static_cast<int>(curve.points.size()) < c.max_points) {
    xp = x + ds * sx * t.head(m);
    const double op = omega + ds * so * t[m];
    xc = xp;
    double oc = op;
    bool converged = false;
    int it = 0;
    double res = 0.0;
    for (; it <= c.max_corrector_iterations; ++it) {
      assemble(xc, oc, t);
      // Scale as NhbSolver::Newton: 1 + max ‖F̃_k‖∞ is not exposed; use 1 + ‖f₀‖∞ + |f₁|∞.
      const double scale = 1.0 + problem.force_mean.lpNorm<Eigen::Infinity>() +
                           problem.force_amplitude.cwiseAbs().maxCoeff();
      res = R.lpNorm<Eigen::Infinity>();
      lu.compute(B);
      if (!std::isfinite(res)) break;
      if (res <= tol_scale * scale) {
        converged = true;
        break;
      }
      if (it == c.max_corrector_iterations) break;
      rhs.head(m) = -R;
      rhs[m] = -(t.head(m).dot(xc - xp) / sx + t[m] * (oc - op) / so);
      z = lu.solve(rhs);
      if (!z.allFinite()) break;
      xc += z.head(m);
      oc += z[m];
      // Stagnation at the residual floor (a sample sitting on a kink of g): a Newton step
      // below round-off of the state counts as converged once the residual is small.
      if (z.lpNorm<Eigen::Infinity>() <= 1e-13 * (1.0 + xc.lpNorm<Eigen::Infinity>()) &&
          R.lpNorm<Eigen::Infinity>() <= 1e3 * tol_scale * scale) {
        assemble(xc, oc, t);
        lu.compute(B);
        res = R.lpNorm<Eigen::Infinity>();
        converged = true;
        ++it;
        break;
      }
    }
    newton += it + 1;
    VectorX t_new;
    bool accept = converged && oc > 0;
    if (accept) {
      t_new = tangent();
      const double cosang = std::clamp(t_new.dot(t), -1.0, 1.0);
      // The curvature limit is a quality control, not a convergence condition: below
      // 1000·min_step a converged point is kept even at a sharp turn (a kink of the AFT curve).
      if (std::acos(cosang) > c.max_tangent_angle && ds > 1e3 * c.min_step) accept = false;
    }
    if (!accept) {
      ++rejected;
      ds *= 0.5;
      if (ds < c.min_step) {
        curve.summary.status = Status::kNotConverged;
        curve.summary.message =
            "continuation step fell below min_step at Ω = " + std::to_string(omega);
        break;
      }
      continue;
    }
    x = xc;
    omega = oc;
    t = t_new;
    if ((omega - c.omega_end) * direction > 0) break;  // passed the end of the range
    if ((omega - c.omega_start) * direction < -0.5 * std::abs(c.omega_end - c.omega_start)) {
      curve.summary.warnings.push_back("curve turned back below omega_start; stopped");
      break;
    }
    record(x, omega, it + 1, res);
    steps.push_back(ds);
    if (it + 1 <= 2) ds = std::min(ds * 1.5, c.max_step);
    if (it + 1 >= 5) ds = std::max(ds * 0.7, c.min_step);
  }
  if (static_cast<int>(curve.points.size()) >= c.max_points) {
    curve.summary.warnings.push_back("max_points reached before omega_end");
  }
  internal::FindFoldsAndJumps(curve, steps, so);
  double err = 0.0;
  for (const NhbPoint& pt : curve.points) err = std::max(err, pt.error_estimate);
  curve.summary.error_estimate = err;
  curve.summary.counters["points"] = static_cast<long>(curve.points.size());
  curve.summary.counters["newton_iterations"] = newton;
  curve.summary.counters["rejected_steps"] = rejected;
  curve.summary.counters["folds"] = static_cast<long>(curve.folds.size());
  curve.summary.counters["harmonics"] = H;
  return curve;
}

}  // namespace

NhbCurve TraceNonlinearHarmonicBalance(const NhbProblem& problem, const NhbOptions& options,
                                       const NhbContinuationOptions& continuation) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  GEARDYN_THROW_UNLESS(problem.IsValid(&why), "nonlinear HB problem: " << why);
  GEARDYN_THROW_UNLESS(options.IsValid(&why), "nonlinear HB options: " << why);
  GEARDYN_THROW_UNLESS(continuation.IsValid(&why), "nonlinear HB continuation: " << why);
  NhbCurve curve;
  if (options.harmonics > 0) {
    curve = TraceWithHarmonics(problem, options, continuation, options.harmonics);
  } else {
    for (int H = 8; H <= options.max_harmonics; H *= 2) {
      curve = TraceWithHarmonics(problem, options, continuation, H);
      if (!curve.summary.ok() || curve.summary.error_estimate <= options.harmonic_tolerance) break;
    }
    if (curve.summary.ok() && curve.summary.error_estimate > options.harmonic_tolerance) {
      curve.summary.status = Status::kToleranceNotMet;
      curve.summary.message = "top-harmonic energy above harmonic_tolerance at max_harmonics";
    }
  }
  curve.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return curve;
}

}  // namespace geardyn
