// kMagnus: Gauss–Legendre Magnus integrators of order 4 and 6 for ż = A(t) z, with the number of
// equal steps per period chosen from the tolerance by a Richardson estimate on the multipliers.
//
// Order 4 (2 nodes c = 1/2 ∓ √3/6): Ω = h/2 (A1 + A2) + (√3/12) h² [A2, A1]
//   (Iserles & Nørsett 1999; Blanes, Casas, Oteo & Ros, Phys. Rep. 470 (2009) Eq. (4.x)).
// Order 6 (3 nodes c = 1/2 − √15/10, 1/2, 1/2 + √15/10), Blanes–Casas–Oteo–Ros 2009 Eq. (253):
//   α1 = h A2, α2 = (√15/3) h (A3 − A1), α3 = (10/3) h (A3 − 2A2 + A1),
//   C1 = [α1, α2], C2 = −(1/60) [α1, 2α3 + C1],
//   Ω = α1 + α3/12 + (1/240) [−20α1 − α3 + C1, α2 + C2].
// Each step multiplies by expm(Ω) (Eigen's scaling-and-squaring Padé); the running product is
// normalized (ScaledMatrix) so that long periods do not overflow.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn::internal {
namespace {

inline MatrixX Commutator(const MatrixX& X, const MatrixX& Y) {
  MatrixX Z = X * Y;
  Z.noalias() -= Y * X;
  return Z;
}

// The companion form of MakeStateSystem (StateSystem::companion): a = [[0, wI], [R, S]] (f × f
// blocks), and the differences of such matrices d = [[0, 0], [P, Q]]. Their commutators by blocks
// (the zero and scaled-identity blocks never multiplied), the same values as Commutator to
// round-off at a quarter and a half of its 16 f³ multiply-adds:
//   [a, d] = [[wP, wQ], [SP − QR, SQ − QS − wP]]                          (4 f³),
//   [a, Z] = a Z − Z a,  a Z = [[w Z_bottom], [[R S] Z]],  Z a = Z_right [R S] + [0, w Z_left]
//                                                                         (8 f³, Z full).
MatrixX CompanionLowerCommutator(const MatrixX& a, const MatrixX& d) {
  const Eigen::Index f = a.rows() / 2;
  const double w = a(0, f);
  MatrixX out(2 * f, 2 * f);
  out.topRows(f) = w * d.bottomRows(f);
  out.bottomRows(f).noalias() = a.bottomRightCorner(f, f) * d.bottomRows(f);
  out.bottomRows(f).noalias() -= d.bottomRightCorner(f, f) * a.bottomRows(f);
  out.bottomRightCorner(f, f) -= w * d.bottomLeftCorner(f, f);
  return out;
}

MatrixX CompanionCommutator(const MatrixX& a, const MatrixX& Z) {
  const Eigen::Index f = a.rows() / 2;
  const double w = a(0, f);
  MatrixX out(2 * f, 2 * f);
  out.topRows(f) = w * Z.bottomRows(f);
  out.bottomRows(f).noalias() = a.bottomRows(f) * Z;
  out.noalias() -= Z.rightCols(f) * a.bottomRows(f);
  out.rightCols(f) -= w * Z.leftCols(f);
  return out;
}

}  // namespace

