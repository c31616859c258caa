// Tests of geardyn/models/mesh/contact_lines.hpp against independent truths: the closed forms of
// the total contact-line length (ε_α = n + f, ε_β = m + g), a brute-force sampled quadrature along
// every line written here from the geometry (no shared code), the uniformly loaded line
// μ = κ² + F²/(12 b²) (spec 01 §3), direct DFTs, and hand-counted contact pairs.
#include "geardyn/models/mesh/contact_lines.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "support/contact_zones.hpp"
#include "support/expect_throws.hpp"
#include "support/no_malloc.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * kPi;
using test::kFace;
using test::kK;
using test::kPitch;
using test::Zone;
// Closed forms vs closed forms: a few ulps of O(10) additions.
constexpr double kExact = 1e-12;
// Brute-force quadrature with M midpoint samples per line: each clipped end errs by ≤ one sample,
// so the relative error is O(lines/M); M = 20000 → ~1e-4.
constexpr int kBruteSamples = 20000;
constexpr double kBruteTol = 5e-4;

struct BruteSums {
  double length = 0.0, k = 0.0, k_sigma = 0.0, k_sigma2 = 0.0;
};

/// Independent midpoint quadrature along every line, written from the geometry: line j is
/// {x + y tan β = (θ/2π + j) p}, a point counts when x_s ≤ x < x_e and |y| ≤ b, its σ is the
/// projection (p − p0)·σ̂ with σ̂ = s(−sin β, cos β) in (roll, face) coordinates.
BruteSums BruteForce(const ZoneOfAction& z, const std::function<double(double)>& k_of_roll,
                     double theta, int samples = kBruteSamples) {
  const double b = 0.5 * z.face_width, p = z.transverse_base_pitch;
  const double beta = z.base_helix_angle, s = z.drive_sign;
  const double xs = -0.5 * z.length - z.pitch_point_offset, xe = xs + z.length;
  const double dy = 2.0 * b / samples, dl = dy / std::cos(beta);
  const int jmax =
      static_cast<int>((std::abs(xs) + std::abs(xe) + b * std::abs(std::tan(beta))) / p +
                       std::abs(theta) / kTwoPi) +
      3;
  BruteSums out;
  for (int j = -jmax; j <= jmax; ++j) {
    const double xj = (theta / kTwoPi + j) * p;
    for (int i = 0; i < samples; ++i) {
      const double y = -b + (i + 0.5) * dy;
      const double x = xj - y * std::tan(beta);
      if (x < xs || x >= xe) continue;
      const double k = k_of_roll(x - xs);
      const double sigma = s * (-x * std::sin(beta) + y * std::cos(beta));
      out.length += dl;
      out.k += k * dl;
      out.k_sigma += k * sigma * dl;
      out.k_sigma2 += k * sigma * sigma * dl;
    }
  }
  return out;
}

/// Compares the model's sums at θ with the brute force (relative to K, K b, K b²).
void ExpectMatchesBruteForce(const ContactLineModel& model,
                             const std::function<double(double)>& k_of_roll, double theta) {
  const ContactLineIntegrals a = model.CalcIntegrals(theta);
  const BruteSums q = BruteForce(model.zone(), k_of_roll, theta);
  const double b = model.half_face_width();
  const double scale_l = std::max(a.length, 1e-3 * kFace);
  const double scale_k = std::max(a.stiffness, 1e-3 * kK * kFace);
  EXPECT_NEAR(a.length, q.length, kBruteTol * scale_l) << "theta = " << theta;
  EXPECT_NEAR(a.stiffness, q.k, kBruteTol * scale_k) << "theta = " << theta;
  EXPECT_NEAR(a.first_moment, q.k_sigma, kBruteTol * scale_k * b) << "theta = " << theta;
  EXPECT_NEAR(a.second_moment, q.k_sigma2, kBruteTol * scale_k * b * b) << "theta = " << theta;
}

// ------------------------------------------------------------------------------------ spur

