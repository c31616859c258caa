// Stress suite part B, linear harmonic balance (issue 16: "geardyn never returns garbage").
// Every case has an independent truth: the SDOF FRF |X| = F/(k|1 − r² + 2iζr|) of the
// torsional pair (hb_stress_cases.hpp), the quasi-static DTE F/k(θ), the mass-dominated limit,
// a converged lower-H answer, a GSL rk8pd time integration (hb_fixtures.hpp), the same system
// in mm–t–s units, or the status the solver must report. No NaN/Inf may reach an HbResult.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "stress/hb_stress_cases.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using stress::AllFinite;
using stress::SdofPair;
using stress::StiffnessShape;

// ---------------------------------------------------------------- the SDOF FRF table

/// What a case must give: the closed-form amplitude within `tol` (relative), or a status other
/// than success (a singular dynamic stiffness has no answer).
enum class Expect { kClosedForm, kFailureStatus };

struct FrfCase {
  std::string name;
  double zeta;
  double r;       // f_m / f_n (used when f_m_hz = 0)
  double f_m_hz;  // absolute mesh frequency [Hz] (tiny and huge speeds)
  Expect expect;
  double tol;  // relative, against the closed form
};

void PrintTo(const FrfCase& c, std::ostream* os) { *os << c.name; }

class LinearHbFrfStress : public ::testing::TestWithParam<FrfCase> {};

TEST_P(LinearHbFrfStress, ClosedFormOrStatus) {
  const FrfCase& c = GetParam();
  SdofPair pair;
  pair.zeta = c.zeta;
  pair.harmonic_torque = 20.0;
  const double f_m = c.f_m_hz > 0.0 ? c.f_m_hz : c.r * pair.NaturalHz();
  HbOptions options;
  options.harmonics = 4;
  const HbResult hb = SolveHarmonicBalance(pair.Model(), options, f_m);
  EXPECT_TRUE(AllFinite(hb)) << c.name << ": " << hb.summary.BriefReport();
  if (c.expect == Expect::kFailureStatus) {
    EXPECT_NE(hb.summary.status, Status::kSuccess) << c.name << ": " << hb.summary.BriefReport();
    EXPECT_FALSE(hb.summary.message.empty());
    return;
  }
  ASSERT_EQ(hb.summary.status, Status::kSuccess) << c.name << ": " << hb.summary.BriefReport();
  ASSERT_GE(hb.meshes[0].dte_amplitudes.size(), 2);
  const double truth = pair.FrfAmplitude(f_m);
  EXPECT_NEAR(hb.meshes[0].dte_amplitudes[1], truth, c.tol * truth) << c.name;
  // The mean comes from the synthesized samples (FFT): its round-off is relative to the largest
  // signal, the resonant amplitude (up to 7e6 static deflections here).
  EXPECT_NEAR(hb.meshes[0].mean_dte, pair.StaticDeflection(),
              1e-9 * pair.StaticDeflection() + 1e-14 * truth)
      << c.name;
  // RMS of a single harmonic: amplitude/√2.
  EXPECT_NEAR(hb.meshes[0].rms_dte, truth / std::sqrt(2.0), c.tol * truth) << c.name;
}

