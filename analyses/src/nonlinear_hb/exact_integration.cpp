/// @file
/// @brief Exact Fourier coefficients of a piecewise-linear law g_i = κ_i(φ) c_i(u_i) and of its
/// Jacobian (nonlinear_hb.hpp, "Exact integration"): the superlevel sets {u > β} of the
/// trigonometric polynomial u(θ) located to round-off, closed-form integrals of e^{−ijθ} over
/// them, and discrete convolutions with the harmonics of u and κ̃.
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "nonlinear_hb/scalar_roots.hpp"
#include "nonlinear_hb/solver_impl.hpp"

namespace geardyn {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kAngleTolerance = 4e-16 * kTwoPi;

}  // namespace

void NhbSolver::Impl::EvaluatePolynomial(const VectorXc& c, double theta, double out[3]) const {
  // v = c_0 + 2 Re Σ c_k z^k, v′ = 2 Re Σ ik c_k z^k, v″ = −2 Re Σ k² c_k z^k, z = e^{iθ}.
  // In real arithmetic (the complex products' NaN/inf branches cost as much as the sums).
  const double zr = std::cos(theta), zi = std::sin(theta);
  double pr = 1.0, pi = 0.0;  // z^k
  double value = c[0].real(), slope = 0.0, curvature = 0.0;
  for (int k = 1; k <= H; ++k) {
    const double qr = pr * zr - pi * zi;
    pi = pr * zi + pi * zr;
    pr = qr;
    const double re = c[k].real() * pr - c[k].imag() * pi;
    const double im = c[k].real() * pi + c[k].imag() * pr;
    value += 2.0 * re;
    slope -= 2.0 * k * im;
    curvature -= 2.0 * k * k * re;
  }
  out[0] = value;
  out[1] = slope;
  out[2] = curvature;
}

void NhbSolver::Impl::FindSuperlevelSet(const VectorX& x, int i, double level) {
  poly.resize(H + 1);
  poly[0] = x[Re(0, i)];
  for (int k = 1; k <= H; ++k) poly[k] = std::complex<double>(x[Re(k, i)], x[Im(k, i)]);
  poly_values = u.row(i).transpose();
  poly_slopes = u_slope.row(i).transpose();
  FindPolynomialSuperlevelSet(level);
}

void NhbSolver::Impl::FindPolynomialSuperlevelSet(double level) {
  const double h = kTwoPi / S;
  auto f = [&](double theta, double* slope) {
    double d[3];
    EvaluatePolynomial(poly, theta, d);
    *slope = d[1];
    return d[0] - level;
  };
  auto df = [&](double theta, double* slope) {
    double d[3];
    EvaluatePolynomial(poly, theta, d);
    *slope = d[2];
    return d[1];
  };
  crossings.clear();
  double amplitude = 0.0;  // ≥ ‖u − U₀‖∞
  for (int k = 1; k <= H; ++k) amplitude += 2.0 * std::sqrt(std::norm(poly[k]));  // no hypot
  intervals.clear();
  // |v − V_0| ≤ amplitude everywhere: a level beyond V_0 ± amplitude is never crossed (e.g. a
  // back flank the orbit does not reach), and the scan below is skipped.
  if (poly[0].real() + amplitude < level) return;
  if (poly[0].real() - amplitude > level) {
    intervals.emplace_back(0.0, kTwoPi);
    return;
  }
  const double hH = h * H;
  const double hermite_error_bound = 2.0 * hH * hH * hH * hH / 384.0 * amplitude;  // 2× margin
  for (int s = 0; s < S; ++s) {
    const int s1 = (s + 1) % S;
    const double a = h * s, b = a + h;
    const double fa = poly_values[s] - level, fb = poly_values[s1] - level;
    const double da = poly_slopes[s], db = poly_slopes[s1];
    if ((fa > 0) != (fb > 0)) {
      // Start at the zero of the Hermite cubic of the sample values and slopes (O(h⁴) off).
      const double start = a + h * internal::HermiteCubic(fa, h * da, fb, h * db).Zero();
      crossings.emplace_back(internal::SafeguardedNewton(f, a, fa, b, fb, kAngleTolerance, start),
                             fb > 0);
    } else if ((da > 0) != (db > 0) && (fa > 0) == (da < 0)) {
      // An extremum inside the interval bends u towards the level: two crossings when it passes
      // (grazing contact, or a short loss of contact, narrower than a sample interval). Skipped
      // when the Hermite cubic of the samples stays farther from the level than its error bound
      // h⁴/384 ‖u⁗‖∞ ≤ h⁴/384 H⁴ ‖u − U₀‖∞ (Bernstein's inequality).
      const double sign = fa > 0 ? -1.0 : 1.0;  // look for the extremum towards the level
      const double peak =
          internal::HermiteCubic(sign * fa, sign * h * da, sign * fb, sign * h * db).Maximum();
      if (peak < -hermite_error_bound) continue;
      const double t = internal::SafeguardedNewton(df, a, da, b, db, kAngleTolerance);
      double slope = 0.0;
      const double ft = f(t, &slope);
      if ((ft > 0) != (fa > 0)) {
        crossings.emplace_back(internal::SafeguardedNewton(f, a, fa, t, ft, kAngleTolerance),
                               ft > 0);
        crossings.emplace_back(internal::SafeguardedNewton(f, t, ft, b, fb, kAngleTolerance),
                               fb > 0);
      }
    }
  }
  intervals.clear();
  if (crossings.empty()) {
    if (poly_values[0] > level) intervals.emplace_back(0.0, kTwoPi);
    return;
  }
  // Pair each entry with the next exit, cyclically (the crossings are in θ order).
  const size_t count = crossings.size();
  size_t first = 0;
  while (first < count && !crossings[first].second) ++first;
  if (first == count) return;  // exits only: inconsistent brackets, treat as empty
  bool open = false;
  double start = 0.0;
  for (size_t step = 0; step < count; ++step) {
    const size_t c = (first + step) % count;
    const double theta = crossings[c].first + (c < first ? kTwoPi : 0.0);
    if (crossings[c].second && !open) {
      open = true;
      start = theta;
    } else if (!crossings[c].second && open) {
      open = false;
      intervals.emplace_back(start, theta);
    }
  }
  if (open) intervals.emplace_back(start, crossings[first].first + kTwoPi);
}

