// Tests of geardyn/system/coefficient.hpp: every expectation is checked against an independent
// truth (closed-form Fourier coefficients, direct trigonometric sums, midpoint quadrature, the
// Wilbraham–Gibbs constant), never against the code's own output.
#include "geardyn/system/coefficient.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <functional>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"
#include "support/no_malloc.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * kPi;
// Closed-form coefficients and direct sums agree to round-off of O(N) terms.
constexpr double kRoundoff = 1e-13;

/// Midpoint-rule L2 norm over [0, T) of g (the functions here are bounded, with finitely many
/// jumps: the midpoint rule converges like 1/M at the jumps, far below the tested errors).
double L2Norm(const std::function<double(double)>& g, double period, int points) {
  double sum = 0.0;
  for (int i = 0; i < points; ++i) {
    const double v = g((i + 0.5) * period / points);
    sum += v * v;
  }
  return std::sqrt(sum / points);
}

double Eval1(const Coefficient& c, double theta) {
  VectorX out(NumChannels(c));
  Evaluate(c, theta, out);
  return out[0];
}

/// Rectangular wave: `high` on [start, start + width), `low` elsewhere, period 2πP.
PiecewiseConstantCoefficient RectangularWave(double start, double width, double high, double low,
                                             std::int64_t p = 1) {
  VectorX bp(2);
  bp << start, start + width;
  MatrixX values(1, 2);
  values << high, low;
  return PiecewiseConstantCoefficient(bp, values, p);
}

TEST(CoefficientTest, RectangularWaveFourierCoefficientsMatchClosedForm) {
  // f = A on [θ1, θ1 + d), B elsewhere:
  //   a_n = (A − B)/(πn) [sin n(θ1 + d) − sin nθ1],  b_n = (A − B)/(πn) [cos nθ1 − cos n(θ1 + d)].
  const double a = 3.0, b = 1.0, t1 = 0.7, d = 2.1;
  const Coefficient wave = RectangularWave(t1, d, a, b);
  const FourierCoefficient f = ToFourier(wave, 60);
  ASSERT_EQ(f.num_terms(), 60);
  EXPECT_NEAR(f.mean()[0], (a * d + b * (kTwoPi - d)) / kTwoPi, kRoundoff);
  const MatrixX cos_c = f.CosCoefficients();
  const MatrixX sin_c = f.SinCoefficients();
  for (int n = 1; n <= 60; ++n) {
    const double an = (a - b) / (kPi * n) * (std::sin(n * (t1 + d)) - std::sin(n * t1));
    const double bn = (a - b) / (kPi * n) * (std::cos(n * t1) - std::cos(n * (t1 + d)));
    EXPECT_NEAR(cos_c(0, n - 1), an, kRoundoff) << "n = " << n;
    EXPECT_NEAR(sin_c(0, n - 1), bn, kRoundoff) << "n = " << n;
  }
}

TEST(CoefficientTest, HuntingPeriodWaveHarmonicsAreFractionsOfMeshOrder) {
  // Period T = 2πP with P = 3: harmonic n has frequency n/3 of the mesh frequency. A wave high on
  // [0, 2π) only (one mesh out of three) has c_n = (1/T) ∫_0^{2π} (A − B) e^{−inθ/3} dθ
  // = (A − B)(1 − e^{−2πin/3}) / (T·in/3).
  const double a = 2.0, b = 0.5;
  const Coefficient wave = RectangularWave(0.0, kTwoPi, a, b, 3);
  const FourierCoefficient f = ToFourier(wave, 12);
  EXPECT_EQ(f.period_meshes(), 3);
  for (int n = 1; n <= 12; ++n) {
    const Complex expected = (a - b) / (3.0 * kTwoPi) *
                             (1.0 - std::exp(Complex(0.0, -kTwoPi * n / 3.0))) /
                             Complex(0.0, n / 3.0);
    EXPECT_NEAR(std::abs(f.harmonics()(0, n - 1) - expected), 0.0, kRoundoff) << "n = " << n;
  }
  EXPECT_NEAR(Period(wave), 3.0 * kTwoPi, 1e-15);
}