TEST(ContactLinesTest, SpurWaveAlternatesBetweenOneAndTwoPairs) {
  // n = ⌊ε_α⌋ pairs for the fraction 1 − f of the mesh period, n + 1 for f = ε_α − n.
  for (double eps : {1.25, 1.5, 1.62, 1.95, 2.4, 3.7}) {
    for (double offset : {0.0, 0.31 * kPitch}) {
      const ContactLineModel model(Zone(eps, 0.0, offset), StiffnessProfile::Constant(kK));
      const PiecewiseConstantCoefficient wave = MakePiecewiseConstantMeshCoefficient(model);
      const int n = static_cast<int>(std::floor(eps));
      const double f = eps - n;
      ASSERT_EQ(wave.num_intervals(), 2) << "eps_alpha = " << eps;
      double high_fraction = 0.0;
      for (int k = 0; k < 2; ++k) {
        const double level = wave.values()(kMeshStiffnessChannel, k);
        const double pairs = level / (kK * kFace);
        EXPECT_NEAR(pairs, std::round(pairs), kExact);
        EXPECT_TRUE(std::round(pairs) == n || std::round(pairs) == n + 1);
        if (std::round(pairs) == n + 1) high_fraction += wave.interval_width(k) / kTwoPi;
        // Independent count of teeth in contact at the interval's middle: x_s ≤ x_j < x_e.
        const double mid = 0.5 * (wave.interval_begin(k) + wave.interval_end(k));
        const double xs = -0.5 * eps * kPitch - offset;
        int count = 0;
        for (int j = -20; j <= 20; ++j) {
          const double xj = (mid / kTwoPi + j) * kPitch;
          if (xj >= xs && xj < xs + eps * kPitch) ++count;
        }
        EXPECT_EQ(static_cast<int>(std::round(pairs)), count);
        // Full-face lines: h = 0 and K μ b² = K b²/3.
        const double b = 0.5 * kFace;
        EXPECT_NEAR(wave.values()(kMeshFirstMomentChannel, k), 0.0, kExact * level * b);
        EXPECT_NEAR(wave.values()(kMeshSecondMomentChannel, k), level * b * b / 3.0,
                    kExact * level * b * b);
      }
      EXPECT_NEAR(high_fraction, f, 1e-12) << "eps_alpha = " << eps;
      EXPECT_EQ(Classify(wave), TimeDependence::kPiecewiseConstant);
      EXPECT_EQ(Classify(MakeMeshCoefficient(model)), TimeDependence::kPiecewiseConstant);
    }
  }
}

TEST(ContactLinesTest, SpurBreakpointsAreWhereLinesEnterAndLeave) {
  // ε_α = 1.5, p0 at mid zone: lines enter at x_s = −0.75 p (θ = 2π frac(−0.75) = π/2) and leave
  // at x_e = 0.75 p (θ = 3π/2); the two-pair level holds on [π/2, 3π/2).
  const ContactLineModel model(Zone(1.5, 0.0), StiffnessProfile::Constant(kK));
  const std::vector<double> breaks = model.Breakpoints();
  ASSERT_EQ(breaks.size(), 2u);
  EXPECT_NEAR(breaks[0], 0.5 * kPi, 1e-14);
  EXPECT_NEAR(breaks[1], 1.5 * kPi, 1e-14);
  EXPECT_NEAR(model.CalcIntegrals(kPi).stiffness, 2.0 * kK * kFace, kExact * kK * kFace);
  EXPECT_NEAR(model.CalcIntegrals(0.1).stiffness, kK * kFace, kExact * kK * kFace);
  EXPECT_EQ(model.CalcIntegrals(kPi).num_lines, 2);
}

TEST(ContactLinesTest, SpurFullFaceLineHasZeroLoadCentreAndMuOneThird) {
  // ε_α = 1: exactly one full-face line at every phase (spec 01 §6 spur limit K2 = K diag(1,
  // b²/3)).
  const ContactLineModel model(Zone(1.0, 0.0), StiffnessProfile::Constant(kK));
  for (double t = 0.0; t < kTwoPi; t += 0.1) {
    const MeshParameters m = model.CalcMeshParameters(t);
    EXPECT_NEAR(m.stiffness, kK * kFace, kExact * kK * kFace);
    EXPECT_NEAR(m.load_centre, 0.0, kExact * kFace);
    EXPECT_NEAR(m.mu, 1.0 / 3.0, kExact);
  }
  // Integer ε_α: K is constant, and kAuto says so.
  const ContactLineModel two(Zone(2.0, 0.0), StiffnessProfile::Constant(kK));
  const Coefficient c = MakeMeshCoefficient(two);
  EXPECT_TRUE(std::holds_alternative<ConstantCoefficient>(c));
  EXPECT_EQ(Classify(c), TimeDependence::kConstant);
  EXPECT_NEAR(Mean(c)[0], 2.0 * kK * kFace, kExact * kK * kFace);
}