MatrixX MagnusStepPropagator(const StateSystem& sys, int order, double t0, double h,
                             long* evaluations) {
  const int N = sys.dim;
  MatrixX A1(N, N), A2(N, N), A3(N, N), Omega(N, N);
  if (order == 4) {
    const double c = std::sqrt(3.0) / 6.0;
    sys.evaluate(t0 + (0.5 - c) * h, &A1);
    sys.evaluate(t0 + (0.5 + c) * h, &A2);
    // [A2, A1] = −[A1, A2 − A1].
    const MatrixX C =
        sys.companion ? MatrixX(-CompanionLowerCommutator(A1, A2 - A1)) : Commutator(A2, A1);
    Omega = 0.5 * h * (A1 + A2) + (std::sqrt(3.0) / 12.0) * h * h * C;
    *evaluations += 2;
  } else {
    const double c = std::sqrt(15.0) / 10.0;
    sys.evaluate(t0 + (0.5 - c) * h, &A1);
    sys.evaluate(t0 + 0.5 * h, &A2);
    sys.evaluate(t0 + (0.5 + c) * h, &A3);
    const MatrixX a1 = h * A2;
    const MatrixX a2 = (std::sqrt(15.0) / 3.0) * h * (A3 - A1);
    const MatrixX a3 = (10.0 / 3.0) * h * (A3 - 2.0 * A2 + A1);
    // a1 is in the companion form, a2 and a3 are differences of such matrices.
    const MatrixX C1 = sys.companion ? CompanionLowerCommutator(a1, a2) : Commutator(a1, a2);
    const MatrixX Z = 2.0 * a3 + C1;
    const MatrixX C2 =
        (-1.0 / 60.0) * (sys.companion ? CompanionCommutator(a1, Z) : Commutator(a1, Z));
    Omega = a1 + a3 / 12.0 + (1.0 / 240.0) * Commutator(-20.0 * a1 - a3 + C1, a2 + C2);
    *evaluations += 3;
  }
  return Omega.exp();
}

std::vector<double> MagnusGrid(const StateSystem& sys, int steps) {
  GEARDYN_DEMAND(steps >= 1);
  const double T = sys.period_s;
  std::vector<double> ends;
  const int pieces = static_cast<int>(sys.kinks.size()) + 1;
  if (steps < pieces) {
    // Steps longer than the smooth pieces: every step spans kinks whatever the grid.
    for (int j = 1; j <= steps; ++j) ends.push_back(j == steps ? T : T * j / steps);
    return ends;
  }
  double begin = 0.0;
  for (int k = 0; k < pieces; ++k) {
    const double end = k + 1 < pieces ? sys.kinks[k] : T;
    const double w = end - begin;
    const int m = std::max(1, static_cast<int>(std::lround(steps * w / T)));
    for (int j = 1; j <= m; ++j) ends.push_back(j == m ? end : begin + w * j / m);
    begin = end;
  }
  return ends;
}

MonodromyOutcome MagnusMonodromyFixed(const StateSystem& sys, int order, int steps) {
  GEARDYN_THROW_UNLESS(static_cast<bool>(sys.evaluate),
                       "method: magnus needs the coefficients callback (or steps)");
  GEARDYN_DEMAND(order == 4 || order == 6);
  const int N = sys.dim;
  const std::vector<double> ends = MagnusGrid(sys, steps);
  MonodromyOutcome out;
  out.phi = ScaledMatrix{MatrixX::Identity(N, N), 0.0};
  double t = 0.0;
  for (const double end : ends) {
    const MatrixX E = MagnusStepPropagator(sys, order, t, end - t, &out.evaluations);
    out.phi.matrix = E * out.phi.matrix;
    out.phi.Normalize();
    t = end;
  }
  out.steps = static_cast<long>(ends.size());
  out.num_factors = static_cast<double>(ends.size());
  return out;
}

double MaxOperatorNormTimesPeriod(const StateSystem& sys, long* evaluations, int samples) {
  // max ‖A(t)‖₁ (an upper bound of the spectral norm's growth rate up to √dim, and of the
  // spectral radius) over 4 samples per Gauss node spacing of a 16-step grid: the coefficients
  // vary on the mesh period, which this resolves; the step matrices when A is piecewise constant.
  double worst = 0.0;
  if (!sys.step_matrices.empty()) {
    for (const MatrixX& A : sys.step_matrices) {
      worst = MaxPropagatingNaN(worst, A.cwiseAbs().colwise().sum().maxCoeff());
    }
  } else if (sys.evaluate) {
    MatrixX A(sys.dim, sys.dim);
    for (int j = 0; j < samples; ++j) {
      sys.evaluate(sys.period_s * (j + 0.5) / samples, &A);
      worst = MaxPropagatingNaN(worst, A.cwiseAbs().colwise().sum().maxCoeff());
      if (evaluations != nullptr) ++*evaluations;
    }
  }
  return worst * sys.period_s;
}