TEST(CoefficientTest, FourierOfStepsConvergesAwayFromJumpsWithGibbsAtJumps) {
  // Jumps of size J = 1 at θ = 1 and θ = 3. The L2 error of the partial sum S_N decays like
  // N^{-1/2} (the coefficients decay like 1/n), the error at points at distance ≥ δ from the jumps
  // like 1/N, and the overshoot next to a jump tends to the Wilbraham–Gibbs constant
  // J (Si(π)/π − 1/2) = 0.0894898722 J.
  const double jump = 1.0;
  const Coefficient wave = RectangularWave(1.0, 2.0, jump, 0.0);
  auto f = [](double t) { return (t >= 1.0 && t < 3.0) ? 1.0 : 0.0; };
  std::vector<double> l2;
  std::vector<double> away;
  const std::vector<int> terms = {16, 64, 256, 1024};
  for (int n : terms) {
    const Coefficient s = ToFourier(wave, n);
    l2.push_back(L2Norm([&](double t) { return Eval1(s, t) - f(t); }, kTwoPi, 1 << 15));
    double worst = 0.0;
    for (double t = 1.5; t <= 2.5; t += 0.01) worst = std::max(worst, std::abs(Eval1(s, t) - f(t)));
    for (double t = 3.5; t <= 6.5; t += 0.01) worst = std::max(worst, std::abs(Eval1(s, t) - f(t)));
    away.push_back(worst);
  }
  for (size_t i = 1; i < terms.size(); ++i) {
    const double order = std::log(l2[i - 1] / l2[i]) / std::log(4.0);
    EXPECT_NEAR(order, 0.5, 0.06) << "L2 order between N = " << terms[i - 1] << " and " << terms[i];
    // Away from jumps (δ ≥ 0.5): |error| ≤ J/(π N sin(δ/2))·(1 + o(1)) for two jumps → 2·that.
    EXPECT_LT(away[i], 2.0 * jump / (kPi * terms[i] * std::sin(0.25)) * 1.2) << "N = " << terms[i];
  }
  // Gibbs overshoot next to the jump at θ = 1 (rising edge), N = 512.
  const Coefficient s = ToFourier(wave, 512);
  double peak = 0.0;
  for (double t = 1.0; t < 1.05; t += 1e-5) peak = std::max(peak, Eval1(s, t));
  EXPECT_NEAR(peak - jump, 0.0894898722 * jump, 2e-3);
}

