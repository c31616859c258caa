/// @file
/// @brief Pseudo-arclength continuation of the nonlinear HB in Ω (Keller), in scaled variables
/// ŷ = (x/x_scale, Ω/omega_scale).
/// * Predictor: the cubic through the last four points extrapolated in arclength (error
///   O(ds⁴)); the unit tangent t̂ (O(ds²)) for the first steps, after a rejected step and for
///   the sampled AFT (see `smooth` below: the chord and refined-tangent items also only apply
///   to exact integration; the sampled AFT takes a Newton step with a fresh LU every time).
/// * Corrector: [R(x, Ω); t̂ᵀ(ŷ − ŷ_pred)] = 0 by chord iterations with the bordered matrix
///   [J R_Ω; t̂_x/x_scale t̂_Ω/Ω_scale] factorised at some earlier point; re-factorised at the
///   iterate when a correction shrinks by less than kSlowContraction (then it is Newton).
/// * Tangent of a new point: after a cubic prediction, the derivative at the new point of the
///   cubic through it and the three points before (O(ds³), no Jacobian); otherwise the
///   solution of the new bordered matrix with right-hand side [0; 1] (so it keeps the
///   orientation), by iterative refinement of the previous tangent with the chord LU, or from
///   a fresh LU (the next chord matrix) when that contracts slowly. Most points cost one or
///   two residuals, one back-substitution and no Jacobian.
/// * Step control: cut by half on corrector failure, a tangent turn above max_tangent_angle
///   (curvature) or a fold in the step that is not located to fold_tolerance; ×1.5 after ≤ 1
///   Newton correction (≤ 3 chord corrections), ×0.7 after ≥ 4 (≥ 6).
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/common/check.hpp"
#include "nonlinear_hb/branch_search.hpp"
#include "nonlinear_hb/folds.hpp"

