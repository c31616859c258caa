/// @file
/// @brief Scalar root finding for the contact switches and extrema of the trigonometric
/// polynomial u(θ): a safeguarded Newton on a sign-changing bracket (Newton steps kept inside
/// it, bisection when a step leaves it or does not halve the step before last: Numerical
/// Recipes' rtsafe idea) and the cubic Hermite interpolant of sampled values and slopes (its
/// zero as the start, its maximum for the grazing test).
#pragma once

#include <algorithm>
#include <cmath>

namespace geardyn::internal {

/// @param f (θ, &slope) → value: the function and its derivative at θ.
/// @param a, fa, b, fb bracket [a, b] with f(a) = fa and f(b) = fb of opposite signs.
/// @return θ once a Newton correction is below tolerance/4 (or f(θ) = 0, or the bracket is
/// narrower than tolerance; at most 80 iterations).
/// @param start first iterate (outside (a, b): the regula falsi point).
template <class Function>
double SafeguardedNewton(Function&& f, double a, double fa, double b, double fb, double tolerance,
                         double start = -HUGE_VAL) {
  if (fa == 0.0) return a;
  if (fb == 0.0) return b;
  const bool rising = fb > 0.0;
  double x = start;
  if (!(x > a && x < b)) x = a - fa * (b - a) / (fb - fa);  // regula falsi start
  if (!(x > a && x < b)) x = 0.5 * (a + b);
  double previous_width = b - a;
  double last_step = HUGE_VAL;
  for (int it = 0; it < 80 && b - a > tolerance; ++it) {
    double slope = 0.0;
    const double value = f(x, &slope);
    if (value == 0.0) return x;
    if ((value > 0.0) == rising) {
      b = x;
    } else {
      a = x;
    }
    double next = slope != 0.0 ? x - value / slope : 0.5 * (a + b);
    if (!(next > a && next < b) || 2.0 * std::abs(next - x) > previous_width) {
      next = 0.5 * (a + b);
    }
    const double step = std::abs(next - x);
    if (step <= 0.25 * tolerance) return next;
    // Quadratic convergence already seen: the next correction ~ step³/previous² is below
    // round-off, so this iterate is final without another evaluation.
    if (step <= 1e-9 && step <= 1e-3 * last_step) return next;
    previous_width = step;
    last_step = step;
    x = next;
  }
  return x;
}

/// Cubic Hermite interpolant on [0, 1] with values f0, f1 and slopes d0, d1 (per unit
/// parameter) at 0 and 1: p(s) = f0 + d0 s + c2 s² + c3 s³.
struct HermiteCubic {
  HermiteCubic(double f0_in, double d0_in, double f1_in, double d1_in)
      : f0(f0_in),
        d0(d0_in),
        f1(f1_in),
        c2(3.0 * (f1_in - f0_in) - 2.0 * d0_in - d1_in),
        c3(2.0 * (f0_in - f1_in) + d0_in + d1_in) {}
  double Value(double s) const { return f0 + s * (d0 + s * (c2 + s * c3)); }
  double Slope(double s) const { return d0 + s * (2.0 * c2 + 3.0 * s * c3); }

  /// Zero in (0, 1) when f0 and f1 have opposite signs: a few Newton steps from the linear
  /// zero; a value outside (0, 1) when they leave it.
  double Zero() const {
    double s = f0 / (f0 - f1);
    for (int it = 0; it < 4; ++it) {
      const double slope = Slope(s);
      if (slope == 0.0) return -1.0;
      s -= Value(s) / slope;
      if (!(s > 0.0 && s < 1.0)) return -1.0;
    }
    return s;
  }

  /// Largest value on [0, 1] (ends and the stationary points p′(s) = 0 inside).
  double Maximum() const {
    double best = std::max(f0, f1);
    auto consider = [&](double s) {
      if (s > 0.0 && s < 1.0) best = std::max(best, Value(s));
    };
    const double qa = 3.0 * c3, qb = 2.0 * c2, qc = d0;
    if (qa == 0.0) {
      if (qb != 0.0) consider(-qc / qb);
    } else {
      const double disc = qb * qb - 4.0 * qa * qc;
      if (disc >= 0.0) {
        const double root = std::sqrt(disc);
        consider((-qb + root) / (2.0 * qa));
        consider((-qb - root) / (2.0 * qa));
      }
    }
    return best;
  }

  double f0, d0, f1, c2, c3;
};

}  // namespace geardyn::internal