TEST(CoefficientTest, TableToFourierIsExactForTrigonometricPolynomials) {
  // Two channels, 16 samples: f0 = 1.5 + 0.3 cos 2θ − 0.7 sin 5θ + 0.2 cos 7θ, f1 = −2 + sin θ.
  const int s_count = 16;
  MatrixX samples(2, s_count);
  for (int s = 0; s < s_count; ++s) {
    const double t = kTwoPi * s / s_count;
    samples(0, s) = 1.5 + 0.3 * std::cos(2 * t) - 0.7 * std::sin(5 * t) + 0.2 * std::cos(7 * t);
    samples(1, s) = -2.0 + std::sin(t);
  }
  const FourierCoefficient f = ToFourier(TableCoefficient(samples), 10);
  MatrixX a = MatrixX::Zero(2, 10), b = MatrixX::Zero(2, 10);
  a(0, 1) = 0.3;
  b(0, 4) = -0.7;
  a(0, 6) = 0.2;
  b(1, 0) = 1.0;
  EXPECT_NEAR(f.mean()[0], 1.5, kRoundoff);
  EXPECT_NEAR(f.mean()[1], -2.0, kRoundoff);
  EXPECT_TRUE(
      test::CompareMatrices(f.CosCoefficients(), a, kRoundoff, test::MatrixCompareType::kAbsolute));
  EXPECT_TRUE(
      test::CompareMatrices(f.SinCoefficients(), b, kRoundoff, test::MatrixCompareType::kAbsolute));
  // Odd sample count and a hunting period P = 2: f = cos(3θ/2) + 0.4 sin(θ/2), 9 samples over 4π.
  const int odd = 9;
  MatrixX s2(1, odd);
  for (int s = 0; s < odd; ++s) {
    const double t = 2.0 * kTwoPi * s / odd;
    s2(0, s) = std::cos(1.5 * t) + 0.4 * std::sin(0.5 * t);
  }
  const FourierCoefficient g = ToFourier(TableCoefficient(s2, 2), 4);
  EXPECT_NEAR(g.CosCoefficients()(0, 2), 1.0, kRoundoff);
  EXPECT_NEAR(g.SinCoefficients()(0, 0), 0.4, kRoundoff);
  EXPECT_NEAR(g.CosCoefficients().norm() + g.SinCoefficients().norm(), 1.4, kRoundoff);
  // And evaluating that series reproduces the trigonometric polynomial everywhere.
  for (double t = -3.0; t < 15.0; t += 0.37) {
    EXPECT_NEAR(Eval1(g, t), std::cos(1.5 * t) + 0.4 * std::sin(0.5 * t), kRoundoff);
  }
}

TEST(CoefficientTest, EvaluateMatchesIndependentDefinitions) {
  // Piecewise: right-continuous, wrap-around before the first breakpoint, any θ.
  VectorX bp(3);
  bp << 0.5, 2.0, 4.0;
  MatrixX v(2, 3);
  v << 1.0, 2.0, 3.0,  //
      -1.0, -2.0, -3.0;
  const Coefficient pc = PiecewiseConstantCoefficient(bp, v);
  VectorX out(2);
  const std::vector<std::pair<double, double>> cases = {{0.5, 1.0},
                                                        {1.999, 1.0},
                                                        {2.0, 2.0},
                                                        {3.9, 2.0},
                                                        {4.0, 3.0},
                                                        {6.2, 3.0},
                                                        {0.1, 3.0},
                                                        {-0.1, 3.0},
                                                        {kTwoPi + 0.6, 1.0},
                                                        {-kTwoPi + 2.5, 2.0},
                                                        {100 * kTwoPi + 4.5, 3.0}};
  for (const auto& [theta, expected] : cases) {
    Evaluate(pc, theta, out);
    EXPECT_EQ(out[0], expected) << "theta = " << theta;
    EXPECT_EQ(out[1], -expected) << "theta = " << theta;
  }
  // Fourier: against a direct cos/sin sum.
  MatrixX a(2, 3), b(2, 3);
  a << 0.5, -0.2, 0.1, 1.0, 0.0, 0.3;
  b << 0.0, 0.7, -0.4, 0.2, 0.1, 0.0;
  VectorX m(2);
  m << 10.0, -1.0;
  const Coefficient fc = FourierCoefficient::FromCosSin(m, a, b, 2);
  for (double t = -7.0; t < 20.0; t += 0.61) {
    Evaluate(fc, t, out);
    for (int c = 0; c < 2; ++c) {
      double expected = m[c];
      for (int n = 1; n <= 3; ++n) {
        expected += a(c, n - 1) * std::cos(n * t / 2.0) + b(c, n - 1) * std::sin(n * t / 2.0);
      }
      EXPECT_NEAR(out[c], expected, kRoundoff) << "theta = " << t;
    }
  }
  // Table: linear between samples, periodic.
  MatrixX s(1, 4);
  s << 0.0, 4.0, 2.0, 8.0;  // at θ = 0, π/2, π, 3π/2
  const Coefficient tc = TableCoefficient(s);
  EXPECT_NEAR(Eval1(tc, kPi / 4), 2.0, kRoundoff);
  EXPECT_NEAR(Eval1(tc, 3 * kPi / 4), 3.0, kRoundoff);
  EXPECT_NEAR(Eval1(tc, 7 * kPi / 4), 4.0, kRoundoff);  // between 8 and the wrapped 0
  EXPECT_NEAR(Eval1(tc, -kPi / 4), 4.0, kRoundoff);
  EXPECT_NEAR(Eval1(tc, kPi), 2.0, kRoundoff);
  // Constant.
  EXPECT_EQ(Eval1(ConstantCoefficient(VectorX::Constant(1, 7.0)), 123.0), 7.0);
}