TEST(ContactLinesTest, SpurWithStiffnessProfileIntegratesAlongThePath) {
  // Linear single-tooth profile k(r) = k0 (1 + 0.5 r/g_α): each full-face line contributes
  // k(r_j) B, r_j = x_j − x_s (counted by hand here).
  const double eps = 1.6, g = eps * kPitch;
  const StiffnessProfile linear = StiffnessProfile::PiecewiseLinear({0.0, g}, {kK, 1.5 * kK});
  const ContactLineModel model(Zone(eps, 0.0, 0.1 * kPitch), linear);
  const double xs = -0.5 * g - 0.1 * kPitch;
  for (double t = 0.05; t < kTwoPi; t += 0.3) {
    double expected = 0.0;
    for (int j = -10; j <= 10; ++j) {
      const double xj = (t / kTwoPi + j) * kPitch;
      if (xj >= xs && xj < xs + g) expected += kK * (1.0 + 0.5 * (xj - xs) / g) * kFace;
    }
    EXPECT_NEAR(model.CalcIntegrals(t).stiffness, expected, kExact * expected);
  }
  // A linear profile makes the spur channels piecewise linear, not steps.
  EXPECT_FALSE(model.is_piecewise_constant());
  EXPECT_THROWS_MESSAGE(MakePiecewiseConstantMeshCoefficient(model), InvalidInput,
                        "piecewise-constant stiffness profile");
  // A piecewise-constant profile keeps exact steps; the knot adds a breakpoint: events at x_s,
  // x_s + 0.64 p_bt (knot) and x_s + 1.6 p_bt (x_e), three distinct phases mod p_bt.
  const StiffnessProfile steps =
      StiffnessProfile::PiecewiseConstant({0.0, 0.4 * g, g}, {0.8 * kK, 1.2 * kK});
  const ContactLineModel stepped(Zone(eps, 0.0), steps);
  const PiecewiseConstantCoefficient wave = MakePiecewiseConstantMeshCoefficient(stepped);
  EXPECT_EQ(wave.num_intervals(), 3);
  for (int k = 0; k < wave.num_intervals(); ++k) {
    const double mid = 0.5 * (wave.interval_begin(k) + wave.interval_end(k));
    const BruteSums q = BruteForce(
        stepped.zone(), [&](double r) { return steps.ValueAt(r); }, mid,
        64);  // spur: exact for any sample count
    EXPECT_NEAR(wave.values()(0, k), q.k, 1e-12 * q.k);
  }
}

// ------------------------------------------------------------------------------------ helical

struct RatioCase {
  double eps_alpha, eps_beta;
};

class HelicalLengthTest : public ::testing::TestWithParam<RatioCase> {};