namespace geardyn {
namespace {

/// A chord correction larger than this fraction of the previous one re-factorises.
constexpr double kSlowContraction = 0.25;
/// Points of the polynomial (cubic) predictor.
constexpr size_t kPredictorNodes = 4;
/// Tangent refinement: relative size of the last step, and most refinement steps.
constexpr double kTangentTolerance = 1e-7;
constexpr int kTangentRefinements = 5;
/// Corrector fallback at fixed Ω only while the unit tangent advances in Ω by at least this
/// (scaled) fraction: near a fold a fixed-Ω solve has no solution or lands on the other branch.
constexpr double kFallbackTangentOmega = 0.2;
/// Undamped resonance: the response norm ‖x‖ doubled (kUndampedGrowth) while every point since
/// stayed within kUndampedBand·|Ω| of the frequency where the growth began, without a fold (a
/// vertical branch). A damped resonance of damping ratio ζ changes its amplitude by at most
/// √(1 + (δ/ζ)²) over a relative detuning δ, so doubling within 10⁻³ needs ζ < 6·10⁻⁴; an
/// undamped one (A ∝ 1/δ) doubles within 10⁻³ once it is within 2·10⁻³ of the resonance.
constexpr double kUndampedGrowth = 2.0;
constexpr double kUndampedBand = 1e-3;
/// Unbounded branch of a damped problem (issue 13: a two-flank branch of a clearance law, which
/// at amplitudes far above the clearance is homogeneous of degree one, so its amplitude grows as
/// 1/|Ω* − Ω| towards the Ω* where the large-amplitude linear system has a multiplier 1): the
/// trace stops once ‖x‖ has grown kUnboundedGrowth-fold since the smallest ‖x‖ of the branch (the
/// points since the last fold) and 1/‖x‖ is linear in Ω — the asymptote Ω* extrapolated from the
/// points at ‖x‖/4 → ‖x‖/2 and from ‖x‖/2 → ‖x‖ agree within kUnboundedConsistency of the
/// remaining distance |Ω* − Ω| — with Ω* within kUnboundedBand·|Ω| and within ζ/2·|Ω|, ζ the
/// problem's damping scale (max_i C_ii/(2 M_ii Ω)). A damped forced resonance of damping ratio ζ
/// reads as 1/δ only while δ ≫ ζ and bends within a few ζ of its peak, so its two
/// extrapolations disagree before it gets within ζ/2 (a test with ζ = 10⁻³ and the band alone
/// stopped a bounded resonance).
constexpr double kUnboundedGrowth = 32.0;
constexpr double kUnboundedConsistency = 0.05;
constexpr double kUnboundedBand = 0.02;
/// Two located folds of the same kind are the same fold when their Ω agree within kSameFold
/// (relative; above the fold tolerance and the sampled AFT's repeatability, ~1e-6 on the rig,
/// far below the distance of distinct folds) and their RMS within kSameFoldRms.
constexpr double kSameFold = 1e-5;
constexpr double kSameFoldRms = 1e-3;
/// ... and the trace went farther than kLoopSpan·|Ω| from the fold in between.
constexpr double kLoopSpan = 1e-2;

std::string OmegaText(const NhbContinuationOptions& c, double omega) {
  if (c.omega_text) return c.omega_text(omega);
  std::ostringstream s;
  s << std::setprecision(10) << "Omega = " << omega;
  return s.str();
}

struct UnboundedBranch {
  bool found = false;
  double omega = 0.0;   ///< extrapolated asymptote Ω*
  double growth = 0.0;  ///< ‖x‖ growth over the points used
};

/// The test of kUnboundedGrowth on the (Ω, ‖x‖) of the current branch (last = newest point).
UnboundedBranch DetectUnboundedBranch(const std::vector<std::array<double, 2>>& pts,
                                      double damping_scale) {
  UnboundedBranch out;
  if (pts.size() < 3) return out;
  const auto& p3 = pts.back();
  double smallest = p3[1];
  for (const auto& p : pts) smallest = std::min(smallest, p[1]);
  if (!(p3[1] >= kUnboundedGrowth * smallest)) return out;
  // The newest points at or below ‖x‖/2 and ‖x‖/4.
  const std::array<double, 2>*p2 = nullptr, *p1 = nullptr;
  for (auto it = pts.rbegin(); it != pts.rend(); ++it) {
    if (p2 == nullptr && (*it)[1] <= 0.5 * p3[1]) p2 = &*it;
    if (p2 != nullptr && (*it)[1] <= 0.25 * p3[1]) {
      p1 = &*it;
      break;
    }
  }
  if (p1 == nullptr || p2 == nullptr) return out;
  // Ω monotone over the three (no fold in between, but a kink could reverse Ω).
  if (!((p1->at(0) < p2->at(0) && p2->at(0) < p3[0]) ||
        (p1->at(0) > p2->at(0) && p2->at(0) > p3[0]))) {
    return out;
  }
  // Zero of the line through (Ω_a, 1/‖x_a‖), (Ω_b, 1/‖x_b‖).
  auto zero = [](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    const double ra = 1.0 / a[1], rb = 1.0 / b[1];
    return b[0] - rb * (b[0] - a[0]) / (rb - ra);
  };
  const double w12 = zero(*p1, *p2), w23 = zero(*p2, p3);
  const double remaining = std::abs(w23 - p3[0]);
  if (!std::isfinite(w12) || !std::isfinite(w23) || (w23 - p3[0]) * (p3[0] - p2->at(0)) <= 0.0 ||
      std::abs(w12 - w23) > kUnboundedConsistency * remaining ||
      remaining >
          std::min(kUnboundedBand, 0.5 * damping_scale / std::abs(p3[0])) * std::abs(p3[0])) {
    return out;
  }
  out.found = true;
  out.omega = w23;
  out.growth = p3[1] / p1->at(1);
  return out;
}

}  // namespace

namespace internal {

NhbCurve TraceWithHarmonics(const NhbProblem& problem, const NhbOptions& options,
                            const NhbContinuationOptions& c, int H, BranchStart* from) {
  NhbCurve curve;
  curve.harmonics_used = H;
  NhbSolver solver(problem, options, H);
  const int n = problem.law->num_coordinates();
  const int m = solver.num_unknowns();
  // The accelerations (polynomial predictor, chord corrector, refined tangents) need a smooth
  // residual: exact integration. The sampled AFT residual has kinks (a sample crossing a
  // contact boundary) that a cubic extrapolation amplifies and a stale Jacobian cannot follow,
  // so there every corrector iteration is a Newton step from the tangent predictor.
  const bool smooth = solver.exact_integration();
  (void)n;
  const double direction = c.omega_end > c.omega_start ? 1.0 : -1.0;
  // A branch-search trace starts from its solution and stops where it leaves the range.
  double omega = from ? from->omega : c.omega_start;
  VectorX x = from ? from->x : solver.ContactGuess(omega);
  Status status;
  double rn = 0.0;
  long newton = solver.Newton(x, omega, &status, &rn);
  if (status != Status::kSuccess) {
    curve.summary.status = status;
    curve.summary.message = "no solution at the start, " + OmegaText(c, omega) +
                            " (Newton ‖R‖∞ = " + std::to_string(rn) + ")";
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
  auto scaled_unit = [&](const VectorX& v) {
    VectorX u(m + 1);
    u.head(m) = v.head(m) / sx;
    u[m] = v[m] / so;
    return VectorX(u / u.norm());
  };
  auto tangent = [&]() {
    rhs.setZero();
    rhs[m] = 1.0;
    z = lu.solve(rhs);
    return scaled_unit(z);
  };
  VectorX t = VectorX::Zero(m + 1);
  // B z = e_{m+1} by iterative refinement from the previous tangent with the (stale) chord LU.
  // Converged when a refinement step is below kTangentTolerance of z (a residual test would
  // not do: J is nearly singular along the tangent at a fold); false when the steps contract
  // slowly (then re-factorise).
  VectorX tangent_step(m + 1);
  auto refine_tangent = [&]() {
    z.head(m) = sx * t.head(m);
    z[m] = so * t[m];
    double previous = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kTangentRefinements; ++k) {
      rhs.setZero();
      rhs[m] = 1.0;
      rhs.noalias() -= B * z;
      tangent_step = lu.solve(rhs);
      z += tangent_step;
      const double step = tangent_step.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(step) || step > kSlowContraction * previous) return false;
      if (step <= kTangentTolerance * z.lpNorm<Eigen::Infinity>()) return true;
      previous = step;
    }
    return false;
  };

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
      point.stable = NhbVerdict(point.max_multiplier, options.stability_margin);
    }
    curve.points.push_back(std::move(point));
    if (c.progress) c.progress(static_cast<int>(curve.points.size()), om);
  };
  record(x, omega, static_cast<int>(newton), rn);
  std::vector<double> steps{0.0};

  double ds = c.initial_step;
  const double tol_scale = options.newton_tolerance;
  // The residual tolerance: the larger of tol·(1 + ‖f₀‖∞ + |f₁|∞) and Newton's own,
  // tol·(1 + max ‖F̃_k‖∞) at the predicted Ω. Issue 13: a gear system's f₀ is in torques on the
  // flexible coordinates (≈ 100 N·m) while its residual is in mesh forces (F̃_0 ≈ 1 400 N), so
  // the first scale alone was 14× tighter than the Newton that found the first point, down at
  // the level where the sampled AFT's kinks stall the corrector: steps were rejected to min_step.
  const double force_tol = tol_scale * (1.0 + problem.force_mean.lpNorm<Eigen::Infinity>() +
                                        problem.force_amplitude.cwiseAbs().maxCoeff());
  VectorX xp(m), xc(m);
  double op_predicted = 0.0;
  long rejected = 0;
  long factorisations = 1;
  long fallbacks = 0;  // corrector failures solved at fixed Ω by NhbSolver::Newton
  // The factorised bordered matrix of the last accepted point (its Jacobian and tangent row)
  // is the chord matrix of the next corrector; restored after a rejected step.
  auto factor_at_accepted = [&]() {
    assemble(x, omega, t);
    lu.compute(B);
    ++factorisations;
  };
  // Last accepted points (x, Ω) and their scaled arclength positions, for the predictor.
  std::vector<VectorX> history{VectorX(m + 1)};
  history[0] << x, omega;
  std::vector<double> history_s{0.0};
  bool tangent_predictor = false;  // after a rejected step: the first-order predictor
  std::vector<NhbFold> located;    // folds located during the trace
  long fold_evaluations = 0;
  // Undamped-resonance watch: Ω and ‖x‖ where the current narrow frequency band began.
  double band_omega = omega;
  double band_norm = x.norm();
  // Unbounded-branch watch: (Ω, ‖x‖) of the points since the last fold.
  const bool damped = !problem.damping.isZero(0.0);
  // The damping scale [1/s]: max_i C_ii/(2 M_ii), so that ζ ≈ damping_rate/Ω (exact for one
  // DOF). A damped forced resonance saturates within ~ζΩ of its frequency, so a 1/|Ω* − Ω| growth
  // is taken as unbounded only within ζΩ/2 of Ω* (ζ = 10⁻³ on the B&K oscillator: no stop).
  double damping_rate = 0.0;
  for (Eigen::Index i = 0; i < problem.mass.rows(); ++i) {
    if (problem.mass(i, i) > 0) {
      damping_rate = std::max(damping_rate, problem.damping(i, i) / (2.0 * problem.mass(i, i)));
    }
  }
  std::vector<std::array<double, 2>> branch_norms{{omega, x.norm()}};
  while (static_cast<int>(curve.points.size()) < c.max_points) {
    if (c.cancel != nullptr && c.cancel->load()) {
      curve.summary.status = Status::kInterrupted;
      curve.summary.message =
          "interrupted after " + std::to_string(curve.points.size()) + " points";
      break;
    }
    // The step taken: ds, capped so that the predicted |ΔΩ| ≤ max_omega_step.
    double step = ds;
    if (c.max_omega_step > 0 && std::abs(t[m]) * so * step > c.max_omega_step) {
      step = c.max_omega_step / (std::abs(t[m]) * so);
    }
    if (smooth && history.size() == kPredictorNodes && !tangent_predictor) {
      // Cubic extrapolation in arclength through the last four points (error O(ds⁴) instead
      // of the tangent's O(ds²): the chord corrector then needs a correction or two).
      const double target = history_s.back() + step;
      VectorX y = VectorX::Zero(m + 1);
      for (size_t j = 0; j < kPredictorNodes; ++j) {
        double w = 1.0;
        for (size_t l = 0; l < kPredictorNodes; ++l) {
          if (l != j) w *= (target - history_s[l]) / (history_s[j] - history_s[l]);
        }
        y += w * history[j];
      }
      xp = y.head(m);
      op_predicted = y[m];
    } else {
      xp = x + step * sx * t.head(m);
      op_predicted = omega + step * so * t[m];
    }
    const double op = op_predicted;
    const double tol = std::max(force_tol, solver.ResidualTolerance(op));
    xc = xp;
    double oc = op;
    bool converged = false;
    int it = 0;
    double res = 0.0;
    double previous_correction = 0.0;
    double tol_it = tol;
    bool assembled = false;  // B holds the bordered matrix at (xc, oc)
    for (; it <= c.max_corrector_iterations; ++it) {
      if (smooth) {
        solver.Evaluate(xc, oc, &R, nullptr, nullptr);
      } else {
        assemble(xc, oc, t);  // Newton: the Jacobian of every iterate
      }
      assembled = !smooth;
      res = R.lpNorm<Eigen::Infinity>();
      if (!std::isfinite(res)) break;
      // Relative to the residual's largest term too: on a branch growing without bound (issue
      // 13: the spur pair's two-flank branch at 260 µm carries 1.6e5 N in N_k against a 1.4e3 N
      // excitation) the round-off of R exceeds the excitation-scaled tolerance.
      tol_it = std::max(tol, tol_scale * solver.LastLawForceNorm());
      if (res <= tol_it) {
        converged = true;
        break;
      }
      if (it == c.max_corrector_iterations) break;
      rhs.head(m) = -R;
      rhs[m] = -(t.head(m).dot(xc - xp) / sx + t[m] * (oc - op) / so);
      if (!smooth) {
        lu.compute(B);
        ++factorisations;
      }
      z = lu.solve(rhs);
      double correction = z.lpNorm<Eigen::Infinity>();
      // Chord steps contract slowly once the matrix is stale: re-factorise at the iterate
      // (a full Newton step), keeping the contraction fast.
      if (smooth && it > 0 && correction > kSlowContraction * previous_correction) {
        assemble(xc, oc, t);
        lu.compute(B);
        ++factorisations;
        z = lu.solve(rhs);
        correction = z.lpNorm<Eigen::Infinity>();
      }
      if (!z.allFinite()) break;
      previous_correction = correction;
      xc += z.head(m);
      oc += z[m];
      // Stagnation at the residual floor: a correction below round-off of the state counts as
      // converged once the residual is small. x and Ω each against their own size: Ω of a gear
      // system is ~1e4 rad/s while x is ~1e-5 m, and one absolute bound never held for both.
      if (z.head(m).lpNorm<Eigen::Infinity>() <= 1e-13 * (1.0 + xc.lpNorm<Eigen::Infinity>()) &&
          std::abs(z[m]) <= 1e-13 * (1.0 + std::abs(oc)) && res <= 1e3 * tol_it) {
        solver.Evaluate(xc, oc, &R, nullptr, nullptr);
        assembled = false;
        res = R.lpNorm<Eigen::Infinity>();
        converged = true;
        ++it;
        break;
      }
    }
    newton += it + 1;
    // Fallback (issue 13): the bordered corrector on the sampled AFT residual can cycle at a
    // contact switch (a sample crossing the contact boundary: the Jacobian of one side, the
    // root on the other). Away from folds (the tangent still advances in Ω) the point at the
    // predicted Ω is solved by NhbSolver::Newton instead — damped Newton, then Powell's dogleg
    // — and kept when it lies within one step of the prediction (the same branch), before the
    // step is cut.
    if (!converged && std::abs(t[m]) >= kFallbackTangentOmega && op > 0 && xp.allFinite()) {
      VectorX xf = xp;
      Status fallback_status = Status::kNotConverged;
      double fallback_res = 0.0;
      const int fallback_it = solver.Newton(xf, op, &fallback_status, &fallback_res);
      newton += fallback_it;
      if (fallback_status == Status::kSuccess && (xf - xp).norm() / sx <= ds) {
        xc = xf;
        oc = op;
        res = fallback_res;
        it = c.max_corrector_iterations;  // a hard step: it will not grow
        converged = true;
        assembled = false;
        ++fallbacks;
      }
    }
    VectorX t_new;
    bool accept = converged && oc > 0;
    const bool cubic = smooth && history.size() == kPredictorNodes && !tangent_predictor;
    if (accept && cubic) {
      // The derivative at the new point of the cubic through it and the three points before
      // (O(ds³)): no Jacobian, no solve. Lagrange weights differentiated at the last node.
      const double s_new = history_s.back() + std::hypot((xc - x).norm() / sx, (oc - omega) / so);
      std::array<double, kPredictorNodes> nodes{};
      for (size_t j = 0; j + 1 < kPredictorNodes; ++j) nodes[j] = history_s[j + 1];
      nodes[kPredictorNodes - 1] = s_new;
      VectorX derivative = VectorX::Zero(m + 1);
      for (size_t j = 0; j < kPredictorNodes; ++j) {
        double w = 0.0;
        if (j + 1 == kPredictorNodes) {
          for (size_t l = 0; l + 1 < kPredictorNodes; ++l) w += 1.0 / (s_new - nodes[l]);
        } else {
          w = 1.0 / (nodes[j] - s_new);
          for (size_t l = 0; l + 1 < kPredictorNodes; ++l) {
            if (l != j) w *= (s_new - nodes[l]) / (nodes[j] - nodes[l]);
          }
        }
        if (j + 1 == kPredictorNodes) {
          derivative.head(m) += w * xc;
          derivative[m] += w * oc;
        } else {
          derivative += w * history[j + 1];
        }
      }
      t_new = scaled_unit(derivative);
    } else if (accept) {
      // The tangent at the new point from its bordered matrix: iterative refinement of the
      // previous tangent with the chord LU, or a fresh factorisation (the next chord matrix)
      // when the refinement contracts slowly.
      if (!assembled) assemble(xc, oc, t);
      if (!smooth || !refine_tangent()) {
        lu.compute(B);
        ++factorisations;
        t_new = tangent();
      } else {
        t_new = scaled_unit(z);
      }
    }
    if (accept) {
      const double cosang = std::clamp(t_new.dot(t), -1.0, 1.0);
      // The curvature limit is a quality control, not a convergence condition: below
      // 1000·min_step a converged point is kept even at a sharp turn (a kink of the AFT curve).
      if (std::acos(cosang) > c.max_tangent_angle && step > 1e3 * c.min_step) accept = false;
    }
    // A fold between the last point and this one is located here, before the step is
    // accepted: when the located fold misses fold_tolerance (the bracket holds more than a
    // simple fold, or a bordered solve failed at a kink of the curve), the step is retried at
    // half the length, as for a sharp turn; below 1000·min_step the fold is kept with its
    // error estimate (and a warning).
    internal::FoldLocation loc;
    bool fold_here = false;
    if (accept && (t_new[m] > 0) != (t[m] > 0) && (oc - c.omega_end) * direction < 0) {
      VectorX ya(m + 1), yb(m + 1);
      ya << x, omega;
      yb << xc, oc;
      loc = internal::LocateFold(solver, ya, t, yb, sx, so, tol, c.fold_tolerance,
                                 c.max_corrector_iterations);
      fold_evaluations += loc.evaluations;
      fold_here = true;
      if (!loc.converged && step > 1e3 * c.min_step) accept = false;
    }
    if (!accept) {
      ++rejected;
      tangent_predictor = true;
      if (smooth) factor_at_accepted();  // the sampled path factorises every iterate anyway
      ds = 0.5 * step;
      if (ds < c.min_step) {
        curve.summary.status = Status::kNotConverged;
        curve.summary.message =
            "continuation step fell below min_step at " + OmegaText(c, omega) +
            " (the corrector does not converge on any smaller step: a bifurcation, a grazing "
            "contact or an ill-posed problem)";
        break;
      }
      continue;
    }
    {
      // Accepted: shift the predictor history (chord length as the arclength increment).
      VectorX y(m + 1);
      y << xc, oc;
      const double chord = std::hypot((xc - x).norm() / sx, (oc - omega) / so);
      if (history.size() == kPredictorNodes) {
        history.erase(history.begin());
        history_s.erase(history_s.begin());
      }
      history_s.push_back(history_s.back() + chord);
      history.push_back(std::move(y));
      tangent_predictor = false;
    }
    if ((oc - c.omega_end) * direction >= 0) {
      // The step reached or passed the end of the range: the last point is the solution at
      // exactly omega_end, by Newton at fixed Ω from the linear interpolation of the step.
      const double w = (c.omega_end - omega) / (oc - omega);
      VectorX x_end = x + w * (xc - x);
      Status end_status;
      double end_res = 0.0;
      const long end_it = solver.Newton(x_end, c.omega_end, &end_status, &end_res);
      newton += end_it;
      if (end_status != Status::kSuccess) {
        curve.summary.status = end_status;
        curve.summary.message = "no solution at the end of the range, " +
                                OmegaText(c, c.omega_end) +
                                " (Newton ‖R‖∞ = " + std::to_string(end_res) + ")";
        break;
      }
      const double chord = std::hypot((x_end - x).norm() / sx, (c.omega_end - omega) / so);
      assemble(x_end, c.omega_end, t);
      lu.compute(B);
      ++factorisations;
      t = tangent();
      x = x_end;
      omega = c.omega_end;
      record(x, omega, static_cast<int>(end_it), end_res);
      steps.push_back(chord);
      break;
    }
    if (fold_here) {
      // A fold between the last point and this one, located above.
      if (std::isfinite(loc.error)) {
        // A closed branch (an isola, or the loops of an undamped system): the trace comes back
        // to a fold it has located before, and would cycle until max_points.
        NhbPoint at_fold;
        solver.Describe(loc.y.head(m), loc.y[m], at_fold);
        // The loop must have left the fold's neighbourhood: the sampled AFT's micro-zigzags
        // put folds of the same kind within ~1e-4 Ω of each other (see folds.cpp).
        auto left_fold = [&](const NhbFold& f) {
          for (size_t i = static_cast<size_t>(f.index) + 1; i < curve.points.size(); ++i) {
            if (std::abs(curve.points[i].omega - f.omega) > kLoopSpan * std::abs(f.omega)) {
              return true;
            }
          }
          return false;
        };
        const auto seen = std::find_if(located.begin(), located.end(), [&](const NhbFold& f) {
          return f.omega_maximum == (t[m] > 0) &&
                 std::abs(f.omega - loc.omega) <= kSameFold * std::abs(loc.omega) &&
                 std::abs(f.rms - at_fold.rms[0]) <= kSameFoldRms * std::abs(f.rms) && left_fold(f);
        });
        if (seen != located.end() && from != nullptr) {
          from->closed = true;  // an isola, traced once around: the result, not a failure
          break;
        }
        if (seen != located.end()) {
          std::ostringstream msg;
          msg << "the branch closed on itself: it came back to the fold at "
              << OmegaText(c, seen->omega) << " after "
              << static_cast<long>(curve.points.size()) - 1 - seen->index
              << " more points (a closed loop, e.g. of an undamped system); the end of the "
              << "range is not on it";
          curve.summary.status = Status::kNotConverged;
          curve.summary.message = msg.str();
          break;
        }
        const NhbPoint& at = at_fold;
        NhbFold fold;
        fold.omega = loc.omega;
        fold.omega_error = loc.error;
        fold.located = loc.converged;
        fold.rms = at.rms[0];
        fold.maximum = at.maximum[0];
        fold.minimum = at.minimum[0];
        fold.index = static_cast<int>(curve.points.size()) - 1;
        fold.omega_maximum = t[m] > 0;
        located.push_back(fold);
      }
    }
    x = xc;
    omega = oc;
    t = t_new;
    if (from != nullptr && (omega - c.omega_start) * direction < 0) break;  // left the range
    if ((omega - c.omega_start) * direction < -0.5 * std::abs(c.omega_end - c.omega_start)) {
      curve.summary.warnings.push_back(
          "the curve turned back past the start of the range (at " + OmegaText(c, omega) +
          ", half the range beyond the start): stopped before the end of the range");
      break;
    }
    record(x, omega, it + 1, res);
    steps.push_back(step);
    {
      // Undamped resonance: a vertical branch (see kUndampedGrowth).
      const double norm = x.norm();
      const bool fold = curve.points.size() >= 2 &&
                        (curve.points[curve.points.size() - 2].tangent_omega > 0) != (t[m] > 0);
      if (fold) branch_norms.clear();
      branch_norms.push_back({omega, norm});
      if (damped) {
        const UnboundedBranch u = DetectUnboundedBranch(branch_norms, damping_rate);
        if (u.found) {
          std::ostringstream msg;
          msg << std::setprecision(6) << "the branch grows without bound towards "
              << OmegaText(c, u.omega) << " (extrapolated from 1/‖x‖, linear in the frequency "
              << "over the last " << std::setprecision(3) << u.growth << "-fold growth): its "
              << "amplitude is unbounded there, so the trace of this branch stops at "
              << OmegaText(c, omega);
          curve.summary.warnings.push_back(msg.str());
          curve.unbounded_branches.push_back({u.omega, omega});
          break;
        }
      }
      if (fold || std::abs(omega - band_omega) > kUndampedBand * std::abs(band_omega)) {
        band_omega = omega;
        band_norm = norm;
      } else if (norm > kUndampedGrowth * band_norm) {
        std::ostringstream msg;
        msg << std::setprecision(3)
            << (damped ? "sharp resonance near " : "undamped resonance near ")
            << OmegaText(c, omega) << ": the response grew " << norm / band_norm
            << "-fold while the frequency stayed "
            << "within " << 100 * kUndampedBand << " % ";
        // A damped problem can meet a mode that its damping hardly reaches (the helical pair's
        // rocking mode, ζ = 8e-5 with mesh damping only): its peak is bounded but too sharp to
        // trace; only an undamped problem is known to grow without bound here.
        if (damped) {
          msg << "(a resonance too sharp to trace: a mode with little or no damping); add "
                 "damping to that mode (bearing damping or scene-level modal damping)";
        } else {
          msg << "(a vertical branch: nothing damps this resonance, and the periodic response "
                 "grows without bound); add damping";
        }
        curve.summary.status = Status::kNotConverged;
        curve.summary.message = msg.str();
        curve.undamped_resonance_omega = omega;
        break;
      }
    }
    // Chord iterations (smooth residual) contract linearly, and each costs one residual (no
    // Jacobian, no factorisation) while every point costs its monodromy, description and
    // tangent: two more corrections than Newton's are normal before the step shrinks (issue
    // 13: with one, the rig sweep placed 3 075 points where 1 664 give the same curve, folds
    // and verdicts; with three the 1 475 Hz fold was no longer located to fold_tolerance).
    const int extra = smooth ? 2 : 0;
    if (it <= 1 + extra) ds = std::min(ds * 1.5, c.max_step);
    if (it >= 4 + extra) ds = std::max(ds * 0.7, c.min_step);
  }
  if (static_cast<int>(curve.points.size()) >= c.max_points && curve.summary.ok()) {
    // The range was not covered: not a result.
    curve.summary.status = Status::kNotConverged;
    curve.summary.message = "max_points (" + std::to_string(c.max_points) + ") reached at " +
                            OmegaText(c, omega) + " before the end of the range, " +
                            OmegaText(c, c.omega_end);
  }
  internal::FindFoldsAndJumps(curve, steps, so, located);
  for (const NhbFold& fold : curve.folds) {
    if (!fold.located) {
      std::ostringstream w;
      w << std::setprecision(3) << "fold near " << OmegaText(c, fold.omega)
        << " not located to fold_tolerance " << c.fold_tolerance << " (estimated relative error "
        << fold.omega_error / std::abs(fold.omega) << ")";
      curve.summary.warnings.push_back(w.str());
    }
  }
  // The worst conditioning of the condensation along the curve, once.
  const NhbPoint* worst = nullptr;
  for (const NhbPoint& pt : curve.points) {
    if (worst == nullptr || pt.condensation_rcond < worst->condensation_rcond) worst = &pt;
  }
  if (worst != nullptr && worst->condensation_rcond < kNhbIllConditioned) {
    std::ostringstream w;
    w << std::setprecision(3) << "nonlinear HB: ill-conditioned condensation (estimated 1/cond "
      << "down to " << worst->condensation_rcond << " at " << OmegaText(c, worst->omega)
      << "): an undamped linear resonance? Expect lost digits";
    curve.summary.warnings.push_back(w.str());
  }
  // A point whose multipliers came out non-finite has no verdict (issue 12): the curve's status
  // says so, as the linear HB's undetermined verdicts do.
  long undetermined = 0;
  const NhbPoint* first_undetermined = nullptr;
  for (const NhbPoint& pt : curve.points) {
    if (pt.stable != FloquetVerdict::kUndetermined) continue;
    ++undetermined;
    if (first_undetermined == nullptr) first_undetermined = &pt;
  }
  if (first_undetermined != nullptr && curve.summary.ok()) {
    std::ostringstream w;
    w << std::setprecision(10) << "stability undetermined (non-finite max |mu|) at " << undetermined
      << " point(s), the first at Omega = " << first_undetermined->omega << " rad/s";
    curve.summary.status = Status::kNumericalIssue;
    curve.summary.message = w.str();
  }
  curve.summary.counters["undetermined_verdicts"] = undetermined;
  double err = 0.0;
  for (const NhbPoint& pt : curve.points) err = std::max(err, pt.error_estimate);
  curve.summary.error_estimate = err;
  curve.summary.counters["points"] = static_cast<long>(curve.points.size());
  curve.summary.counters["newton_iterations"] = newton;
  curve.summary.counters["rejected_steps"] = rejected;
  curve.summary.counters["factorisations"] = factorisations;
  curve.summary.counters["newton_fallbacks"] = fallbacks;
  curve.summary.counters["folds"] = static_cast<long>(curve.folds.size());
  curve.summary.counters["fold_solves"] = fold_evaluations;
  curve.summary.counters["harmonics"] = H;
  return curve;
}

}  // namespace internal