// f' of a Fourier coefficient against the derivative of the closed form, term by term:
// d/dθ [a cos(nθ/P) + b sin(nθ/P)] = (n/P)(−a sin(nθ/P) + b cos(nθ/P)); 40 terms (past one
// re-anchoring of the rotation), P = 3, θ far from the first period; the value equals Evaluate's.
TEST(CoefficientTest, FourierDerivativeIsTheDerivativeOfTheClosedForm) {
  const int terms = 40;
  const double P = 3.0;
  MatrixX a(2, terms), b(2, terms);
  for (int n = 1; n <= terms; ++n) {
    a(0, n - 1) = 1.0 / n;
    b(0, n - 1) = std::pow(-1.0, n) / (n * n);
    a(1, n - 1) = std::sin(0.3 * n);
    b(1, n - 1) = 0.0;
  }
  VectorX m(2);
  m << 5.0, -2.0;
  const FourierCoefficient fc = FourierCoefficient::FromCosSin(m, a, b, 3);
  VectorX value(2), derivative(2), plain(2);
  for (const double t : {-4.1, 0.0, 0.37, 9.9, 1e5 + 0.25}) {
    EvaluateWithDerivative(fc, t, value, derivative);
    Evaluate(fc, t, plain);
    for (int c = 0; c < 2; ++c) {
      double expected = 0.0, scale = 0.0;
      for (int n = 1; n <= terms; ++n) {
        const double w = n / P;
        expected += w * (-a(c, n - 1) * std::sin(w * t) + b(c, n - 1) * std::cos(w * t));
        scale += w * (std::abs(a(c, n - 1)) + std::abs(b(c, n - 1)));
      }
      // θ = 1e5 loses ~1e-11 of the phase in the reduction modulo 6π, times |f'|'s scale.
      EXPECT_NEAR(derivative[c], expected, 1e-10 * scale) << "theta = " << t;
      EXPECT_NEAR(value[c], plain[c], kRoundoff * std::abs(plain[c]) + kRoundoff) << t;
    }
  }
  VectorX wrong(3);
  EXPECT_THROW(EvaluateWithDerivative(fc, 0.0, value, wrong), InvalidInput);
}

TEST(CoefficientTest, MeanEqualsAnalyticMean) {
  VectorX bp(3);
  bp << 1.0, 2.5, 5.0;
  MatrixX v(1, 3);
  v << 2.0, -1.0, 4.0;
  // Interval widths 1.5, 2.5 and 2π − 4 (wrapping from 5 to 1 + 2π).
  const double expected = (2.0 * 1.5 - 1.0 * 2.5 + 4.0 * (kTwoPi - 4.0)) / kTwoPi;
  EXPECT_NEAR(Mean(PiecewiseConstantCoefficient(bp, v))[0], expected, kRoundoff);
  // Table of 2 + cos θ + sin 3θ (mean 2, the trapezoid rule is exact).
  MatrixX s(1, 10);
  for (int i = 0; i < 10; ++i) {
    const double t = kTwoPi * i / 10;
    s(0, i) = 2.0 + std::cos(t) + std::sin(3 * t);
  }
  EXPECT_NEAR(Mean(TableCoefficient(s))[0], 2.0, kRoundoff);
  // Table mean = mean of its linear interpolant (midpoint quadrature of Evaluate).
  const Coefficient tc = TableCoefficient(s);
  double q = 0.0;
  const int pts = 1 << 14;
  for (int i = 0; i < pts; ++i) q += Eval1(tc, (i + 0.5) * kTwoPi / pts);
  EXPECT_NEAR(Mean(tc)[0], q / pts, 1e-7);
  EXPECT_NEAR(Mean(FourierCoefficient(VectorX::Constant(1, 3.5), MatrixXc::Ones(1, 4)))[0], 3.5,
              0.0);
  EXPECT_EQ(Mean(ConstantCoefficient(VectorX::Constant(2, -1.0)))[1], -1.0);
}