TEST_P(HelicalLengthTest, MeanMinMaxMatchClosedForms) {
  const auto [ea, eb] = GetParam();
  const ContactLineModel model(Zone(ea, eb, 0.13 * kPitch), StiffnessProfile::Constant(1.0));
  const double c = std::cos(model.zone().base_helix_angle);
  const double n = std::floor(ea), f = ea - n;
  const double m = std::floor(eb), gg = eb - m;
  const double mean = kFace * ea / c;
  const double lmin = kFace / c * (ea - (f * gg - std::max(0.0, f + gg - 1.0)) / eb);
  const double lmax = kFace / c * (ea + (std::min(f, gg) - f * gg) / eb);
  (void)m;
  // L(θ) is piecewise linear: its extremes are at the breakpoints.
  double got_min = 1e300, got_max = -1e300;
  for (double t : model.Breakpoints()) {
    const double l = model.CalcIntegrals(t).length;
    got_min = std::min(got_min, l);
    got_max = std::max(got_max, l);
  }
  EXPECT_NEAR(got_min, lmin, kExact * mean) << "eps = " << ea << ", " << eb;
  EXPECT_NEAR(got_max, lmax, kExact * mean) << "eps = " << ea << ", " << eb;
  // A dense grid never leaves [min, max] and the mean (exact Fourier c_0, and a plain Riemann
  // sum) equals the closed form.
  double riemann = 0.0;
  const int pts = 4000;
  for (int i = 0; i < pts; ++i) {
    const double l = model.CalcIntegrals((i + 0.5) * kTwoPi / pts).length;
    EXPECT_GE(l, lmin - kExact * mean);
    EXPECT_LE(l, lmax + kExact * mean);
    riemann += l / pts;
  }
  EXPECT_NEAR(riemann, mean, 1e-5 * mean);
  const FourierCoefficient series = MakeFourierMeshCoefficient(model, 0);
  EXPECT_NEAR(series.mean()[kMeshStiffnessChannel], mean, kExact * mean);  // k = 1 ⇒ K = L
  // And against the brute-force quadrature along each line.
  for (double t : {0.0, 0.7, 2.2, 3.9, 5.5}) {
    EXPECT_NEAR(model.CalcIntegrals(t).length,
                BruteForce(
                    model.zone(), [](double) { return 1.0; }, t)
                    .length,
                kBruteTol * mean);
  }
}

INSTANTIATE_TEST_SUITE_P(ContactRatios, HelicalLengthTest,
                         ::testing::Values(RatioCase{1.4, 0.3},    // f + g < 1
                                           RatioCase{1.6, 0.7},    // f + g > 1
                                           RatioCase{1.5, 2.0},    // integer ε_β: L constant
                                           RatioCase{2.3, 1.4},    // f + g < 1, ε_α > 2
                                           RatioCase{1.25, 0.5},   //
                                           RatioCase{1.8, 1.45},   // f + g > 1, ε_β > 1
                                           RatioCase{2.0, 0.6},    // integer ε_α: L constant
                                           RatioCase{0.7, 0.55}),  // ε_α < 1, ε_α + ε_β > 1
                         [](const ::testing::TestParamInfo<RatioCase>& param_info) {
                           return "a" +
                                  std::to_string(
                                      static_cast<int>(param_info.param.eps_alpha * 100)) +
                                  "_b" +
                                  std::to_string(static_cast<int>(param_info.param.eps_beta * 100));
                         });

TEST(ContactLinesTest, HelicalMomentsMatchBruteForceQuadrature) {
  const double g = 1.55 * kPitch;
  const StiffnessProfile constant = StiffnessProfile::Constant(kK);
  // A single-tooth-like profile: low at the ends of the path, high in the middle.
  const StiffnessProfile tooth =
      StiffnessProfile::PiecewiseLinear({0.0, 0.3 * g, 0.7 * g, g}, {0.6 * kK, kK, kK, 0.5 * kK});
  const StiffnessProfile steps =
      StiffnessProfile::PiecewiseConstant({-0.1 * g, 0.45 * g, 1.1 * g}, {0.7 * kK, 1.3 * kK});
  for (const StiffnessProfile* profile : {&constant, &tooth, &steps}) {
    for (int s : {1, -1}) {
      for (double beta_sign : {1.0, -1.0}) {
        const ContactLineModel model(Zone(1.55, 1.3, 0.2 * kPitch, s, beta_sign), *profile);
        for (double t : {0.0, 0.9, 2.5, 4.1, 6.0}) {
          ExpectMatchesBruteForce(
              model, [&](double r) { return profile->ValueAt(r); }, t);
        }
      }
    }
  }
}