int MagnusStartSteps(double norm_times_period) {
  // The Magnus series converges for ∫‖A‖dt < π over a step (Moan & Niesen, Found. Comput. Math.
  // 8 (2008) 291–301); the truncation error of the order-p method is O((h‖A‖)^{p+1}) per step,
  // so only h‖A‖ ≤ 1 puts every step well inside the radius with a leading term that decays.
  // Below that count the step-doubling estimate compares two diverging series and can be
  // non-finite or meaninglessly small (issue 12: low speed, stiff bearings).
  if (!std::isfinite(norm_times_period)) return kMaxMagnusSteps + 1;
  const double n = std::ceil(norm_times_period / kMagnusStepNorm);
  if (n > kMaxMagnusSteps) return kMaxMagnusSteps + 1;
  return std::max(kMinMagnusSteps, static_cast<int>(n));
}

namespace {

// The outcome of a system too stiff for the step cap: NaN Φ, not converged, with the reason.
MonodromyOutcome TooStiff(const StateSystem& sys, double norm_T, long evaluations,
                          const char* rule) {
  MonodromyOutcome out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.phi = ScaledMatrix{MatrixX::Constant(sys.dim, sys.dim, nan), 0.0};
  out.truncation_error = nan;
  out.evaluations = evaluations;
  out.converged = false;
  out.message = "magnus: max‖A‖₁·T = " + FormatEstimate(norm_T) + " needs more than " +
                std::to_string(kMaxMagnusSteps) + " steps per period (" + rule +
                "); not attempted (the system is too stiff for the period: use exact_steps for "
                "piecewise-constant coefficients)";
  return out;
}

// MagnusMonodromyMeasured on an analytic A(t) (StateSystem::analytic: a verified trigonometric
// polynomial, no kinks). The order-measuring runs of the general rule (the count ⌈‖A‖T/2π⌉ outside
// the radius, then its double) only find what analyticity already gives: the Gauss–Legendre
// Magnus method's global error is C h^order + O(h^{order+1}) for a smooth A (Iserles & Nørsett
// 1999). So the first run is the general rule's second count N₁ = 2⌈‖A‖T/2π⌉ (h‖A‖₁ ≤ π: inside
// the radius), the second N₂ = ⌈r N₁⌉, and the estimate e(N₂) = s·‖Φ(N₂) − Φ(N₁)‖/‖Φ‖ / ((N₂/N₁)^q
// − 1) uses q = order − 1, one below the nominal order to cover the pre-asymptotic range: on the
// README chart the order measured from three runs inside the radius is ≥ 5.22 at all 4 517 pairs
// (docs/design.md "Stability charts: known order on prepared rows"). From the third run on, q is
// also capped by the order measured from the last three runs (ObservedOrderOfThree), so a lower
// order is seen wherever a run is added. r = 3.5: on the README chart at 1e-6 the second run is
// the accepted one at 2 863 of 2 888 evaluations (r = 2.5: 1 842; r = 4 costs 9 % more steps).
MonodromyOutcome MagnusMonodromyAnalytic(const StateSystem& sys, int order, double tolerance,
                                         double norm_T, long evaluations) {
  constexpr double kSafety = 2.0;
  constexpr double kFirstRatio = 3.5;
  const double known = static_cast<double>(order - 1);
  int n = 2 * std::max(kMinMeasuredSteps,
                       static_cast<int>(std::ceil(norm_T / (2.0 * std::numbers::pi))));
  n = std::min(n, kMaxMagnusSteps / 2);
  MonodromyOutcome previous = MagnusMonodromyFixed(sys, order, n);
  evaluations += previous.evaluations;
  long older_steps = 0;
  double older_difference = std::numeric_limits<double>::quiet_NaN();
  double grow = kFirstRatio;
  while (true) {
    n = static_cast<int>(std::min<double>(kMaxMagnusSteps, std::ceil(n * grow)));
    MonodromyOutcome current = MagnusMonodromyFixed(sys, order, n);
    evaluations += current.evaluations;
    const double ratio = static_cast<double>(current.steps) / static_cast<double>(previous.steps);
    const double difference = RelativeDifference(current.phi, previous.phi);
    const double p =
        older_steps > 0
            ? std::min(known, ObservedOrderOfThree(older_difference, difference, older_steps,
                                                   previous.steps, current.steps, order))
            : known;
    double err = ratio > 1.0 ? kSafety * difference / (std::pow(ratio, p) - 1.0)
                             : std::numeric_limits<double>::infinity();
    if (std::isnan(err)) err = std::numeric_limits<double>::infinity();
    if (err <= tolerance || current.steps >= kMaxMagnusSteps || ratio <= 1.0) {
      current.truncation_error = err;
      current.evaluations = evaluations;
      if (!(err <= tolerance)) {
        current.converged = false;
        current.message = "magnus: relative error estimate of the monodromy " +
                          FormatEstimate(err) + " above the tolerance at " +
                          std::to_string(current.steps) + " steps (order " + FormatEstimate(p) +
                          ")";
      }
      return current;
    }
    grow = std::isfinite(err) && p >= known
               ? std::clamp(1.2 * std::pow(err / tolerance, 1.0 / p), 1.5, 16.0)
               : 2.0;
    older_steps = previous.steps;
    older_difference = difference;
    previous = std::move(current);
  }
}

}  // namespace