// Conditioning: the dynamic stiffness of the resonant harmonic is k|1 − r² + 2iζr|, so the
// relative round-off of the solve is ~ 1e-16 / |1 − r² + 2iζr| (times a few for the rank-one
// mesh operator and the FFT outputs).
INSTANTIATE_TEST_SUITE_P(
    Cases, LinearHbFrfStress,
    ::testing::Values(
        // Undamped, driven exactly at ω_n: the dynamic stiffness is singular to round-off.
        FrfCase{"undamped_exactly_at_resonance", 0.0, 1.0, 0.0, Expect::kFailureStatus, 0.0},
        // ζ = 1e-8 at ω_n: |X| = F/(2ζk) = 5e7 static deflections, conditioning 5e7.
        FrfCase{"zeta_1e-8_at_resonance", 1e-8, 1.0, 0.0, Expect::kClosedForm, 1e-6},
        FrfCase{"zeta_1e-8_just_below_resonance", 1e-8, 1.0 - 1e-7, 0.0, Expect::kClosedForm, 1e-6},
        FrfCase{"zeta_1e-8_just_above_resonance", 1e-8, 1.0 + 3e-8, 0.0, Expect::kClosedForm, 1e-6},
        FrfCase{"undamped_below_resonance", 0.0, 0.45, 0.0, Expect::kClosedForm, 1e-10},
        // r = 1/2: harmonic 2 sits exactly on the undamped mode. It is not loaded, but the free
        // vibration at ω_n = 2ω_m is then periodic too: the periodic solution is not unique and
        // the operator singular — a status, not an answer.
        FrfCase{"undamped_second_harmonic_at_resonance", 0.0, 0.5, 0.0, Expect::kFailureStatus,
                0.0},
        FrfCase{"undamped_above_resonance", 0.0, 2.0, 0.0, Expect::kClosedForm, 1e-10},
        // |1 − r²| = 2e-9: the f_m round-off (1e-16) moves 1 − r² by 2e-16, 1e-7 relative.
        FrfCase{"undamped_1e-9_off_resonance", 0.0, 1.0 - 1e-9, 0.0, Expect::kClosedForm, 1e-5},
        // Tiny speed: quasi-static, |X| → F/k.
        FrfCase{"quasi_static_1e-3_Hz", 0.05, 0.0, 1e-3, Expect::kClosedForm, 1e-10},
        // Huge speed: mass dominated, |X| → F/(m_e ω²) (r ≈ 216: |X| ≈ 2e-5 F/k).
        FrfCase{"mass_dominated_1e6_Hz", 0.05, 0.0, 1e6, Expect::kClosedForm, 1e-8},
        FrfCase{"undamped_mass_dominated_1e6_Hz", 0.0, 0.0, 1e6, Expect::kClosedForm, 1e-8}),
    [](const ::testing::TestParamInfo<FrfCase>& param_info) {
      std::string s = param_info.param.name;
      for (char& ch : s) {
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      }
      return s;
    });

TEST(LinearHbStress, MassDominatedLimitIsForceOverMassOmegaSquared) {
  SdofPair pair;
  pair.harmonic_torque = 20.0;
  HbOptions options;
  options.harmonics = 4;
  const double f_m = 1e6, w = 2.0 * stress::kPi * f_m;
  const HbResult hb = SolveHarmonicBalance(pair.Model(), options, f_m);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  // |X| = F/(m_e ω²) (1 + O(1/r²)), r² ≈ 4.7e4.
  const double limit = pair.AlternatingForce() / (pair.MeanMass() * w * w);
  EXPECT_NEAR(hb.meshes[0].dte_amplitudes[1], limit, 1e-4 * limit);
}

// ---------------------------------------------------------------- LTV: tiny and huge speeds

// Quasi-static limit of k(θ) = k(1 + a cos θ), ε = 0: δ(θ) = F/k(θ), so
// mean = F/(k√(1−a²)) and mean of δ² = F²/(k²(1−a²)^{3/2}) (Gradshteyn 3.613).
TEST(LinearHbStress, LtvQuasiStaticAtOneMilliHertzIsTheStaticDeflectionPerTheta) {
  SdofPair pair;
  pair.shape = StiffnessShape::kCosine;
  pair.a = 0.5;
  HbOptions options;
  options.harmonics = 48;  // Fourier coefficients of 1/(1 + a cos θ) decay like 0.268^k
  const HbResult hb = SolveHarmonicBalance(pair.Model(), options, 1e-3);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  EXPECT_TRUE(AllFinite(hb));
  const double F_k = pair.StaticDeflection(), s = 1.0 - pair.a * pair.a;
  const double mean = F_k / std::sqrt(s);
  const double rms = F_k * std::sqrt(std::pow(s, -1.5) - 1.0 / s);
  EXPECT_NEAR(hb.meshes[0].mean_dte, mean, 1e-9 * mean);
  EXPECT_NEAR(hb.meshes[0].rms_dte, rms, 1e-8 * rms);
  // The reported error estimate is honest: the answer is converged.
  EXPECT_LT(hb.summary.error_estimate, 1e-8);
}

// Mass-dominated limit: at f_m = 1 MHz (r ≈ 216) the mesh cannot follow k(θ): δ ≈ const and the
// mean force balance k̄ δ̄ = F gives mean DTE = F/k̄ (the mean stiffness), the ripple O(a/r²).
TEST(LinearHbStress, LtvAtOneMegaHertzIsTheMeanStiffnessDeflection) {
  SdofPair pair;
  pair.shape = StiffnessShape::kCosine;
  pair.a = 0.5;
  HbOptions options;
  options.harmonics = 16;
  const HbResult hb = SolveHarmonicBalance(pair.Model(), options, 1e6);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  EXPECT_TRUE(AllFinite(hb));
  const double F_k = pair.StaticDeflection();
  const double r2 = std::pow(1e6 / pair.NaturalHz(), 2);
  EXPECT_NEAR(hb.meshes[0].mean_dte, F_k, 10.0 * pair.a * pair.a / r2 * F_k);
  EXPECT_LT(hb.meshes[0].rms_dte, 10.0 * pair.a / r2 * F_k);
}