TEST(CoefficientTest, ToFourierWithToleranceMeetsItsTolerance) {
  // Steps: error measured independently by midpoint quadrature of the partial sum.
  const Coefficient wave = RectangularWave(0.3, 2.4, 5.0, 1.0);
  auto f = [](double t) { return (t >= 0.3 && t < 2.7) ? 5.0 : 1.0; };
  const double mean = (5.0 * 2.4 + 1.0 * (kTwoPi - 2.4)) / kTwoPi;
  const double variation = L2Norm([&](double t) { return f(t) - mean; }, kTwoPi, 1 << 16);
  for (double tol : {0.2, 0.05, 0.02}) {
    const FourierFit fit = ToFourierWithTolerance(wave, tol);
    ASSERT_TRUE(fit.tolerance_met) << "tol = " << tol;
    const Coefficient s = fit.fourier;
    const double err = L2Norm([&](double t) { return Eval1(s, t) - f(t); }, kTwoPi, 1 << 16);
    EXPECT_LE(err / variation, tol * 1.001) << "tol = " << tol;
    EXPECT_NEAR(err / variation, fit.error_estimate, 1e-3) << "tol = " << tol;
    // Minimal: one term fewer misses the tolerance.
    const Coefficient fewer = ToFourier(wave, fit.num_terms - 1);
    const double err_fewer =
        L2Norm([&](double t) { return Eval1(fewer, t) - f(t); }, kTwoPi, 1 << 16);
    EXPECT_GT(err_fewer / variation, tol * 0.999) << "tol = " << tol;
  }
  // A smooth table: exp(cos θ) sampled 64 times. Its series is the trigonometric interpolant;
  // the tail beyond N of a geometric-like spectrum must be below tol.
  MatrixX samples(1, 64);
  for (int i = 0; i < 64; ++i) samples(0, i) = std::exp(std::cos(kTwoPi * i / 64));
  const Coefficient table = TableCoefficient(samples);
  const Coefficient full = ToFourier(table, 32);
  for (double tol : {1e-3, 1e-6, 1e-10}) {
    const FourierFit fit = ToFourierWithTolerance(table, tol);
    const Coefficient s = fit.fourier;
    const double var =
        L2Norm([&](double t) { return Eval1(full, t) - Mean(full)[0]; }, kTwoPi, 4096);
    const double err = L2Norm([&](double t) { return Eval1(full, t) - Eval1(s, t); }, kTwoPi, 4096);
    EXPECT_TRUE(fit.tolerance_met);
    EXPECT_LE(err / var, tol) << "tol = " << tol << ", N = " << fit.num_terms;
    EXPECT_LT(fit.num_terms, 16) << "exp(cos θ) has super-geometric coefficients (I_n(1))";
  }
  // Fourier input with a known tail: c_n = 2^{-n}; e(N)² = Σ_{n>N} 4^{-n} / Σ_{n≥1} 4^{-n} =
  // 4^{-N}.
  MatrixXc h(1, 40);
  for (int n = 1; n <= 40; ++n) h(0, n - 1) = std::pow(0.5, n);
  const FourierFit fit = ToFourierWithTolerance(FourierCoefficient(VectorX::Zero(1), h), 1e-6);
  EXPECT_EQ(fit.num_terms, 20);  // 2^{-20} ≈ 9.5e-7 ≤ 1e-6 < 2^{-19}
  EXPECT_NEAR(fit.error_estimate, std::pow(0.5, 20), 1e-12);
  // Constant: no terms.
  EXPECT_EQ(ToFourierWithTolerance(ConstantCoefficient(VectorX::Ones(2)), 1e-9).num_terms, 0);
  // Tolerance not reachable within max_terms: reported, not thrown.
  const FourierFit capped = ToFourierWithTolerance(wave, 1e-4, 100);
  EXPECT_FALSE(capped.tolerance_met);
  EXPECT_EQ(capped.num_terms, 100);
}

