// Tests of geardyn/models/mesh/transmission_error.hpp against independent truths:
//  * a brute-force composite Simpson quadrature along every clipped contact line, written here
//    from the documented geometry (lines by mesh cycle n at x = (θ/2π − n) p_bt, the projection σ,
//    the relief/crowning/slope/pitch/runout formulas of tooth_modifications.hpp) with no shared
//    code and no knowledge of the kinks;
//  * closed forms: a uniform separation gives ε = [e0, 0]; a lead slope on a spur pair is the
//    twist ε_ζ = −s f_Hβ/B; crowning gives ∫ke = k C_b B/3 per line; a linear tip relief in the
//    double-contact zone is two springs in parallel with one relieved; runout is a sinusoid;
//  * periodicity over the hunting period lcm(z_1, z_2) and not over any proper divisor;
//  * Fourier coefficients against a direct trapezoidal DFT of the pointwise channels.
#include "geardyn/models/mesh/transmission_error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <ostream>
#include <random>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
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
constexpr double kUm = 1e-6;  // [m]
// Exact integrals vs closed forms: round-off of O(100) flops.
constexpr double kExact = 1e-12;
// Brute force: composite Simpson with 4000 panels per clipped line, blind to the kinks of e and
// k; a panel holding a kink errs by O(h²·jump of the slope) → ~1e-8 relative.
constexpr int kSimpsonPanels = 4000;
constexpr double kBruteTol = 1e-7;

/// Single-tooth-like profile k(r) over the path, continuous (0.6, 1, 1, 0.5)·k at r/g_α = (0,
/// 0.3, 0.7, 1).
StiffnessProfile ToothProfile(double eps_alpha) {
  const double g = eps_alpha * kPitch;
  return StiffnessProfile::PiecewiseLinear({0.0, 0.3 * g, 0.7 * g, g},
                                           {0.6 * kK, kK, kK, 0.5 * kK});
}
double ToothProfileAt(double eps_alpha, double r) {
  const double u = r / (eps_alpha * kPitch);
  if (u < 0.3) return kK * (0.6 + 0.4 * u / 0.3);
  if (u < 0.7) return kK;
  return kK * (1.0 - 0.5 * (u - 0.7) / 0.3);
}

/// Independent separation e(x, y, n, θ) from the documented formulas.
struct TestSeparation {
  double xs = 0.0, xe = 0.0, b = 0.0, cos_b = 1.0;
  ToothModifications m;
  ToothErrors err;
  std::vector<double> lag1, lag2;

  TestSeparation(const ZoneOfAction& z, const ToothModifications& mods, const ToothErrors& errors)
      : m(mods), err(errors) {
    xs = -0.5 * z.length - z.pitch_point_offset;
    xe = xs + z.length;
    b = 0.5 * z.face_width;
    cos_b = std::cos(z.base_helix_angle);
    lag1 = Lags(err.pinion_pitch_deviations);
    lag2 = Lags(err.gear_pitch_deviations);
  }
  static std::vector<double> Lags(const std::vector<double>& f) {
    std::vector<double> lag(f.size(), 0.0);
    double mean = 0.0;
    for (size_t i = 1; i < f.size(); ++i) lag[i] = lag[i - 1] + f[i];
    for (double v : lag) mean += v / static_cast<double>(f.size());
    for (double& v : lag) v -= mean;
    return lag;
  }
  static double Band(const ProfileRelief& r, double depth) {
    if (r.amount == 0.0 || depth <= 0.0) return 0.0;
    const double u = depth / r.length;
    return r.shape == ReliefShape::kLinear ? r.amount * u : r.amount * u * u;
  }
  double operator()(double x, double y, long n, double theta) const {
    double e = Band(m.pinion_tip_relief, x - (xe - m.pinion_tip_relief.length)) +
               Band(m.gear_root_relief, x - (xe - m.gear_root_relief.length)) +
               Band(m.gear_tip_relief, xs + m.gear_tip_relief.length - x) +
               Band(m.pinion_root_relief, xs + m.pinion_root_relief.length - x);
    e += m.lead_crowning * (y / b) * (y / b) + m.lead_slope * y / (2.0 * b);
    double lag = 0.0;
    if (!lag1.empty()) lag += lag1[((n % err.pinion_teeth) + err.pinion_teeth) % err.pinion_teeth];
    if (!lag2.empty()) lag -= lag2[((n % err.gear_teeth) + err.gear_teeth) % err.gear_teeth];
    if (err.pinion_runout > 0.0) {
      lag -= err.pinion_runout * std::cos(theta / err.pinion_teeth + err.pinion_runout_phase);
    }
    if (err.gear_runout > 0.0) {
      lag += err.gear_runout * std::cos(theta / err.gear_teeth + err.gear_runout_phase);
    }
    return e + cos_b * lag;
  }
};

struct BruteSums {
  double k = 0.0, k_sigma = 0.0, k_e = 0.0, k_sigma_e = 0.0;
  int lines = 0;
};