// ---------------------------------------------------------------- many harmonics

// A smooth LTV pair converges to round-off at H = 24; H = 256 (513 harmonics, a Woodbury
// coupling of size 2·513) must give the same answer — no loss to conditioning or aliasing.
TEST(LinearHbStress, SmoothLtvAt256HarmonicsEqualsTheConvergedLowH) {
  SdofPair pair;
  pair.shape = StiffnessShape::kCosine;
  pair.a = 0.4;
  pair.e1 = 3e-6;
  pair.harmonic_torque = 10.0;
  const SystemModel model = pair.Model();
  for (const double f_m : {0.31 * pair.NaturalHz(), 0.97 * pair.NaturalHz()}) {
    HbOptions options;
    options.harmonics = 24;
    options.time_samples = 4096;  // the same samples: peak-to-peak is a sampled max − min
    const HbResult low = SolveHarmonicBalance(model, options, f_m);
    options.harmonics = 256;
    const HbResult high = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(low.summary.ok() && high.summary.ok()) << high.summary.BriefReport();
    EXPECT_TRUE(AllFinite(high));
    EXPECT_EQ(high.harmonics, 256);
    const HbMeshOutput &a = low.meshes[0], &b = high.meshes[0];
    EXPECT_NEAR(b.mean_dte, a.mean_dte, 1e-9 * std::abs(a.mean_dte)) << f_m;
    EXPECT_NEAR(b.rms_dte, a.rms_dte, 1e-9 * a.rms_dte) << f_m;
    EXPECT_NEAR(b.peak_to_peak_dte, a.peak_to_peak_dte, 1e-8 * a.peak_to_peak_dte) << f_m;
    EXPECT_LT(high.summary.error_estimate, 1e-12);
  }
}

// A rectangular stiffness wave (Fourier coefficients ∝ 1/k: the slowest case) at H = 256
// against an independent GSL rk8pd integration of the same equations (exact steps, K frozen
// per interval): the RMS DTE within the reported error estimate. Parametric excitation only
// (ε = 0, no harmonic torque): the reference freezes the load with K per interval, exact only
// for a load that is constant there.
TEST(LinearHbStress, SpurWaveAt256HarmonicsAgreesWithTimeIntegrationWithinItsEstimate) {
  SdofPair pair;
  pair.shape = StiffnessShape::kSpurWave;
  const SystemModel model = pair.Model();
  const double f_m = 0.37 * pair.NaturalHz();
  HbOptions options;
  options.harmonics = 256;
  options.keep_harmonics = true;
  const HbResult hb = SolveHarmonicBalance(model, options, f_m);
  ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
  EXPECT_TRUE(AllFinite(hb));
  const test::OdeSteadyState ode = test::IntegrateSteadyState(model, f_m, 60, 1024);
  const double rms_ode = test::RmsAboutMean(ode.dte.row(0).transpose());
  const double mean_ode = ode.dte.row(0).mean();
  // The estimate is an estimate (harmonic_balance.hpp): allow a factor 3, plus the sampled
  // RMS's own error (1024 samples of a kinked DTE).
  const double allowed = 3.0 * hb.summary.error_estimate * rms_ode + 1e-4 * rms_ode;
  EXPECT_NEAR(hb.meshes[0].rms_dte, rms_ode, allowed)
      << "error_estimate " << hb.summary.error_estimate;
  EXPECT_NEAR(hb.meshes[0].mean_dte, mean_ode, 1e-6 * std::abs(mean_ode));
}

// ---------------------------------------------------------------- hunting period ≥ 1e4 meshes

constexpr std::int64_t kCoprime = 988027;  // lcm(997, 991): 997/991 teeth
constexpr std::int64_t kLine = 300 * 997;  // a line at 300/991 mesh orders

TransmissionErrorSidebands RunoutLine(std::complex<double> c) {
  TransmissionErrorSidebands sb;
  sb.period_meshes = kCoprime;
  sb.harmonics = {kLine};
  sb.coefficients = MatrixXc::Zero(2, 1);
  sb.coefficients(0, 0) = c;
  return sb;
}