TEST(ContactLinesTest, SignsOfLoadCentreFollowDriveAndHelix) {
  // K, L and μ do not depend on the drive sign or the sign of β_b; h flips with the drive sign
  // (σ̂ = ζ × η with ζ = s·(x̂ × ŷ)) and, mirrored in the face (y → −y, β → −β), with β_b.
  const ContactLineModel a(Zone(1.45, 0.8, 0.0, 1, 1.0), StiffnessProfile::Constant(kK));
  const ContactLineModel b(Zone(1.45, 0.8, 0.0, -1, 1.0), StiffnessProfile::Constant(kK));
  const ContactLineModel c(Zone(1.45, 0.8, 0.0, 1, -1.0), StiffnessProfile::Constant(kK));
  for (double t = 0.05; t < kTwoPi; t += 0.4) {
    const MeshParameters pa = a.CalcMeshParameters(t), pb = b.CalcMeshParameters(t),
                         pc = c.CalcMeshParameters(t);
    EXPECT_NEAR(pa.stiffness, pb.stiffness, kExact * pa.stiffness);
    EXPECT_NEAR(pa.stiffness, pc.stiffness, kExact * pa.stiffness);
    EXPECT_NEAR(pa.mu, pb.mu, kExact);
    EXPECT_NEAR(pa.mu, pc.mu, kExact);
    EXPECT_NEAR(pb.load_centre, -pa.load_centre, kExact * kFace);
    EXPECT_NEAR(pc.load_centre, -pa.load_centre, kExact * kFace);
    EXPECT_GE(pa.mu, pa.kappa * pa.kappa);  // K2 PSD
  }
  // Concrete geometry: with ε_α = 1, ε_β = 0.5 and p0 at mid zone, at θ = 0 the only line in
  // contact passes through p0 and lies entirely inside the zone (x ∈ ±p_bt/4 ⊂ [−p_bt/2, p_bt/2)),
  // so h = 0 and μ = 1/(3 cos² β_b) (a full line of half-length b/cos β_b centred at σ = 0).
  const ContactLineModel one(Zone(1.0, 0.5), StiffnessProfile::Constant(kK));
  const MeshParameters p0 = one.CalcMeshParameters(0.0);
  EXPECT_NEAR(p0.load_centre, 0.0, kExact * kFace);
  EXPECT_NEAR(p0.mu, 1.0 / (3.0 * std::pow(std::cos(one.zone().base_helix_angle), 2)), kExact);
}