/// Composite Simpson along every clipped line. Line n (the pair of mesh cycle n) is
/// {x + y tan β = (θ/2π − n) p}; a point counts when x_s ≤ x ≤ x_e and |y| ≤ b; its σ is the
/// projection (p − p0)·σ̂ with σ̂ = s(−sin β, cos β) in (roll, face) coordinates.
BruteSums BruteForce(const ZoneOfAction& z, const std::function<double(double)>& k_of_roll,
                     const TestSeparation& e, double theta) {
  const double b = 0.5 * z.face_width, p = z.transverse_base_pitch;
  const double beta = z.base_helix_angle, s = z.drive_sign, t = std::tan(beta);
  const double xs = -0.5 * z.length - z.pitch_point_offset, xe = xs + z.length;
  const double reach = b * std::abs(t);
  const long n_lo = static_cast<long>(std::floor(theta / kTwoPi - (xe + reach) / p)) - 1;
  const long n_hi = static_cast<long>(std::ceil(theta / kTwoPi - (xs - reach) / p)) + 1;
  BruteSums out;
  for (long n = n_lo; n <= n_hi; ++n) {
    const double xn = (theta / kTwoPi - static_cast<double>(n)) * p;
    double lo = -b, hi = b;
    if (t == 0.0) {
      if (xn < xs || xn >= xe) continue;
    } else {
      const double y1 = (xn - xe) / t, y2 = (xn - xs) / t;
      lo = std::max(-b, std::min(y1, y2));
      hi = std::min(b, std::max(y1, y2));
      if (!(hi > lo)) continue;
    }
    ++out.lines;
    const double h = (hi - lo) / kSimpsonPanels;
    for (int i = 0; i <= 2 * kSimpsonPanels; ++i) {
      const double y = lo + 0.5 * h * i;
      const double w = (i == 0 || i == 2 * kSimpsonPanels) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      const double x = xn - y * t;
      const double kk = k_of_roll(x - xs) * w * h / 6.0 / std::cos(beta);
      const double sigma = s * (-x * std::sin(beta) + y * std::cos(beta));
      const double ee = e(x, y, n, theta);
      out.k += kk;
      out.k_sigma += kk * sigma;
      out.k_e += kk * ee;
      out.k_sigma_e += kk * sigma * ee;
    }
  }
  return out;
}

// Modifications and errors touching every channel: tip reliefs of both shapes, crowning, a lead
// slope; pitch deviations and runout on both members (hunting period lcm(3, 4) = 12).
ToothModifications SampleModifications() {
  ToothModifications m;
  m.pinion_tip_relief = {12 * kUm, 0.35 * kPitch, ReliefShape::kLinear};
  m.gear_tip_relief = {9 * kUm, 0.45 * kPitch, ReliefShape::kParabolic};
  m.lead_crowning = 5 * kUm;
  m.lead_slope = -7 * kUm;
  return m;
}

ToothErrors SampleErrors() {
  ToothErrors err;
  err.pinion_teeth = 3;
  err.gear_teeth = 4;
  err.pinion_pitch_deviations = {1.5 * kUm, -2.5 * kUm, 1.0 * kUm};
  err.gear_pitch_deviations = {0.0, 2 * kUm, -1 * kUm, -1 * kUm};
  err.pinion_runout = 4 * kUm;
  err.pinion_runout_phase = 0.3;
  err.gear_runout = 6 * kUm;
  err.gear_runout_phase = 2.1;
  return err;
}

// --------------------------------------------------------------------- brute-force quadrature

struct BruteCase {
  double eps_alpha, eps_beta, offset;
  int drive_sign;
  double beta_sign;
  bool tooth_profile;
};

void PrintTo(const BruteCase& c, std::ostream* os) {
  *os << "eps_alpha " << c.eps_alpha << ", eps_beta " << c.beta_sign * c.eps_beta << ", offset "
      << c.offset / kPitch << " p_bt, drive " << c.drive_sign
      << (c.tooth_profile ? ", tooth profile" : ", constant k");
}

class TransmissionErrorBruteForceTest : public ::testing::TestWithParam<BruteCase> {};