MonodromyOutcome MagnusMonodromy(const StateSystem& sys, int order, double tolerance) {
  // Richardson on Φ: with N₁ < N₂ steps, e(N₂) ≈ ‖Φ(N₂) − Φ(N₁)‖/‖Φ‖ / ((N₂/N₁)^p − 1). The
  // criterion is on the matrix, not on the multipliers, which are only √-conditioned where two
  // of them meet (transition curves); SpectrumOf turns e into the multiplier estimate.
  long probe_evaluations = 0;
  const double norm_T = MaxOperatorNormTimesPeriod(sys, &probe_evaluations);
  int n1 = MagnusStartSteps(norm_T);
  if (n1 > kMaxMagnusSteps) return TooStiff(sys, norm_T, probe_evaluations, "h‖A‖ ≤ 1");
  n1 = std::min(n1, kMaxMagnusSteps / 2);  // room for one doubling (h‖A‖ ≤ 2 < π still)
  MonodromyOutcome coarse = MagnusMonodromyFixed(sys, order, n1);
  int n2 = std::min(kMaxMagnusSteps, 2 * n1);
  long evaluations = coarse.evaluations + probe_evaluations;
  double previous_difference = std::numeric_limits<double>::quiet_NaN();
  int previous_n = 0;
  while (true) {
    MonodromyOutcome fine = MagnusMonodromyFixed(sys, order, n2);
    evaluations += fine.evaluations;
    // The actual counts (MagnusGrid rounds to the kink pieces) set the step ratio.
    const double ratio = static_cast<double>(fine.steps) / static_cast<double>(coarse.steps);
    const double difference = RelativeDifference(fine.phi, coarse.phi);
    double p = ObservedOrder(previous_difference, difference, previous_n,
                             static_cast<int>(coarse.steps), order);
    // A non-finite difference (an overflowing coarse run) is "not converged", never "done".
    double err = ratio > 1.0 ? difference / (std::pow(ratio, p) - 1.0)
                             : std::numeric_limits<double>::infinity();
    if (!(err <= tolerance) && n2 >= kMaxMagnusSteps && previous_n == 0 && n2 - n1 >= 2 &&
        std::isfinite(difference)) {
      // The cap came at the first comparison, where the order is unknown and taken as 1 (a
      // 2^p − 1 = 63× more pessimistic divisor than order 6). Measure it instead with a run
      // between the two counts (finer than the coarse one, so inside the series' radius too):
      // two differences give the order (issue 12: the helical pair at 5 rpm stopped here at
      // "observed order 1").
      const MonodromyOutcome mid = MagnusMonodromyFixed(sys, order, n1 + (n2 - n1) / 2);
      evaluations += mid.evaluations;
      p = ObservedOrderOfThree(RelativeDifference(mid.phi, coarse.phi),
                               RelativeDifference(fine.phi, mid.phi), coarse.steps, mid.steps,
                               fine.steps, order);
      err = ratio > 1.0 ? difference / (std::pow(ratio, p) - 1.0)
                        : std::numeric_limits<double>::infinity();
    }
    if (err <= tolerance || n2 >= kMaxMagnusSteps) {
      fine.truncation_error = std::isnan(err) ? std::numeric_limits<double>::infinity() : err;
      fine.evaluations = evaluations;
      if (!(err <= tolerance)) {
        fine.converged = false;
        fine.message = "magnus: relative error estimate of the monodromy " + FormatEstimate(err) +
                       " above the tolerance at " + std::to_string(n2) + " steps (observed order " +
                       FormatEstimate(p) + ")";
      }
      return fine;
    }
    // Next count from the asymptotic model e ∝ N^−p (with a safety factor), ×1.5 … ×16; ×4 past
    // a non-finite estimate.
    const double grow =
        std::isfinite(err) ? std::clamp(1.2 * std::pow(err / tolerance, 1.0 / p), 1.5, 16.0) : 4.0;
    previous_difference = difference;
    previous_n = static_cast<int>(coarse.steps);
    n1 = n2;
    coarse = std::move(fine);
    n2 = static_cast<int>(std::min<double>(kMaxMagnusSteps, std::ceil(n2 * grow)));
  }
}