TEST(ContactLinesTest, SingleUniformlyLoadedLineHasMuKappaSquaredPlusF2Over12) {
  // ε_α = 0.6, ε_β = 0.5: at most phases exactly one (clipped) line is in contact. For one
  // uniformly loaded line of length F centred at h: μ = κ² + F²/(12 b²) (spec 01 §3). F and the
  // centre are computed here by clipping the line to the rectangle by hand.
  const ZoneOfAction z = Zone(0.6, 0.5, 0.05 * kPitch);
  const ContactLineModel model(z, StiffnessProfile::Constant(kK));
  const double b = 0.5 * kFace, t = std::tan(z.base_helix_angle), cb = std::cos(z.base_helix_angle),
               sb = std::sin(z.base_helix_angle);
  const double xs = -0.5 * z.length - z.pitch_point_offset, xe = xs + z.length;
  int checked = 0;
  for (double theta = 0.01; theta < kTwoPi; theta += 0.05) {
    const ContactLineIntegrals sums = model.CalcIntegrals(theta);
    if (sums.num_lines != 1) continue;
    // Find the line and clip: y ∈ [−b, b] ∩ [(x_j − x_e)/t, (x_j − x_s)/t] (t > 0).
    for (int j = -5; j <= 5; ++j) {
      const double xj = (theta / kTwoPi + j) * kPitch;
      const double lo = std::max(-b, (xj - xe) / t), hi = std::min(b, (xj - xs) / t);
      if (hi <= lo) continue;
      const double f_len = (hi - lo) / cb;
      const double h = 0.5 * (lo + hi) / cb - xj * sb;  // centre's σ (s = +1)
      const MeshParameters p = model.CalcMeshParameters(theta);
      EXPECT_NEAR(sums.length, f_len, kExact * kFace);
      EXPECT_NEAR(p.load_centre, h, kExact * kFace);
      EXPECT_NEAR(p.mu, (h / b) * (h / b) + f_len * f_len / (12.0 * b * b), 1e-11);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(ContactLinesTest, FourierCoefficientsAreExact) {
  // Against a direct DFT of M samples: for these continuous piecewise-polynomial channels the
  // aliasing error is O(M^-2) of the kinks ≈ 1e-9 relative at M = 2^15.
  for (const ZoneOfAction& z :
       {Zone(1.55, 1.3, 0.2 * kPitch), Zone(1.3, 0.45, -0.1 * kPitch, -1)}) {
    const double g = z.length;
    const StiffnessProfile tooth =
        StiffnessProfile::PiecewiseLinear({0.0, 0.5 * g, g}, {0.7 * kK, kK, 0.6 * kK});
    const ContactLineModel model(z, tooth);
    const int terms = 40;
    const FourierCoefficient series = MakeFourierMeshCoefficient(model, terms);
    const int m = 1 << 15;
    std::vector<VectorX> samples(m, VectorX(3));
    for (int i = 0; i < m; ++i) model.CalcChannels(kTwoPi * i / m, samples[i]);
    const double kbar = series.mean()[0];
    const double b = model.half_face_width();
    for (int n = 0; n <= terms; ++n) {
      VectorXc dft = VectorXc::Zero(3);
      for (int i = 0; i < m; ++i) {
        dft += samples[i].cast<Complex>() * std::polar(1.0 / m, -kTwoPi * n * i / m);
      }
      for (int c = 0; c < 3; ++c) {
        const Complex mine = n == 0 ? Complex(series.mean()[c], 0.0) : series.harmonics()(c, n - 1);
        EXPECT_NEAR(std::abs(mine - dft[c]), 0.0, 1e-8 * kbar * std::pow(b, c))
            << "n = " << n << ", channel " << c;
      }
    }
  }
  // Spur: the exact series of the steps equals ToFourier of the piecewise-constant coefficient
  // (closed-form sinc coefficients, an independent path).
  const ContactLineModel spur(Zone(1.62, 0.0, 0.07 * kPitch), StiffnessProfile::Constant(kK));
  const FourierCoefficient a = MakeFourierMeshCoefficient(spur, 30);
  const FourierCoefficient b = ToFourier(MakePiecewiseConstantMeshCoefficient(spur), 30);
  EXPECT_LT((a.harmonics() - b.harmonics()).cwiseAbs().maxCoeff(), 1e-12 * kK * kFace);
  EXPECT_NEAR(a.mean()[0], b.mean()[0], 1e-12 * kK * kFace);
}

TEST(ContactLinesTest, FourierConvergesAtTheRateOfKinksAndMeetsTolerance) {
  // Helical, constant k: K(θ) ∝ L(θ) is continuous and piecewise linear, so c_n = O(n^-2) and the
  // L2 error of S_N decays like N^{-3/2}. Errors by midpoint quadrature against CalcChannels.
  const ContactLineModel model(Zone(1.6, 0.7), StiffnessProfile::Constant(kK));
  auto l2_error = [&](const Coefficient& c, int channel) {
    const int pts = 1 << 14;
    VectorX exact(3), approx(3);
    double sum = 0.0;
    for (int i = 0; i < pts; ++i) {
      const double t = (i + 0.5) * kTwoPi / pts;
      model.CalcChannels(t, exact);
      Evaluate(c, t, approx);
      sum += std::pow(exact[channel] - approx[channel], 2);
    }
    return std::sqrt(sum / pts);
  };
  std::vector<double> err;
  for (int n : {16, 64, 256}) err.push_back(l2_error(MakeFourierMeshCoefficient(model, n), 0));
  for (size_t i = 1; i < err.size(); ++i) {
    EXPECT_NEAR(std::log(err[i - 1] / err[i]) / std::log(4.0), 1.5, 0.15);
  }
  for (double tol : {1e-2, 1e-3}) {
    const FourierFit fit = MakeFourierMeshCoefficientWithTolerance(model, tol);
    ASSERT_TRUE(fit.tolerance_met);
    const Coefficient mean_only = FourierCoefficient(fit.fourier.mean(), MatrixXc(3, 0));
    for (int c = 0; c < 3; ++c) {
      const double variation = l2_error(mean_only, c);
      EXPECT_LE(l2_error(fit.fourier, c), tol * variation * 1.001) << "channel " << c;
    }
  }
}

TEST(ContactLinesTest, TableSamplesAndAutoForms) {
  const ContactLineModel model(Zone(1.6, 0.7), StiffnessProfile::Constant(kK));
  const TableCoefficient table = MakeTableMeshCoefficient(model, 64);
  VectorX direct(3);
  for (int s = 0; s < 64; ++s) {
    model.CalcChannels(table.sample_theta(s), direct);
    EXPECT_EQ((table.samples().col(s) - direct).norm(), 0.0);
  }
  const Coefficient helical = MakeMeshCoefficient(model);
  EXPECT_TRUE(std::holds_alternative<FourierCoefficient>(helical));
  EXPECT_EQ(Classify(helical), TimeDependence::kSmoothPeriodic);
  MeshCoefficientOptions opts;
  opts.form = MeshCoefficientForm::kTable;
  opts.num_samples = 32;
  EXPECT_EQ(std::get<TableCoefficient>(MakeMeshCoefficient(model, opts)).num_samples(), 32);
  opts.form = MeshCoefficientForm::kFourier;
  opts.num_terms = 7;
  EXPECT_EQ(std::get<FourierCoefficient>(MakeMeshCoefficient(model, opts)).num_terms(), 7);
  opts.num_terms = -1;
  EXPECT_THROWS_MESSAGE(MakeMeshCoefficient(model, opts), InvalidInput, "num_terms");
  // Helical with integer ε_β and constant k: L (hence K) is constant, but K h is not (the lines'
  // distance from p0 along the path moves), so the coefficient stays periodic.
  const ContactLineModel integer(Zone(1.5, 1.0), StiffnessProfile::Constant(kK));
  const FourierCoefficient s = MakeFourierMeshCoefficient(integer, 8);
  EXPECT_LT(s.harmonics().row(kMeshStiffnessChannel).cwiseAbs().maxCoeff(), 1e-12 * kK * kFace);
}

TEST(ContactLinesTest, MeshParametersFromChannelsInvertsTheChannels) {
  const MeshParameters p = MeshParametersFromChannels(2.0, 0.5, 0.3, 0.5);
  EXPECT_DOUBLE_EQ(p.stiffness, 2.0);
  EXPECT_DOUBLE_EQ(p.load_centre, 0.25);
  EXPECT_DOUBLE_EQ(p.kappa, 0.5);
  EXPECT_DOUBLE_EQ(p.mu, 0.3 / (2.0 * 0.25));
  const MeshParameters none = MeshParametersFromChannels(0.0, 0.0, 0.0, 0.5);
  EXPECT_EQ(none.load_centre, 0.0);
  EXPECT_EQ(none.mu, 0.0);
}

TEST(ContactLinesTest, ZoneFromGearGeometry) {
  // z1 = 20, z2 = 40, m = 2 mm, α = 20°, no shift, standard centre distance:
  // r_b2 = 40 mm cos 20°, r_a2 = 42 mm, g_f = √(r_a2² − r_b2²) − r_b2 tan 20° (hand-computed
  // 5.058576 mm), g_a = √(22² − r_b1²) − r_b1 tan 20° (4.595991 mm).
  GearPairGeometry geo;
  const double alpha = DegToRad(20.0);
  geo.gear.base_radius = 0.040 * std::cos(alpha);
  geo.gear.tip_radius = 0.042;
  geo.pinion.base_radius = 0.020 * std::cos(alpha);
  geo.pinion.tip_radius = 0.022;
  geo.operating_pressure_angle = alpha;
  geo.transverse_base_pitch = kPi * 0.002 * std::cos(alpha);
  geo.line_of_action_length = 0.005058576 + 0.004595991;
  geo.face_width = 0.02;
  geo.base_helix_angle = 0.25;
  geo.pinion.hand = HelixHand::kRight;
  const ZoneOfAction z = MakeZoneOfAction(geo, 1);
  EXPECT_NEAR(-0.5 * z.length - z.pitch_point_offset, -0.005058576, 1e-9);  // x_s = −g_f
  EXPECT_DOUBLE_EQ(z.face_width, 0.02);
  EXPECT_DOUBLE_EQ(z.base_helix_angle, -0.25);  // ψ = −s·h·β_b (as mesh_frame.hpp)
  EXPECT_EQ(z.drive_sign, 1);
  EXPECT_DOUBLE_EQ(MakeZoneOfAction(geo, -1).base_helix_angle, 0.25);
  geo.pinion.hand = HelixHand::kLeft;
  EXPECT_DOUBLE_EQ(MakeZoneOfAction(geo, 1).base_helix_angle, 0.25);
  EXPECT_THROWS_MESSAGE(MakeZoneOfAction(geo, 0), InvalidInput, "drive_sign");
  geo.pinion.hand = HelixHand::kNone;
  EXPECT_THROWS_MESSAGE(MakeZoneOfAction(geo, 1), InvalidInput, "hand");
}

TEST(ContactLinesTest, InvalidInputThrowsNamingTheField) {
  const StiffnessProfile k = StiffnessProfile::Constant(kK);
  ZoneOfAction z = Zone(1.5, 0.5);
  z.length = 0.0;
  EXPECT_THROWS_MESSAGE(ContactLineModel(z, k), InvalidInput, "zone.length");
  z = Zone(1.5, 0.5);
  z.face_width = std::nan("");
  EXPECT_THROWS_MESSAGE(ContactLineModel(z, k), InvalidInput, "zone.face_width");
  z = Zone(1.5, 0.5);
  z.transverse_base_pitch = -1.0;
  EXPECT_THROWS_MESSAGE(ContactLineModel(z, k), InvalidInput, "zone.transverse_base_pitch");
  z = Zone(1.5, 0.5);
  z.base_helix_angle = 2.0;
  EXPECT_THROWS_MESSAGE(ContactLineModel(z, k), InvalidInput, "zone.base_helix_angle");
  z = Zone(1.5, 0.5);
  z.drive_sign = 0;
  EXPECT_THROWS_MESSAGE(ContactLineModel(z, k), InvalidInput, "zone.drive_sign");
  EXPECT_THROWS_MESSAGE(ContactLineModel(Zone(0.6, 0.3), k), InvalidInput, "total contact ratio");
  EXPECT_THROWS_MESSAGE(
      ContactLineModel(Zone(1.5, 0.5), StiffnessProfile::PiecewiseConstant({0.0, 0.001}, {kK})),
      InvalidInput, "profile: its knots cover");
  EXPECT_THROWS_MESSAGE(StiffnessProfile::PiecewiseConstant({0.0, 0.2, 0.1}, {kK, kK}),
                        InvalidInput, "profile knots: must be strictly increasing");
  EXPECT_THROWS_MESSAGE(StiffnessProfile::PiecewiseLinear({0.0, 0.1}, {kK, -1.0}), InvalidInput,
                        "profile values\\[1\\]");
  EXPECT_THROWS_MESSAGE(StiffnessProfile::Constant(-1.0), InvalidInput, "profile k");
  EXPECT_THROWS_MESSAGE(MakePiecewiseConstantMeshCoefficient(ContactLineModel(Zone(1.5, 0.5), k)),
                        InvalidInput, "zone.base_helix_angle");
  EXPECT_THROWS_MESSAGE(MakeFourierMeshCoefficient(ContactLineModel(Zone(1.5, 0.5), k), -1),
                        InvalidInput, "num_terms");
}

TEST(ContactLinesTest, CalcChannelsDoesNotAllocate) {
  if (!GEARDYN_HAVE_ALLOCATION_COUNTER) GTEST_SKIP() << "no allocation counter in this build";
  const double g = 1.55 * kPitch;
  const ContactLineModel model(
      Zone(1.55, 1.3), StiffnessProfile::PiecewiseLinear({0.0, 0.5 * g, g}, {kK, 2 * kK, kK}));
  VectorX out(3);
  double sink = 0.0;
  const long allocations = test::CountAllocations([&] {
    for (double t = -20.0; t < 20.0; t += 0.01) {
      model.CalcChannels(t, out);
      sink += out[0] + model.CalcMeshParameters(t).mu;
    }
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace geardyn