// The mean-LTI pair with a runout line over the 997/991 hunting period (≈ 1e6 mesh cycles) at
// H = 256: the sparse-harmonic path's sideband must be the SDOF closed form
// DTE_c = δ_c − ε_c, δ_c = k ε_c/(k − m_e ω_c² + i c ω_c), ω_c = ω_m · 300/991.
TEST(LinearHbStress, HuntingPeriod997x991SidebandIsTheClosedForm) {
  SdofPair pair;
  const std::complex<double> eps(2e-6, -1e-6);
  const double k = pair.p.k;
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            ConstantCoefficient(Vector3(k, 0.0, k * pair.p.b * pair.p.b / 3.0)),
                            pair.p.b, Coefficient(test::SmoothTransmissionError(1e-6, 0, 0)),
                            MeshDamping::FromCoefficient(pair.Damping()), false, RunoutLine(eps));
  const SystemModel model = pair.ModelWith(core);
  ASSERT_EQ(model.period_meshes(), kCoprime);
  for (const double f_m : {1500.0, 991.0 / 300.0 * pair.NaturalHz()}) {
    HbOptions options;
    options.harmonics = 256;
    const HbResult hb = SolveHarmonicBalance(model, options, f_m);
    ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
    EXPECT_TRUE(hb.sparse_harmonics);
    EXPECT_TRUE(AllFinite(hb));
    const auto it = std::find(hb.kept_harmonics.begin(), hb.kept_harmonics.end(), kLine);
    ASSERT_NE(it, hb.kept_harmonics.end());
    const double got = hb.meshes[0].dte_amplitudes[it - hb.kept_harmonics.begin()];
    const double w = 2.0 * stress::kPi * f_m * static_cast<double>(kLine) / kCoprime;
    const std::complex<double> delta =
        k * eps / std::complex<double>(k - pair.MeanMass() * w * w, pair.Damping() * w);
    const double truth = 2.0 * std::abs(delta - eps);
    EXPECT_NEAR(got, truth, 1e-9 * truth) << "f_m " << f_m;
    EXPECT_NEAR(hb.meshes[0].mean_dte, pair.StaticDeflection(), 1e-9 * pair.StaticDeflection());
  }
}

// Forcing the dense storage over ≈ 1e6 mesh cycles: a clear refusal naming the cost.
TEST(LinearHbStress, HuntingPeriod997x991DenseStorageIsRefusedWithItsCost) {
  SdofPair pair;
  pair.shape = StiffnessShape::kCosine;
  const LinearMeshCore base = pair.Core();
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh, base.stiffness(), pair.p.b,
                            std::nullopt, MeshDamping::FromCoefficient(pair.Damping()), false,
                            RunoutLine({1e-6, 0.0}));
  HbOptions options;
  options.harmonics = 8;
  options.harmonic_storage = HbHarmonicStorage::kDense;
  EXPECT_THROWS_MESSAGE(SolveHarmonicBalance(pair.ModelWith(core), options, 2000.0), InvalidInput,
                        "GB");
}

// ---------------------------------------------------------------- unit scaling

// The same LTV pair (spur wave, ε, harmonic torque) in SI and in mm–t–s: the DTE over the static
// deflection and the amplitudes in units of it are the same numbers (the mesh frequency, in s⁻¹,
// is unchanged).
TEST(LinearHbStress, MillimetreTonneSecondUnitsGiveTheSameDimensionlessAnswer) {
  SdofPair si;
  si.shape = StiffnessShape::kSpurWave;
  si.e1 = 2e-6;
  si.harmonic_torque = 15.0;
  SdofPair mm = si;
  mm.units = stress::kMmTonneSecond;
  HbOptions options;
  options.harmonics = 64;
  for (const double r : {0.3, 1.0, 2.5}) {
    const double f_m = r * si.NaturalHz();
    const HbResult a = SolveHarmonicBalance(si.Model(), options, f_m);
    const HbResult b = SolveHarmonicBalance(mm.Model(), options, f_m);
    ASSERT_TRUE(a.summary.ok() && b.summary.ok()) << b.summary.BriefReport();
    const double sa = si.StaticDeflection(), sb = si.StaticDeflection() * 1e3;
    const HbMeshOutput &x = a.meshes[0], &y = b.meshes[0];
    EXPECT_NEAR(y.mean_dte / sb, x.mean_dte / sa, 1e-10 * x.mean_dte / sa) << r;
    EXPECT_NEAR(y.rms_dte / sb, x.rms_dte / sa, 1e-9 * x.rms_dte / sa) << r;
    EXPECT_NEAR(y.peak_to_peak_dte / sb, x.peak_to_peak_dte / sa, 1e-9 * x.peak_to_peak_dte / sa);
    EXPECT_NEAR(y.mean_force, x.mean_force, 1e-10 * x.mean_force) << r;  // N in both
    EXPECT_NEAR(b.summary.error_estimate, a.summary.error_estimate,
                1e-6 * a.summary.error_estimate + 1e-15);
  }
}

}  // namespace
}  // namespace geardyn