MonodromyOutcome MagnusMonodromyMeasured(const StateSystem& sys, int order, double tolerance) {
  // The same Richardson estimate on Φ as MagnusMonodromy, e(N_k) = s·‖Φ(N_k) − Φ(N_{k−1})‖/‖Φ‖ /
  // ((N_k/N_{k−1})^p − 1), with three changes that make it tight instead of ≈ 63× pessimistic:
  //  * p is the order measured from the last three runs (ObservedOrderOfThree, clamped to
  //    [1, order]; 1 while only two exist), so a kink or a jump inside a step (order 1–2) is
  //    seen, not assumed away; s = kSafety covers the ±20 % of an asymptotic fit.
  //  * The first count puts h‖A‖₁ ≤ 2π (2 at least): such a run may lie outside the radius of
  //    the Magnus series, but it only enters the order fit. A result is accepted only when the
  //    coarser of the two runs compared has h‖A‖₁ ≤ π: inside the radius ∫‖A‖₂ < π of Moan &
  //    Niesen, Found. Comput. Math. 8 (2008) 291–301, where the series converges (the 1-norm
  //    as in MagnusStartSteps; ‖A‖₂ = 0.99‖A‖₁ on the helical pair's scaled state).
  //  * The next count follows the fitted model e ∝ N^−p (×1.5 … ×16, with a 1.2 margin) when the
  //    measured order is within 1 of the nominal one; ×2 otherwise (order unknown or low,
  //    estimate not finite, outside the radius).
  // On the 12-DOF helical pair at 1e-6 this takes ≈ 2× fewer A(t) evaluations than
  // MagnusMonodromy, with estimates 1.7–3.8× the true error of Φ: it delivers the tolerance where
  // MagnusMonodromy delivers ≈ 50× better (docs/design.md "Stability charts: the measured-order").
  constexpr double kSafety = 2.0;
  constexpr double kRadius = std::numbers::pi;
  // 16 samples (4 per quarter period), not 64: the norm only sets the first count and the
  // radius test, and the accepted estimate rests on the measured order.
  constexpr int kNormSamples = 16;
  long evaluations = 0;
  const double norm_T = MaxOperatorNormTimesPeriod(sys, &evaluations, kNormSamples);
  if (!std::isfinite(norm_T) || norm_T / kRadius > kMaxMagnusSteps / 2) {
    return TooStiff(sys, norm_T, evaluations, "h‖A‖ ≤ π on the second-finest run");
  }
  if (sys.analytic && sys.kinks.empty()) {
    return MagnusMonodromyAnalytic(sys, order, tolerance, norm_T, evaluations);
  }
  int n = std::max(kMinMeasuredSteps, static_cast<int>(std::ceil(norm_T / (2.0 * kRadius))));
  MonodromyOutcome previous = MagnusMonodromyFixed(sys, order, n);
  evaluations += previous.evaluations;
  long older_steps = 0;  // steps of the run before `previous` (0: none yet)
  double older_difference = std::numeric_limits<double>::quiet_NaN();
  double grow = 2.0;
  while (true) {
    n = static_cast<int>(std::min<double>(kMaxMagnusSteps, std::ceil(n * grow)));
    MonodromyOutcome current = MagnusMonodromyFixed(sys, order, n);
    evaluations += current.evaluations;
    if (current.steps <= previous.steps && current.steps < kMaxMagnusSteps) {
      grow = 2.0;  // MagnusGrid rounded to the same count (many kink pieces): grow further
      continue;
    }
    const double ratio = static_cast<double>(current.steps) / static_cast<double>(previous.steps);
    const double difference = RelativeDifference(current.phi, previous.phi);
    const double p = older_steps > 0
                         ? ObservedOrderOfThree(older_difference, difference, older_steps,
                                                previous.steps, current.steps, order)
                         : 1.0;
    // Non-finite, or not refined (ratio ≤ 1 at the cap): "not converged", never "done".
    double err = ratio > 1.0 ? kSafety * difference / (std::pow(ratio, p) - 1.0)
                             : std::numeric_limits<double>::infinity();
    if (std::isnan(err)) err = std::numeric_limits<double>::infinity();
    const bool inside = static_cast<double>(previous.steps) * kRadius >= norm_T;
    if ((err <= tolerance && inside) || current.steps >= kMaxMagnusSteps || ratio <= 1.0) {
      current.truncation_error = err;
      current.evaluations = evaluations;
      if (!(err <= tolerance && inside)) {
        current.converged = false;
        current.message = "magnus: relative error estimate of the monodromy " +
                          FormatEstimate(err) + " above the tolerance at " +
                          std::to_string(current.steps) + " steps (measured order " +
                          FormatEstimate(p) + ")";
      }
      return current;
    }
    // Extrapolate only a measured order near the nominal one: a low order measured before the
    // asymptotic regime (or across a kink) would make e ∝ N^−p ask for far too many steps.
    grow = older_steps > 0 && std::isfinite(err) && inside && p >= order - 1.0
               ? std::clamp(1.2 * std::pow(err / tolerance, 1.0 / p), 1.5, 16.0)
               : 2.0;
    older_steps = previous.steps;
    older_difference = difference;
    previous = std::move(current);
  }
}