NhbCurve TraceNonlinearHarmonicBalance(const NhbProblem& problem, const NhbOptions& options,
                                       const NhbContinuationOptions& continuation) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  GEARDYN_THROW_UNLESS(problem.IsValid(&why), "nonlinear HB problem: " << why);
  GEARDYN_THROW_UNLESS(options.IsValid(&why), "nonlinear HB options: " << why);
  GEARDYN_THROW_UNLESS(continuation.IsValid(&why), "nonlinear HB continuation: " << why);
  NhbCurve curve;
  using internal::TraceWithHarmonics;
  if (options.harmonics > 0) {
    curve = TraceWithHarmonics(problem, options, continuation, options.harmonics, nullptr);
  } else {
    for (int H = 8; H <= options.max_harmonics; H *= 2) {
      curve = TraceWithHarmonics(problem, options, continuation, H, nullptr);
      if (!curve.summary.ok() || curve.summary.error_estimate <= options.harmonic_tolerance) break;
    }
    if (curve.summary.ok() && curve.summary.error_estimate > options.harmonic_tolerance) {
      curve.summary.status = Status::kToleranceNotMet;
      curve.summary.message = "top-harmonic energy above harmonic_tolerance at max_harmonics";
    }
  }
  if (continuation.branch_search > 0 && !curve.points.empty() &&
      curve.summary.status != Status::kNotConverged) {
    internal::SearchBranches(problem, options, continuation, curve);
  }
  curve.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return curve;
}

}  // namespace geardyn