TEST_P(TransmissionErrorBruteForceTest, IntegralsMatchBruteForceQuadrature) {
  const BruteCase c = GetParam();
  const ZoneOfAction zone = Zone(c.eps_alpha, c.eps_beta, c.offset, c.drive_sign, c.beta_sign);
  const double ea = c.eps_alpha;
  const StiffnessProfile profile =
      c.tooth_profile ? ToothProfile(ea) : StiffnessProfile::Constant(kK);
  std::function<double(double)> k_of_roll = [&](double r) {
    return c.tooth_profile ? ToothProfileAt(ea, r) : kK;
  };
  ToothModifications m = SampleModifications();
  m.pinion_root_relief = {3 * kUm, 0.2 * kPitch, ReliefShape::kLinear};
  const ToothErrors err = SampleErrors();
  const TestSeparation truth(zone, m, err);

  for (const bool with_errors : {false, true}) {
    const ToothErrors used = with_errors ? err : ToothErrors{};
    const TransmissionErrorModel model(ContactLineModel(zone, profile), m, used);
    const TestSeparation e(zone, m, used);
    const ContactLineModel& lines = model.contact_lines();
    EXPECT_EQ(model.period_meshes(), with_errors ? 12 : 1);
    const double b = lines.half_face_width();
    for (double theta : {0.1234, 1.0, 2.5, 3.3, 4.71, 5.9, 9.4, 27.3, 61.0, 75.0}) {
      const SeparationIntegrals a = model.CalcIntegrals(theta);
      const BruteSums q = BruteForce(zone, k_of_roll, e, theta);
      const double scale = kK * kFace * 20 * kUm;  // K·e magnitude [N]
      EXPECT_EQ(a.num_lines, q.lines) << "theta " << theta;
      EXPECT_NEAR(a.stiffness, q.k, kBruteTol * kK * kFace) << "theta " << theta;
      EXPECT_NEAR(a.k_e, q.k_e, kBruteTol * scale) << "theta " << theta;
      EXPECT_NEAR(a.k_sigma_e, q.k_sigma_e, kBruteTol * scale * b) << "theta " << theta;
      // K and K·h are ContactLineModel's (the same clipped lines and σ).
      const ContactLineIntegrals cl = lines.CalcIntegrals(theta);
      EXPECT_NEAR(a.stiffness, cl.stiffness, kExact * cl.stiffness);
      EXPECT_NEAR(a.first_moment, cl.first_moment, kExact * cl.stiffness * b);
      EXPECT_EQ(a.num_lines, cl.num_lines);
      // The channels are the integrals.
      VectorX ch(kNumSeparationChannels);
      model.CalcChannels(theta, ch);
      EXPECT_EQ(ch[kSeparationKeChannel], a.k_e);
      EXPECT_EQ(ch[kSeparationKSigmaEChannel], a.k_sigma_e);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Zones, TransmissionErrorBruteForceTest,
                         ::testing::Values(BruteCase{1.62, 0.0, 0.0, 1, 1.0, false},
                                           BruteCase{1.62, 0.0, 0.2 * kPitch, -1, 1.0, true},
                                           BruteCase{1.55, 1.3, 0.2 * kPitch, 1, 1.0, true},
                                           BruteCase{1.55, 1.3, 0.2 * kPitch, -1, 1.0, true},
                                           BruteCase{1.55, 1.3, -0.1 * kPitch, 1, -1.0, false},
                                           BruteCase{1.4, 0.45, 0.0, -1, -1.0, true},
                                           BruteCase{2.3, 2.7, 0.3 * kPitch, 1, 1.0, true}));

// --------------------------------------------------------------------------- closed forms

TEST(TransmissionErrorTest, UniformSeparationGivesNormalErrorOnly) {
  // A gear eccentricity moves every contact point of the pair by the same normal distance
  // e0(θ) = cos β_b r_e cos(θ/z_2 + φ): ε = [e0, 0] for any K, h, μ (helical zones with a moving
  // load centre, a stiffness profile, both drive signs).
  for (int s : {1, -1}) {
    for (double eps_beta : {0.0, 0.7, 1.3}) {
      const ZoneOfAction zone = Zone(1.55, eps_beta, 0.25 * kPitch, s);
      ToothErrors err;
      err.pinion_teeth = 25;
      err.gear_teeth = 61;
      err.gear_runout = 20 * kUm;
      err.gear_runout_phase = 0.8;
      const TransmissionErrorModel model(ContactLineModel(zone, ToothProfile(1.55)), {}, err);
      const double cb = std::cos(zone.base_helix_angle);
      for (double theta = 0.05; theta < kTwoPi * 1525; theta += 37.1) {
        const Vector2 eps = model.CalcTransmissionError(theta);
        const double e0 = cb * 20 * kUm * std::cos(theta / 61 + 0.8);
        EXPECT_NEAR(eps[0], e0, 1e-12 * 20 * kUm) << "theta " << theta;
        EXPECT_NEAR(eps[1], 0.0, 1e-12 * 20 * kUm / kFace) << "theta " << theta;
      }
    }
  }
}

TEST(TransmissionErrorTest, LeadSlopeOnSpurIsAPureTwist) {
  // e = f y/B = (s f/B) σ on every line (σ = s y): e = ε_η − σ ε_ζ with ε_η = 0, ε_ζ = −s f/B.
  const double f = 9 * kUm;
  for (int s : {1, -1}) {
    for (double eps_alpha : {1.3, 1.62, 2.4}) {
      ToothModifications m;
      m.lead_slope = f;
      const TransmissionErrorModel model(
          ContactLineModel(Zone(eps_alpha, 0.0, 0.1 * kPitch, s), ToothProfile(eps_alpha)), m);
      for (double theta = 0.01; theta < kTwoPi; theta += 0.173) {
        const Vector2 eps = model.CalcTransmissionError(theta);
        EXPECT_NEAR(eps[0], 0.0, kExact * f);
        EXPECT_NEAR(eps[1], -s * f / kFace, kExact * f / kFace);
      }
    }
  }
}

/// Spur lines in contact at θ, counted from the geometry: x_n = (θ/2π − n) p ∈ [x_s, x_e).
std::vector<long> SpurLinesInContact(const ZoneOfAction& z, double theta) {
  const double xs = -0.5 * z.length - z.pitch_point_offset, xe = xs + z.length;
  std::vector<long> lines;
  for (long n = static_cast<long>(theta / kTwoPi) - 20; n <= static_cast<long>(theta / kTwoPi) + 20;
       ++n) {
    const double xn = (theta / kTwoPi - static_cast<double>(n)) * z.transverse_base_pitch;
    if (xn >= xs && xn < xe) lines.push_back(n);
  }
  return lines;
}

TEST(TransmissionErrorTest, CrowningOnSpurIsAThirdOfTheAmountPerLine) {
  // ∫k C_b (y/b)² dy over [−b, b] = k C_b B/3 per full-face line; with slope too, ε = [C_b/3,
  // −s f/B] (the two are orthogonal on the face).
  const double cb = 6 * kUm, f = -4 * kUm;
  for (int s : {1, -1}) {
    for (double eps_alpha : {1.25, 1.62, 2.3}) {
      const ZoneOfAction zone = Zone(eps_alpha, 0.0, 0.0, s);
      ToothModifications crown;
      crown.lead_crowning = cb;
      const TransmissionErrorModel model(ContactLineModel(zone, StiffnessProfile::Constant(kK)),
                                         crown);
      ToothModifications both = crown;
      both.lead_slope = f;
      const TransmissionErrorModel model2(ContactLineModel(zone, StiffnessProfile::Constant(kK)),
                                          both);
      for (double theta = 0.02; theta < kTwoPi; theta += 0.31) {
        const double lines = static_cast<double>(SpurLinesInContact(zone, theta).size());
        const SeparationIntegrals a = model.CalcIntegrals(theta);
        EXPECT_NEAR(a.k_e, kK * cb * kFace / 3.0 * lines, kExact * kK * cb * kFace * lines);
        EXPECT_NEAR(a.k_sigma_e, 0.0, kExact * kK * cb * kFace * kFace);
        const Vector2 eps = model.CalcTransmissionError(theta);
        EXPECT_NEAR(eps[0], cb / 3.0, kExact * cb);
        EXPECT_NEAR(eps[1], 0.0, kExact * cb / kFace);
        const Vector2 eps2 = model2.CalcTransmissionError(theta);
        EXPECT_NEAR(eps2[0], cb / 3.0, kExact * cb);
        EXPECT_NEAR(eps2[1], -s * f / kFace, kExact * cb / kFace);
      }
    }
  }
}

TEST(TransmissionErrorTest, LinearTipReliefOnSpurIsTwoSpringsInParallel) {
  // ε_α = 1.6: one pair on [x_e − p, x_e − 0.6p), two pairs otherwise. A pinion tip relief of
  // length 0.5p (or a gear tip relief of 0.4p) < 0.6p acts only in a double-contact zone: there
  // ε_η = k_r e_r/(k_r + k_o) for the relieved line r and the other line o (two springs in
  // parallel, one shortened by e_r); in the single zone ε_η = 0.
  const double eps_alpha = 1.6, offset = 0.13 * kPitch;
  const double xs = -0.5 * eps_alpha * kPitch - offset, xe = xs + eps_alpha * kPitch;
  const ZoneOfAction zone = Zone(eps_alpha, 0.0, offset);
  for (const bool pinion : {true, false}) {
    for (const bool profile : {false, true}) {
      ToothModifications m;
      if (pinion) {
        m.pinion_tip_relief = {15 * kUm, 0.5 * kPitch, ReliefShape::kLinear};
      } else {
        m.gear_tip_relief = {15 * kUm, 0.4 * kPitch, ReliefShape::kLinear};
      }
      const StiffnessProfile k = profile ? ToothProfile(eps_alpha) : StiffnessProfile::Constant(kK);
      const TransmissionErrorModel model(ContactLineModel(zone, k), m);
      auto k_at = [&](double x) { return profile ? ToothProfileAt(eps_alpha, x - xs) : kK; };
      auto relief = [&](double x) {
        if (pinion) {
          return x > xe - 0.5 * kPitch ? 15 * kUm * (x - (xe - 0.5 * kPitch)) / (0.5 * kPitch)
                                       : 0.0;
        }
        return x < xs + 0.4 * kPitch ? 15 * kUm * (xs + 0.4 * kPitch - x) / (0.4 * kPitch) : 0.0;
      };
      int single = 0, relieved = 0;
      for (double theta = 0.011; theta < kTwoPi; theta += 0.0371) {
        const std::vector<long> lines = SpurLinesInContact(zone, theta);
        const Vector2 eps = model.CalcTransmissionError(theta);
        EXPECT_NEAR(eps[1], 0.0, kExact * 15 * kUm / kFace);
        if (lines.size() == 1) {
          ++single;
          EXPECT_NEAR(eps[0], 0.0, kExact * 15 * kUm) << "theta " << theta;
          continue;
        }
        ASSERT_EQ(lines.size(), 2u);
        const double x0 = (theta / kTwoPi - static_cast<double>(lines[0])) * kPitch;
        const double x1 = (theta / kTwoPi - static_cast<double>(lines[1])) * kPitch;
        const double e0 = relief(x0), e1 = relief(x1);
        EXPECT_TRUE(e0 == 0.0 || e1 == 0.0);  // one spring relieved
        if (e0 + e1 > 0.0) ++relieved;
        const double expected = (k_at(x0) * e0 + k_at(x1) * e1) / (k_at(x0) + k_at(x1));
        EXPECT_NEAR(eps[0], expected, kExact * 15 * kUm) << "theta " << theta;
      }
      EXPECT_GT(single, 20);
      EXPECT_GT(relieved, 20);
    }
  }
}

// ---------------------------------------------------------------------------- pitch errors

TEST(TransmissionErrorTest, SinglePitchErrorShowsUpOnceEveryPinionRevolution) {
  // Spur, constant k: ε_η = mean over the lines in contact of e_pair(n). Pinion tooth 2 trails by
  // d (f_p = (0, 0, d, −d, 0) for z_1 = 5): lags (0, 0, d, 0, 0) − d/5.
  const double d = 4 * kUm;
  const ZoneOfAction zone = Zone(1.62, 0.0, 0.1 * kPitch);
  ToothErrors err;
  err.pinion_teeth = 5;
  err.gear_teeth = 7;
  err.pinion_pitch_deviations = {0.0, 0.0, d, -d, 0.0};
  const TransmissionErrorModel model(ContactLineModel(zone, StiffnessProfile::Constant(kK)), {},
                                     err);
  ASSERT_EQ(model.period_meshes(), 35);
  int windows = 0;  // separate θ-windows with tooth 2 in mesh over one hunting period
  bool in_window = false;
  for (double theta = 0.013; theta < kTwoPi * 35; theta += 0.0917) {
    const std::vector<long> lines = SpurLinesInContact(zone, theta);
    double expected = 0.0;
    bool tooth2 = false;
    for (long n : lines) {
      const bool hit = ((n % 5) + 5) % 5 == 2;
      tooth2 = tooth2 || hit;
      expected += ((hit ? d : 0.0) - d / 5) / static_cast<double>(lines.size());
    }
    const Vector2 eps = model.CalcTransmissionError(theta);
    EXPECT_NEAR(eps[0], expected, kExact * d) << "theta " << theta;
    // Outside the windows where tooth 2 is in mesh only the common offset −d/5 remains.
    if (!tooth2) {
      EXPECT_NEAR(eps[0], -d / 5, kExact * d);
    }
    if (tooth2 && !in_window) ++windows;
    in_window = tooth2;
  }
  // Once every z_1 = 5 mesh cycles: 35/5 = 7 windows per hunting period.
  EXPECT_EQ(windows, 7);
}

/// Prime factors of P.
std::vector<std::int64_t> PrimeFactors(std::int64_t p) {
  std::vector<std::int64_t> f;
  for (std::int64_t q = 2; q * q <= p; ++q) {
    if (p % q == 0) f.push_back(q);
    while (p % q == 0) p /= q;
  }
  if (p > 1) f.push_back(p);
  return f;
}

/// Closed random single pitch deviations (mean removed) in [−a, a].
std::vector<double> RandomPitch(int z, double a, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-a, a);
  std::vector<double> f(static_cast<size_t>(z));
  double mean = 0.0;
  for (double& v : f) {
    v = u(*rng);
    mean += v / z;
  }
  for (double& v : f) v -= mean;
  return f;
}

TEST(TransmissionErrorTest, PitchErrorsRepeatOverTheHuntingPeriodOnly) {
  std::mt19937 rng(12345);
  const ZoneOfAction zone = Zone(1.55, 1.3, 0.2 * kPitch);
  for (const auto& [z1, z2] : std::vector<std::pair<int, int>>{{3, 4}, {5, 7}, {25, 61}}) {
    ToothErrors err;
    err.pinion_teeth = z1;
    err.gear_teeth = z2;
    err.pinion_pitch_deviations = RandomPitch(z1, 3 * kUm, &rng);
    err.gear_pitch_deviations = RandomPitch(z2, 3 * kUm, &rng);
    const TransmissionErrorModel model(ContactLineModel(zone, ToothProfile(1.55)), {}, err);
    const std::int64_t period = std::lcm(std::int64_t{z1}, std::int64_t{z2});
    ASSERT_EQ(model.period_meshes(), period);
    const double span = kTwoPi * static_cast<double>(period);
    // Periodic over P mesh cycles ...
    double worst = 0.0;
    for (double theta = 0.071; theta < span; theta += 0.37) {
      worst = std::max(
          worst, (model.CalcTransmissionError(theta + span) - model.CalcTransmissionError(theta))
                         .cwiseAbs()
                         .maxCoeff() /
                     kUm);
    }
    EXPECT_LT(worst, 1e-9) << z1 << "/" << z2;
    // ... and over no proper divisor of P (every proper divisor divides some P/q, q prime).
    for (std::int64_t q : PrimeFactors(period)) {
      const double shift = kTwoPi * static_cast<double>(period / q);
      double change = 0.0;
      for (double theta = 0.071; theta < span; theta += 0.37) {
        change = std::max(change, std::abs(model.CalcTransmissionError(theta + shift)[0] -
                                           model.CalcTransmissionError(theta)[0]));
      }
      EXPECT_GT(change, 0.05 * kUm) << z1 << "/" << z2 << " shift " << period / q << " meshes";
    }
    // The coefficients carry the hunting period.
    EXPECT_EQ(MakeTransmissionErrorTableCoefficient(model, 4).period_meshes(), period);
    EXPECT_EQ(MakeSeparationTableCoefficient(model, 4).num_samples(), 4 * period);
    EXPECT_EQ(MakeSeparationFourierCoefficient(model, 3).period_meshes(), period);
  }
}

// --------------------------------------------------------------------------------- runout

TEST(TransmissionErrorTest, RunoutIsASinusoidOncePerRevolution) {
  // ε_η = cos β_b [−r_1 cos(θ/z_1 + φ_1) + r_2 cos(θ/z_2 + φ_2)]: amplitude r cos β_b, period
  // 2π z (one revolution of that member), for every zone and profile.
  const ZoneOfAction zone = Zone(1.45, 0.9, -0.1 * kPitch, -1);
  const double cb = std::cos(zone.base_helix_angle);
  ToothErrors err;
  err.pinion_teeth = 5;
  err.gear_teeth = 7;
  err.pinion_runout = 12 * kUm;
  err.pinion_runout_phase = -0.6;
  const TransmissionErrorModel model(ContactLineModel(zone, ToothProfile(1.45)), {}, err);
  double max_eta = -1.0, min_eta = 1.0;
  for (double theta = 0.0; theta < kTwoPi * 35; theta += 0.05) {
    const double expected = -cb * 12 * kUm * std::cos(theta / 5 - 0.6);
    const Vector2 eps = model.CalcTransmissionError(theta);
    EXPECT_NEAR(eps[0], expected, 1e-12 * 12 * kUm);
    max_eta = std::max(max_eta, eps[0]);
    min_eta = std::min(min_eta, eps[0]);
  }
  EXPECT_NEAR(max_eta, cb * 12 * kUm, 1e-4 * 12 * kUm);
  EXPECT_NEAR(min_eta, -cb * 12 * kUm, 1e-4 * 12 * kUm);
  // Its Fourier series over the hunting period (P = 35) has the once-per-pinion-revolution
  // harmonic m = P/z_1 = 7 in ∫ke = e0 K: c_7 = (A/2) e^{iφ} K̄ with A = −cos β_b r_1 (plus the
  // sidebands of the mesh harmonics of K, at 35 ± 7, ...).
  const FourierCoefficient fc = MakeSeparationFourierCoefficient(model, 40);
  const double kbar = MakeFourierMeshCoefficient(model.contact_lines(), 0).mean()[0];  // K̄
  const Complex c7 = fc.harmonics()(kSeparationKeChannel, 6);
  const Complex expected7 = 0.5 * (-cb * 12 * kUm) * std::polar(1.0, -0.6);
  EXPECT_NEAR(std::abs(c7 / kbar - expected7), 0.0, 1e-12 * 12 * kUm);
  for (int m : {1, 2, 3, 5, 6, 8, 20}) {
    EXPECT_EQ(fc.harmonics()(kSeparationKeChannel, m - 1), Complex(0.0, 0.0)) << "m " << m;
  }
}

// ------------------------------------------------------------------------- coefficients

/// c_m = (1/T) ∫_0^T f e^{−imθ/P} dθ by the trapezoidal rule on `samples` points.
MatrixXc TrapezoidDft(const TransmissionErrorModel& model, int samples, int num_terms) {
  const auto period = static_cast<double>(model.period_meshes());
  MatrixXc c = MatrixXc::Zero(kNumSeparationChannels, num_terms + 1);
  VectorX ch(kNumSeparationChannels);
  for (int s = 0; s < samples; ++s) {
    const double theta = kTwoPi * period * s / samples;
    model.CalcChannels(theta, ch);
    // e^{−imθ/P} by repeated rotation (≤ 300 products: a few hundred ulps).
    const Complex step = std::polar(1.0, -theta / period);
    Complex w(1.0 / samples, 0.0);
    for (int m = 0; m <= num_terms; ++m, w *= step) c.col(m) += ch.cast<Complex>() * w;
  }
  return c;
}

TEST(TransmissionErrorTest, FourierCoefficientsAreExact) {
  // Helical channels are continuous with kinks: the trapezoidal DFT errs by O(h²) ≈ 1e-8.
  const ToothModifications m = SampleModifications();
  const ToothErrors err = SampleErrors();
  for (int s : {1, -1}) {
    const ZoneOfAction zone = Zone(1.55, 1.3, 0.2 * kPitch, s);
    for (const bool with_errors : {false, true}) {
      const TransmissionErrorModel model(ContactLineModel(zone, ToothProfile(1.55)), m,
                                         with_errors ? err : ToothErrors{});
      // Without errors P = 1: harmonics up to 300 (where c_n has decayed by ~1e-4), checking
      // the moment integrals at large arguments; the DFT's aliasing error is O(1/S²).
      const int terms = with_errors ? 60 : 300;
      const int samples = with_errors ? 12 * 8192 : 65536;
      const FourierCoefficient fc = MakeSeparationFourierCoefficient(model, terms);
      ASSERT_EQ(fc.num_terms(), terms);
      const MatrixXc dft = TrapezoidDft(model, samples, terms);
      const double scale = kK * kFace * 10 * kUm;
      double b = 1.0;
      for (int ch = 0; ch < kNumSeparationChannels; ++ch) {
        EXPECT_NEAR(fc.mean()[ch], dft(ch, 0).real(), 1e-6 * scale * b) << "channel " << ch;
        for (int k = 1; k <= terms; ++k) {
          EXPECT_NEAR(std::abs(fc.harmonics()(ch, k - 1) - dft(ch, k)), 0.0, 1e-6 * scale * b)
              << "channel " << ch << " harmonic " << k << " errors " << with_errors;
        }
        b *= 0.5 * kFace;
      }
    }
  }
}

TEST(TransmissionErrorTest, SpurFourierCoefficientsMatchAFineDft) {
  // Spur channels jump where lines enter and leave: the trapezoidal DFT errs by O(h).
  ToothModifications m;
  m.pinion_tip_relief = {12 * kUm, 0.35 * kPitch, ReliefShape::kParabolic};
  m.lead_crowning = 5 * kUm;
  m.lead_slope = 3 * kUm;
  ToothErrors err;
  err.pinion_teeth = 3;
  err.gear_teeth = 2;
  err.gear_pitch_deviations = {2 * kUm, -2 * kUm};
  err.gear_runout = 5 * kUm;
  const TransmissionErrorModel model(
      ContactLineModel(Zone(1.62, 0.0, 0.1 * kPitch), StiffnessProfile::Constant(kK)), m, err);
  const int terms = 30;
  const FourierCoefficient fc = MakeSeparationFourierCoefficient(model, terms);
  const MatrixXc dft = TrapezoidDft(model, 6 * 65536, terms);
  const double scale = kK * kFace * 10 * kUm;
  double b = 1.0;
  for (int ch = 0; ch < kNumSeparationChannels; ++ch) {
    for (int k = 1; k <= terms; ++k) {
      EXPECT_NEAR(std::abs(fc.harmonics()(ch, k - 1) - dft(ch, k)), 0.0, 2e-5 * scale * b)
          << "channel " << ch << " harmonic " << k;
    }
    b *= 0.5 * kFace;
  }
}

TEST(TransmissionErrorTest, TablesHoldExactSamples) {
  ToothModifications m;
  m.pinion_tip_relief = {12 * kUm, 0.35 * kPitch, ReliefShape::kLinear};
  m.lead_crowning = 5 * kUm;
  const ZoneOfAction zone = Zone(1.55, 1.3, 0.2 * kPitch);
  const TransmissionErrorModel plain(ContactLineModel(zone, ToothProfile(1.55)), m);
  const TableCoefficient t1 = MakeSeparationTableCoefficient(plain, 64);
  EXPECT_EQ(t1.period_meshes(), 1);
  EXPECT_EQ(t1.num_samples(), 64);
  const TableCoefficient te = MakeTransmissionErrorTableCoefficient(plain, 64);
  VectorX ch(2);
  for (int s = 0; s < 64; ++s) {
    plain.CalcChannels(t1.sample_theta(s), ch);
    EXPECT_NEAR((t1.samples().col(s) - ch).norm(), 0.0, 1e-13 * ch.norm());
    const Vector2 eps = plain.CalcTransmissionError(t1.sample_theta(s));
    EXPECT_NEAR((te.samples().col(s) - eps).norm(), 0.0, 1e-13 * eps.norm());
  }
  ToothErrors err;
  err.pinion_teeth = 3;
  err.gear_teeth = 4;
  err.gear_runout = 2 * kUm;
  const TransmissionErrorModel hunting(ContactLineModel(zone, ToothProfile(1.55)), m, err);
  const TableCoefficient t2 = MakeTransmissionErrorTableCoefficient(hunting, 16);
  EXPECT_EQ(t2.period_meshes(), 12);
  EXPECT_EQ(t2.num_samples(), 192);
  // The trigonometric interpolant of many exact ε samples reproduces ε between the samples
  // (helical ε is continuous with kinks: aliasing error ~1e-4 of its range).
  const FourierCoefficient f2 = MakeTransmissionErrorFourierCoefficient(hunting, 12 * 128, 2048);
  EXPECT_EQ(f2.period_meshes(), 12);
  VectorX value(2);
  double worst = 0.0;
  for (double theta = 0.037; theta < kTwoPi * 12; theta += 0.29) {
    Evaluate(Coefficient(f2), theta, value);
    worst = std::max(worst, std::abs(value[0] - hunting.CalcTransmissionError(theta)[0]));
  }
  EXPECT_LT(worst, 0.05 * kUm);
}

// Coprime tooth counts (23/19, hunting period P = 437) with pitch deviations and runout on both
// members: the harmonics computed directly at any m (CalcSeparationHarmonics, Poisson sums)
// against an FFT (ToFourier of the table) of the pointwise channels sampled over the whole
// hunting period. Every m up to 3P + 40 is compared, so the zeros between the mesh orders and
// their sidebands jP ± 19, jP ± 23 (and the pitch lines at multiples of 19 and 23) are checked
// too. Helical channels are continuous with kinks: the FFT of 2048 samples per mesh cycle errs
// by O(h²), 16 × the 1e-6 of FourierCoefficientsAreExact's 8192 → 2e-5.
TEST(TransmissionErrorTest, DirectHarmonicsMatchAnFftOverTheCoprimeHuntingPeriod) {
  const ToothModifications m = SampleModifications();
  ToothErrors err;
  err.pinion_teeth = 23;
  err.gear_teeth = 19;
  for (int i = 0; i < 23; ++i) {
    err.pinion_pitch_deviations.push_back(1.5 * kUm * std::sin(kTwoPi * 3 * i / 23.0) +
                                          0.7 * kUm * std::cos(kTwoPi * 5 * i / 23.0));
  }
  for (int i = 0; i < 19; ++i) {
    err.gear_pitch_deviations.push_back(1.1 * kUm * std::cos(kTwoPi * 2 * i / 19.0));
  }
  err.pinion_runout = 4 * kUm;
  err.pinion_runout_phase = 0.3;
  err.gear_runout = 6 * kUm;
  err.gear_runout_phase = 2.1;
  const TransmissionErrorModel model(
      ContactLineModel(Zone(1.55, 1.3, 0.2 * kPitch, 1), ToothProfile(1.55)), m, err);
  ASSERT_EQ(model.period_meshes(), 437);
  const int highest = 3 * 437 + 40;
  const FourierCoefficient fft =
      ToFourier(Coefficient(MakeSeparationTableCoefficient(model, 2048)), highest);
  std::vector<std::int64_t> wanted(highest + 1);
  std::iota(wanted.begin(), wanted.end(), std::int64_t{0});
  const MatrixXc direct = CalcSeparationHarmonics(model, wanted);
  ASSERT_EQ(direct.cols(), highest + 1);
  const double scale = kK * kFace * 10 * kUm;
  double b = 1.0;
  for (int ch = 0; ch < kNumSeparationChannels; ++ch) {
    EXPECT_NEAR(std::abs(direct(ch, 0) - fft.mean()[ch]), 0.0, 2e-5 * scale * b);
    for (int k = 1; k <= highest; ++k) {
      EXPECT_NEAR(std::abs(direct(ch, k) - fft.harmonics()(ch, k - 1)), 0.0, 2e-5 * scale * b)
          << "channel " << ch << " harmonic " << k;
    }
    b *= 0.5 * kFace;
  }
  // The sidebands carry what the runouts put there: the first-order runout lines are of the
  // size A·K̄/2 (not a round-off): compare magnitudes against the FFT at jP ± r.
  for (std::int64_t j : {1, 2}) {
    for (std::int64_t r : {19, 23}) {
      EXPECT_GT(std::abs(direct(0, j * 437 + r)), 1e-4 * scale);
    }
  }
  EXPECT_THROWS_MESSAGE(CalcSeparationHarmonics(model, {-1}), InvalidInput, "harmonics");
}

// ------------------------------------------------------------------------- error paths

TEST(TransmissionErrorTest, InvalidInputsNameTheArgument) {
  const ContactLineModel lines(Zone(1.5, 0.0), StiffnessProfile::Constant(kK));
  ToothModifications bad;
  bad.pinion_tip_relief = {1e-6, 2.0 * kPitch, ReliefShape::kLinear};
  EXPECT_THROWS_MESSAGE(TransmissionErrorModel(lines, bad), InvalidInput,
                        "modifications.pinion_tip_relief.length");
  ToothErrors err;
  err.pinion_teeth = 3;
  err.gear_teeth = 4;
  err.gear_pitch_deviations = {1e-6, 1e-6, 1e-6};
  EXPECT_THROWS_MESSAGE(TransmissionErrorModel(lines, {}, err), InvalidInput,
                        "errors.gear_pitch_deviations");
  const TransmissionErrorModel model(lines, {});
  EXPECT_THROWS_MESSAGE(MakeSeparationTableCoefficient(model, 0), InvalidInput, "samples_per_mesh");
  EXPECT_THROWS_MESSAGE(MakeTransmissionErrorTableCoefficient(model, -2), InvalidInput,
                        "samples_per_mesh");
  EXPECT_THROWS_MESSAGE(MakeSeparationFourierCoefficient(model, -1), InvalidInput, "num_terms");
  EXPECT_THROWS_MESSAGE(MakeTransmissionErrorFourierCoefficient(model, 9, 16), InvalidInput,
                        "num_terms");
  EXPECT_THROWS_MESSAGE(model.CalcIntegrals(std::numeric_limits<double>::infinity()), InvalidInput,
                        "theta");
  VectorX wrong(3);
  EXPECT_THROWS_MESSAGE(model.CalcChannels(0.0, wrong), InvalidInput, "out");
  // No modification at all: zero channels, zero ε.
  EXPECT_EQ(model.CalcTransmissionError(1.0), Vector2::Zero());
  EXPECT_EQ(MakeSeparationFourierCoefficient(model, 4).mean(), VectorX::Zero(2));
}

TEST(TransmissionErrorTest, PointwiseEvaluationDoesNotAllocate) {
  if (!GEARDYN_HAVE_ALLOCATION_COUNTER) GTEST_SKIP() << "no allocation counter in this build";
  ToothModifications m;
  m.pinion_tip_relief = {12 * kUm, 0.35 * kPitch, ReliefShape::kLinear};
  m.lead_crowning = 5 * kUm;
  ToothErrors err;
  err.pinion_teeth = 3;
  err.gear_teeth = 4;
  err.pinion_pitch_deviations = {1.5 * kUm, -2.5 * kUm, 1.0 * kUm};
  err.gear_runout = 6 * kUm;
  const TransmissionErrorModel model(
      ContactLineModel(Zone(1.55, 1.3, 0.2 * kPitch), ToothProfile(1.55)), m, err);
  VectorX out(2);
  double sink = 0.0;
  const long allocations = test::CountAllocations([&] {
    for (double t = -20.0; t < 80.0; t += 0.01) {
      model.CalcChannels(t, out);
      sink += out[0] + model.CalcTransmissionError(t)[1];
    }
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace geardyn