void NhbSolver::Impl::SynthesizeSlope(const VectorX& x) {
  // du/dθ at the samples: c2r of ik U_k.
  for (int i = 0; i < n; ++i) {
    std::fill(&freq_buf[0][0], &freq_buf[0][0] + 2 * (S / 2 + 1), 0.0);
    for (int k = 1; k <= H; ++k) {
      freq_buf[k][0] = -k * x[Im(k, i)];
      freq_buf[k][1] = k * x[Re(k, i)];
    }
    fftw_execute(c2r);
    for (int s = 0; s < S; ++s) u_slope(i, s) = time_buf[s];
  }
}

void NhbSolver::Impl::IntegrateExactly(const VectorX& x) {
  using C = std::complex<double>;
  const int P = kappa_order;
  const int Q = H + P;       // harmonics of κ̃ (u − β)
  const int Jr = 2 * H + P;  // harmonics of the set integrals needed
  SynthesizeSlope(x);
  for (int i = 0; i < n; ++i) {
    const size_t ii = static_cast<size_t>(i);
    for (int l = 0; l <= H; ++l) {
      const C c = l == 0 ? C(x[i], 0.0) : C(x[Re(l, i)], x[Im(l, i)]);
      u_full[H + l] = c;
      u_full[H - l] = std::conj(c);
    }
    kappa.setZero();
    for (int j = 0; j * p <= P && j < form.modulation.cols(); ++j) {
      kappa[P + j * p] = form.modulation(i, j);
      kappa[P - j * p] = std::conj(form.modulation(i, j));
    }
    // Linear part κ̃ (s u + c₀): exact convolution.
    const double slope = form.slope[i], offset = form.offset[i];
    for (int k = 0; k <= H; ++k) {
      C sum = 0.0;
      for (int j = -P; j <= P; j += p) {
        const int l = k - j;
        if (l < -H || l > H) continue;
        sum += kappa[P + j] * (slope * u_full[H + l] + (l == 0 ? offset : 0.0));
      }
      g_h(i, k) = sum;
    }
    for (int d = 0; d <= 2 * H; ++d) dg_h[d](i, i) = d <= P ? slope * kappa[P + d] : C(0.0);
    // Ramps Δs [u − β]₊ over the superlevel sets.
    for (size_t ramp = 0; ramp < form.ramp_points[ii].size(); ++ramp) {
      const double level = form.ramp_points[ii][ramp], ds = form.ramp_slopes[ii][ramp];
      FindSuperlevelSet(x, i, level);
      if (intervals.empty()) continue;
      if (intervals.size() == 1 && intervals[0].first == 0.0 && intervals[0].second == kTwoPi) {
        // The whole period (a flank never left): I_j = δ_j, so the ramp is linear here.
        for (int k = 0; k <= H; ++k) {
          C sum = 0.0;
          for (int j = -P; j <= P; j += p) {
            const int l = k - j;
            if (l >= -H && l <= H) sum += kappa[P + j] * (u_full[H + l] - (l == 0 ? level : 0.0));
          }
          g_h(i, k) += ds * sum;
        }
        for (int d = 0; d <= P && d <= 2 * H; ++d) dg_h[d](i, i) += ds * kappa[P + d];
        continue;
      }
      set_integrals.setZero();
      for (const auto& [ta, tb] : intervals) {
        set_integrals[Jr] += (tb - ta) / kTwoPi;
        const C za = std::polar(1.0, -ta), zb = std::polar(1.0, -tb);
        C pa = 1.0, pb = 1.0;
        for (int j = 1; j <= Jr; ++j) {
          pa *= za;
          pb *= zb;
          // (1/2π) ∫_{ta}^{tb} e^{−ijθ} dθ = (e^{−ij ta} − e^{−ij tb}) / (2π i j)
          const C d = (pa - pb) * (1.0 / (kTwoPi * j));
          set_integrals[Jr + j] += C(d.imag(), -d.real());  // d / i
        }
      }
      for (int j = 1; j <= Jr; ++j) set_integrals[Jr - j] = std::conj(set_integrals[Jr + j]);
      // q_m = Σ_j κ̃_j (U_{m−j} − β δ_{m−j}), |m| ≤ Q.
      for (int mm = -Q; mm <= Q; ++mm) {
        C sum = 0.0;
        for (int j = -P; j <= P; j += p) {
          const int l = mm - j;
          if (l < -H || l > H) continue;
          sum += kappa[P + j] * (u_full[H + l] - (l == 0 ? level : 0.0));
        }
        ramp_product[Q + mm] = sum;
      }
      // N_k += Δs Σ_m q_m I_{k−m} = Δs Σ_r q_{Q−r} I_{k−Q+r}: with q reversed, four forward
      // real dot products per k (vectorised).
      const int len = 2 * Q + 1;
      for (int r = 0; r < len; ++r) {
        q_re[r] = ramp_product[len - 1 - r].real();
        q_im[r] = ramp_product[len - 1 - r].imag();
      }
      for (int j = 0; j < 2 * Jr + 1; ++j) {
        integrals_re[j] = set_integrals[j].real();
        integrals_im[j] = set_integrals[j].imag();
      }
      for (int k = 0; k <= H; ++k) {
        const int base = Jr + k - Q;
        const auto ire = integrals_re.segment(base, len), iim = integrals_im.segment(base, len);
        g_h(i, k) += ds * C(q_re.dot(ire) - q_im.dot(iim), q_re.dot(iim) + q_im.dot(ire));
      }
      for (int d = 0; d <= 2 * H; ++d) {
        C sum = 0.0;
        for (int j = -P; j <= P; j += p) sum += kappa[P + j] * set_integrals[Jr + d - j];
        dg_h[d](i, i) += ds * sum;
      }
    }
  }
}

double NhbSolver::Impl::ExtremeValue(const VectorX& x, int i, double sign) {
  int best = 0;
  for (int s = 1; s < S; ++s) {
    if (sign * u(i, s) > sign * u(i, best)) best = s;
  }
  const double h = kTwoPi / S;
  auto df = [&](double theta, double* slope) {
    double d[3];
    EvaluateCoordinate(x, i, theta, d);
    *slope = d[2];
    return d[1];
  };
  double value = u(i, best);
  // The stationary point lies where u′ changes sign next to the extreme sample.
  for (int side : {-1, 1}) {
    const double a = h * (best + std::min(side, 0)), b = a + h;
    double da_slope = 0.0, db_slope = 0.0;
    const double da = df(a, &da_slope), db = df(b, &db_slope);
    if ((da > 0) == (db > 0)) continue;
    const double t = internal::SafeguardedNewton(df, a, da, b, db, kAngleTolerance);
    double d[3];
    EvaluateCoordinate(x, i, t, d);
    if (sign * d[0] > sign * value) value = d[0];
  }
  return value;
}

}  // namespace geardyn