TEST(CoefficientTest, ClassifyReportsTheCheapestExactPath) {
  EXPECT_EQ(Classify(ConstantCoefficient(VectorX::Ones(1))), TimeDependence::kConstant);
  EXPECT_EQ(Classify(RectangularWave(1.0, 1.0, 2.0, 1.0)), TimeDependence::kPiecewiseConstant);
  EXPECT_EQ(Classify(RectangularWave(1.0, 1.0, 2.0, 2.0)), TimeDependence::kConstant);
  EXPECT_EQ(Classify(FourierCoefficient(VectorX::Ones(1), MatrixXc::Zero(1, 5))),
            TimeDependence::kConstant);
  EXPECT_EQ(Classify(FourierCoefficient(VectorX::Ones(1), MatrixXc::Ones(1, 5))),
            TimeDependence::kSmoothPeriodic);
  EXPECT_EQ(Classify(TableCoefficient(MatrixX::Ones(2, 8))), TimeDependence::kConstant);
  MatrixX s = MatrixX::Ones(2, 8);
  s(1, 3) = 2.0;
  EXPECT_EQ(Classify(TableCoefficient(s)), TimeDependence::kSmoothPeriodic);
  EXPECT_EQ(Combine(TimeDependence::kPiecewiseConstant, TimeDependence::kConstant),
            TimeDependence::kPiecewiseConstant);
  EXPECT_EQ(Combine(TimeDependence::kPiecewiseConstant, TimeDependence::kSmoothPeriodic),
            TimeDependence::kSmoothPeriodic);
  EXPECT_STREQ(TimeDependenceName(TimeDependence::kPiecewiseConstant), "piecewise_constant");
}

TEST(CoefficientTest, IntervalsCoverOnePeriod) {
  VectorX bp(3);
  bp << 0.5, 2.0, 4.0;
  const PiecewiseConstantCoefficient pc(bp, MatrixX::Ones(1, 3), 2);
  double total = 0.0;
  for (int k = 0; k < pc.num_intervals(); ++k) total += pc.interval_width(k);
  EXPECT_NEAR(total, 2.0 * kTwoPi, 1e-14);
  EXPECT_NEAR(pc.interval_end(2), 0.5 + 2.0 * kTwoPi, 1e-14);
  EXPECT_EQ(pc.FindInterval(0.2), 2);
  EXPECT_EQ(pc.FindInterval(2.0), 1);
  EXPECT_EQ(pc.FindInterval(2.0 * kTwoPi + 0.6), 0);
}