double ObservedOrderOfThree(double d01, double d12, long n0, long n1, long n2, int order) {
  // e(N) = C N^−q: d01 = C (n0^−q − n1^−q), d12 = C (n1^−q − n2^−q); their ratio g(q) grows
  // with q (2^q for n1 = 2 n0, n2 = 2 n1: ObservedOrder), so bisect g(q) = d01/d12 on [1, order].
  if (!(d01 > 0.0) || !(d12 > 0.0) || !(n0 < n1 && n1 < n2)) return 1.0;
  const double x0 = static_cast<double>(n0), x1 = static_cast<double>(n1),
               x2 = static_cast<double>(n2);
  auto g = [&](double q) {
    return (std::pow(x0, -q) - std::pow(x1, -q)) / (std::pow(x1, -q) - std::pow(x2, -q));
  };
  const double target = d01 / d12;
  double lo = 1.0, hi = static_cast<double>(order);
  if (!(target > g(lo))) return lo;
  if (target >= g(hi)) return hi;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < target ? lo : hi) = mid;
  }
  return lo;
}

double ObservedOrder(double previous_difference, double difference, int n0, int n1, int order) {
  // d₀ = ‖Φ(N₁) − Φ(N₀)‖ ≈ C N₀^−q and d₁ = ‖Φ(N₂) − Φ(N₁)‖ ≈ C N₁^−q: q = ln(d₀/d₁)/ln(N₁/N₀),
  // clamped to [1, order]. The nominal order holds only for smooth coefficients: a jump (steps
  // forced through Magnus) or a kink (linearly interpolated tables) inside a step lowers it to
  // 1 or 2, and a Richardson divisor 2^6 − 1 then claims 63× (or 21×) too little (issue 12: a
  // confident "stable" where the exact product is unstable). Before two differences exist the
  // order is 1 (conservative).
  if (!(previous_difference > 0.0) || !(difference > 0.0) || n0 <= 0 || n1 <= n0) return 1.0;
  const double q = std::log(previous_difference / difference) /
                   std::log(static_cast<double>(n1) / static_cast<double>(n0));
  if (!std::isfinite(q)) return 1.0;
  return std::clamp(q, 1.0, static_cast<double>(order));
}

}  // namespace geardyn::internal
