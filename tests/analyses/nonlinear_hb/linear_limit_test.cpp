/// @file
/// @brief Nonlinear HB in the linear limit: the B&K oscillator with α = 0 and a mean force so
/// large that contact is never lost is x'' + 2ζx' + x − 1 = F_m + F_a cos(Ωt + φ), whose
/// closed-form response is U_0 = 1 + F_m, U_1 = (F_a/2) e^{iφ} / (1 − Ω² + 2iζΩ), U_k = 0 (k ≥ 2).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

ClearanceOscillatorParameters LinearParameters() {
  ClearanceOscillatorParameters p;
  p.zeta = 0.05;
  p.alpha = 0.0;
  p.mean_force = 10.0;
  p.alternating_force = 0.5;  // peak amplitude F_a/(2ζ) = 5 < 1 + F_m − 1: never loses contact
  p.force_phase = 0.3;
  return p;
}

std::complex<double> ClosedFormU1(const ClearanceOscillatorParameters& p, double w) {
  return 0.5 * std::polar(p.alternating_force, p.force_phase) /
         std::complex<double>(1.0 - w * w, 2.0 * p.zeta * w);
}

TEST(NonlinearHbLinearLimit, SingleFrequencyEqualsClosedForm) {
  const ClearanceOscillatorParameters p = LinearParameters();
  NhbOptions options;
  options.harmonics = 8;
  for (double w : {0.3, 0.9, 1.0, 1.1, 2.5}) {
    const NhbSolveResult r = SolveNonlinearHarmonicBalance(MakeClearanceOscillator(p), w, options);
    ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
    EXPECT_NEAR(r.point.harmonics(0, 0).real(), 1.0 + p.mean_force, 1e-10);
    EXPECT_NEAR(std::abs(r.point.harmonics(0, 1) - ClosedFormU1(p, w)), 0.0, 1e-10) << w;
    for (int k = 2; k <= 8; ++k) EXPECT_NEAR(std::abs(r.point.harmonics(0, k)), 0.0, 1e-10);
    EXPECT_EQ(r.point.stable, FloquetVerdict::kStable);  // a damped LTI oscillator
    EXPECT_LT(r.point.max_multiplier, 1.0);
  }
}

TEST(NonlinearHbLinearLimit, ContinuationTracesTheLinearCurveWithoutFolds) {
  const ClearanceOscillatorParameters p = LinearParameters();
  NhbOptions options;
  options.harmonics = 4;
  options.newton_tolerance = 1e-13;  // the corrector's residual bound sets the accuracy
  NhbContinuationOptions c;
  c.omega_start = 0.5;
  c.omega_end = 1.5;
  const NhbCurve curve = TraceNonlinearHarmonicBalance(MakeClearanceOscillator(p), options, c);
  ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
  EXPECT_TRUE(curve.folds.empty());
  EXPECT_GT(curve.points.size(), 10u);
  EXPECT_EQ(curve.points.back().omega, 1.5);  // the requested end, exactly
  for (const NhbPoint& pt : curve.points) {
    const double rms = std::sqrt(2.0) * std::abs(ClosedFormU1(p, pt.omega));
    EXPECT_NEAR(pt.rms[0], rms, 1e-10 * (1.0 + rms)) << pt.omega;
    // Peak-to-peak of a sinusoid sampled at S = 64 points: each extreme is missed by at most
    // A(1 − cos(π/S)).
    const double ptp = 4.0 * std::abs(ClosedFormU1(p, pt.omega));
    EXPECT_NEAR(pt.peak_to_peak[0], ptp, ptp * (1.0 - std::cos(M_PI / 64)) + 1e-12);
    EXPECT_EQ(pt.stable, FloquetVerdict::kStable);
  }
}

}  // namespace
}  // namespace geardyn