TEST(CoefficientTest, InvalidInputThrowsNamingTheField) {
  VectorX bp(2);
  bp << 2.0, 1.0;
  EXPECT_THROWS_MESSAGE(PiecewiseConstantCoefficient(bp, MatrixX::Ones(1, 2)), InvalidInput,
                        "breakpoints: must be strictly increasing");
  bp << 1.0, 7.0;
  EXPECT_THROWS_MESSAGE(PiecewiseConstantCoefficient(bp, MatrixX::Ones(1, 2)), InvalidInput,
                        "breakpoints\\[1\\] = 7 is outside");
  bp << -0.1, 1.0;
  EXPECT_THROWS_MESSAGE(PiecewiseConstantCoefficient(bp, MatrixX::Ones(1, 2)), InvalidInput,
                        "breakpoints\\[0\\]");
  bp << 1.0, 2.0;
  EXPECT_THROWS_MESSAGE(PiecewiseConstantCoefficient(bp, MatrixX::Ones(1, 3)), InvalidInput,
                        "values: has 3 columns but breakpoints has 2");
  MatrixX bad = MatrixX::Ones(2, 2);
  bad(1, 0) = std::nan("");
  EXPECT_THROWS_MESSAGE(PiecewiseConstantCoefficient(bp, bad), InvalidInput,
                        "values\\(1, 0\\) = nan is not finite");
  EXPECT_THROWS_MESSAGE(PiecewiseConstantCoefficient(bp, MatrixX::Ones(1, 2), 0), InvalidInput,
                        "period_meshes");
  EXPECT_THROWS_MESSAGE(TableCoefficient(MatrixX(1, 0)), InvalidInput, "samples");
  EXPECT_THROWS_MESSAGE(FourierCoefficient(VectorX::Ones(2), MatrixXc::Ones(3, 4)), InvalidInput,
                        "harmonics: has 3 rows but mean has 2");
  EXPECT_THROWS_MESSAGE(ConstantCoefficient(VectorX(0)), InvalidInput, "values");
  const Coefficient c = TableCoefficient(MatrixX::Ones(3, 4));
  VectorX wrong(2);
  EXPECT_THROWS_MESSAGE(Evaluate(c, 0.0, wrong), InvalidInput, "out: size 2");
  VectorX right(3);
  EXPECT_THROWS_MESSAGE(Evaluate(c, std::nan(""), right), InvalidInput, "theta");
  EXPECT_THROWS_MESSAGE(ToFourier(c, -1), InvalidInput, "num_terms");
  EXPECT_THROWS_MESSAGE(ToFourierWithTolerance(c, 0.0), InvalidInput, "rel_tol");
  EXPECT_THROWS_MESSAGE(ToFourierWithTolerance(c, 1e-3, -2), InvalidInput, "max_terms");
}

TEST(CoefficientTest, EvaluateDoesNotAllocate) {
  if (!GEARDYN_HAVE_ALLOCATION_COUNTER) GTEST_SKIP() << "no allocation counter in this build";
  VectorX bp(3);
  bp << 0.5, 2.0, 4.0;
  const std::vector<Coefficient> coefs = {
      ConstantCoefficient(VectorX::Ones(3)),
      PiecewiseConstantCoefficient(bp, MatrixX::Random(3, 3)),
      FourierCoefficient(VectorX::Ones(3), MatrixXc::Random(3, 100)),
      TableCoefficient(MatrixX::Random(3, 64)),
  };
  VectorX out(3);
  Eigen::Matrix<double, 8, 1> fixed;
  double sink = 0.0;
  const long allocations = test::CountAllocations([&] {
    for (const Coefficient& c : coefs) {
      for (double t = -10.0; t < 10.0; t += 0.1) {
        Evaluate(c, t, out);
        Evaluate(c, t, fixed.segment<3>(2));  // any contiguous buffer of the right size
        sink += out[0] + fixed[2];
      }
    }
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(std::isfinite(sink));
  // The counter works: an Eigen allocation is seen. The buffer escapes through a volatile
  // pointer, or clang may elide the allocation (malloc is a builtin: its definition is now in
  // another file, tests/support/allocation_counter.cpp).
  VectorX v;
  static double* volatile escaped = nullptr;
  const long eigen_allocations = test::CountAllocations([&] {
    v = VectorX::Ones(1000);
    escaped = v.data();
  });
  EXPECT_GE(eigen_allocations, 1);
  EXPECT_EQ(escaped, v.data());
  EXPECT_EQ(v.size(), 1000);
}

}  // namespace
}  // namespace geardyn
