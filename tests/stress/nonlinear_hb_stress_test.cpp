// Stress suite part B, nonlinear harmonic balance (issue 16) on the Blankenship & Kahraman
// clearance oscillator x'' + 2ζx' + (1 + α cos Ωt) g(x) = F_m + F_a cos Ωt: a point exactly on
// a fold, grazing contact, zero damping, very large clearances. Truths: the linear closed form
// (y = x − 1 in contact: F_m + F_a cos(Ωt − φ)/|1 − Ω² + 2iζΩ|), an independent GSL rk8pd time
// integration (bk_time_integration.hpp: the jump on either side of a fold, the periodicity of
// an HB orbit), or the status that must be reported. No NaN/Inf may reach a point.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <string>

#include "analyses/nonlinear_hb/bk_parameter_sets.hpp"
#include "analyses/nonlinear_hb/bk_time_integration.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

using testing::BkParameters;
using testing::BkState;
using testing::BkStats;

constexpr double kInf = std::numeric_limits<double>::infinity();

::testing::AssertionResult AllFinite(const NhbPoint& p) {
  if (!std::isfinite(p.omega) || !p.harmonics.allFinite() || !p.mean.allFinite() ||
      !p.rms.allFinite() || !p.peak_to_peak.allFinite() || !p.maximum.allFinite() ||
      !p.minimum.allFinite() || !std::isfinite(p.error_estimate) ||
      !std::isfinite(p.residual_norm)) {
    return ::testing::AssertionFailure() << "non-finite value in the point at Ω = " << p.omega;
  }
  return ::testing::AssertionSuccess();
}

BkParameters Bk(const ClearanceOscillatorParameters& p) {
  return {p.zeta, p.alpha, p.mean_force, p.alternating_force, p.force_phase, p.back_contact};
}

/// The oscillator with its law replaced: front gap b, back gap a (the B&K scaling has b = 1).
NhbProblem WithGaps(const ClearanceOscillatorParameters& p, double front, double back) {
  NhbProblem problem = MakeClearanceOscillator(p);
  problem.law = std::make_shared<NhbClearanceLaw>(
      VectorX::Constant(1, 1.0), VectorX::Constant(1, p.alpha), VectorX::Zero(1),
      VectorX::Constant(1, front), VectorX::Constant(1, back));
  return problem;
}

/// x(0), x'(0) of the HB orbit (x = U_0 + 2 Re Σ U_k e^{ikΩt}, p = 1).
BkState StartOf(const NhbPoint& p) {
  BkState s;
  for (int k = 0; k < p.harmonics.cols(); ++k) {
    const std::complex<double> u = p.harmonics(0, k);
    s.x += (k == 0 ? 1.0 : 2.0) * u.real();
    s.v += -2.0 * k * p.omega * u.imag();
  }
  return s;
}

/// Linear closed form in full contact (α = 0): amplitude of y = x − b.
double LinearAmplitude(const ClearanceOscillatorParameters& p, double omega) {
  return p.alternating_force /
         std::abs(std::complex<double>(1.0 - omega * omega, 2.0 * p.zeta * omega));
}

// ---------------------------------------------------------------- grazing contact

// F_a chosen so that the linear contact response just reaches x = 1 (y = 0) once per period:
// F_a = F_m |1 − Ω² + 2iζΩ|. The nonlinear answer must equal the linear one there (the gap is
// touched on a set of measure zero) — by exact integration and by sampled AFT.
TEST(NonlinearHbStress, GrazingContactEqualsTheLinearAnswer) {
  for (const NhbForceIntegration integration :
       {NhbForceIntegration::kExact, NhbForceIntegration::kSampled}) {
    for (const double omega : {0.4, 0.8, 1.3}) {
      ClearanceOscillatorParameters p;
      p.zeta = 0.05;
      p.alpha = 0.0;
      p.mean_force = 0.1;
      p.alternating_force =
          p.mean_force * std::abs(std::complex<double>(1.0 - omega * omega, 2.0 * p.zeta * omega));
      NhbOptions options;
      options.harmonics = 16;
      options.force_integration = integration;
      const NhbSolveResult r =
          SolveNonlinearHarmonicBalance(MakeClearanceOscillator(p), omega, options);
      const std::string what = "Ω = " + std::to_string(omega) +
                               (integration == NhbForceIntegration::kExact ? " exact" : " AFT");
      ASSERT_TRUE(r.summary.ok()) << what << ": " << r.summary.BriefReport();
      EXPECT_TRUE(AllFinite(r.point)) << what;
      const double A = LinearAmplitude(p, omega);  // = F_m
      EXPECT_NEAR(r.point.mean[0], 1.0 + p.mean_force, 1e-9) << what;
      EXPECT_NEAR(r.point.rms[0], A / std::sqrt(2.0), 1e-9) << what;
      EXPECT_NEAR(r.point.minimum[0], 1.0, 1e-8) << what;
      EXPECT_NEAR(r.point.maximum[0], 1.0 + 2.0 * p.mean_force, 1e-8) << what;
    }
  }
}

// Just past grazing (F_a = (1 + 1e-4) × the grazing value): the contact is lost for a sliver of
// the period, and the answer is continuous — within O(1e-4) of the linear one, never a jump to
// garbage (Newton near grazing, where the residual is only C¹).
TEST(NonlinearHbStress, JustPastGrazingIsContinuous) {
  const double omega = 0.8;
  ClearanceOscillatorParameters p;
  p.zeta = 0.05;
  p.alpha = 0.0;
  p.mean_force = 0.1;
  const double graze =
      p.mean_force * std::abs(std::complex<double>(1.0 - omega * omega, 2.0 * p.zeta * omega));
  for (const double excess : {1e-10, 1e-6, 1e-4}) {
    p.alternating_force = graze * (1.0 + excess);
    NhbOptions options;
    options.harmonics = 16;
    const NhbSolveResult r =
        SolveNonlinearHarmonicBalance(MakeClearanceOscillator(p), omega, options);
    ASSERT_TRUE(r.summary.ok()) << excess << ": " << r.summary.BriefReport();
    EXPECT_TRUE(AllFinite(r.point));
    const double linear_rms = LinearAmplitude(p, omega) / std::sqrt(2.0);
    EXPECT_NEAR(r.point.rms[0], linear_rms, 10.0 * excess * linear_rms + 1e-9) << excess;
    EXPECT_LE(r.point.minimum[0], 1.0 + 1e-9) << excess;
  }
}

// ---------------------------------------------------------------- folds

/// The stable-side point of a fold's branch (the traced point next to the fold on the stable
/// branch ending there).
const NhbPoint* StableNeighbour(const NhbCurve& curve, const NhbFold& fold) {
  for (const int i : {fold.index, fold.index + 1}) {
    if (i < 0 || i >= static_cast<int>(curve.points.size())) continue;
    if (curve.points[i].stable == FloquetVerdict::kStable) return &curve.points[i];
  }
  return nullptr;
}

// The single-sided B&K set traced through both folds of its softening resonance: each fold is
// passed and located, and an independent time integration confirms the turning point — started
// on the HB branch 1 % inside the fold it stays there (RMS within 2 %); 1 % outside it leaves
// (RMS changes by more than 20 %).
TEST(NonlinearHbStress, FoldsArePassedAndConfirmedByTimeIntegration) {
  const ClearanceOscillatorParameters params = testing::BkSingleSidedSet();
  const NhbProblem problem = MakeClearanceOscillator(params);
  NhbOptions options;
  options.harmonics = 24;
  NhbContinuationOptions c;
  c.omega_start = 0.6;
  c.omega_end = 1.2;
  const NhbCurve curve = TraceNonlinearHarmonicBalance(problem, options, c);
  ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
  for (const NhbPoint& p : curve.points) ASSERT_TRUE(AllFinite(p));
  ASSERT_EQ(curve.folds.size(), 2u);
  NhbSolver solver(problem, options, 24);
  for (const NhbFold& fold : curve.folds) {
    EXPECT_TRUE(fold.located);
    const NhbPoint* near = StableNeighbour(curve, fold);
    ASSERT_NE(near, nullptr) << "fold at " << fold.omega;
    // The branch ending at a fold with an Ω maximum exists below it, the other above it.
    const double inside = fold.omega * (fold.omega_maximum ? 0.99 : 1.01);
    const double outside = fold.omega * (fold.omega_maximum ? 1.01 : 0.99);
    VectorX x = testing::PointUnknowns(*near);
    Status status;
    double residual;
    solver.Newton(x, inside, &status, &residual);
    ASSERT_EQ(status, Status::kSuccess) << "fold at " << fold.omega;
    NhbPoint on_branch;
    solver.Describe(x, inside, on_branch);
    const BkState start = StartOf(on_branch);
    BkState s = start;
    BkStats stay;
    testing::BkIntegrate(Bk(params), inside, 400, 20, s, &stay);
    EXPECT_NEAR(stay.rms, on_branch.rms[0], 0.02 * on_branch.rms[0]) << "fold at " << fold.omega;
    s = start;
    BkStats leave;
    testing::BkIntegrate(Bk(params), outside, 600, 20, s, &leave);
    EXPECT_GT(std::abs(leave.rms - on_branch.rms[0]), 0.2 * on_branch.rms[0])
        << "fold at " << fold.omega << ": the time integration stays past the HB fold";
  }
}

// A single solve exactly at the fold frequency (the Jacobian of the fold point is singular):
// from the contact guess and from the fold's neighbour, each answer is either reported as not
// converged or is a true periodic orbit — one period of time integration from it returns to it.
TEST(NonlinearHbStress, SolveExactlyOnAFoldIsAnOrbitOrAStatus) {
  const ClearanceOscillatorParameters params = testing::BkSingleSidedSet();
  const NhbProblem problem = MakeClearanceOscillator(params);
  NhbOptions options;
  options.harmonics = 32;
  NhbContinuationOptions c;
  c.omega_start = 0.6;
  c.omega_end = 1.2;
  const NhbCurve curve = TraceNonlinearHarmonicBalance(problem, options, c);
  ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
  ASSERT_EQ(curve.folds.size(), 2u);
  NhbSolver solver(problem, options, 32);
  auto check_orbit = [&](const NhbPoint& p, const std::string& what) {
    ASSERT_TRUE(AllFinite(p)) << what;
    const BkState start = StartOf(p);
    BkState s = start;
    testing::BkIntegrate(Bk(params), p.omega, 1, 1, s, nullptr);
    const double scale = std::max(p.peak_to_peak[0], 1e-3);
    EXPECT_NEAR(s.x, start.x, 1e-4 * scale) << what;
    EXPECT_NEAR(s.v, start.v, 1e-4 * scale * p.omega) << what;
  };
  for (const NhbFold& fold : curve.folds) {
    const std::string where = "fold at Ω = " + std::to_string(fold.omega);
    const NhbSolveResult guess = SolveNonlinearHarmonicBalance(problem, fold.omega, options);
    if (guess.summary.ok()) {
      check_orbit(guess.point, where + " (contact guess)");
    } else {
      EXPECT_FALSE(guess.summary.message.empty()) << where;
      EXPECT_TRUE(AllFinite(guess.point)) << where;
    }
    VectorX x = testing::PointUnknowns(curve.points[fold.index], 32);
    Status status;
    double residual;
    solver.Newton(x, fold.omega, &status, &residual);
    EXPECT_TRUE(x.allFinite()) << where;
    if (status == Status::kSuccess) {
      NhbPoint p;
      solver.Describe(x, fold.omega, p);
      check_orbit(p, where + " (neighbour guess)");
    }
  }
}

// ---------------------------------------------------------------- zero damping

/// Zero backlash and both flanks (front gap 0, back gap 0): g(x) = x, the undamped linear
/// oscillator x'' + x = F_m + F_a cos Ωt (ζ = 0).
NhbProblem UndampedLinear() {
  ClearanceOscillatorParameters p;
  p.zeta = 0.0;
  p.alpha = 0.0;
  p.mean_force = 0.1;
  p.alternating_force = 0.05;
  return WithGaps(p, 0.0, 0.0);
}

struct UndampedCase {
  std::string name;
  double omega;
  /// Driven at the natural frequency 1: the orbit is unbounded, a status is required. (At
  /// Ω = 1/3, harmonic 3 sits on ω_n but is not loaded: the particular solution is exact, the
  /// free vibration adds a non-unique part; the engine returns the particular one — checked as
  /// a closed form — and warns that the solution is not unique. The linear HB reports
  /// kNumericalIssue in the same situation.)
  bool singular;
  /// A harmonic kΩ on ω_n without load: the summary must warn of the non-unique solution.
  bool non_unique = false;
};

void PrintTo(const UndampedCase& c, std::ostream* os) { *os << c.name; }

class NonlinearHbUndampedStress : public ::testing::TestWithParam<UndampedCase> {};

TEST_P(NonlinearHbUndampedStress, ClosedFormOrStatus) {
  const UndampedCase& c = GetParam();
  NhbOptions options;
  options.harmonics = 8;
  const NhbSolveResult r = SolveNonlinearHarmonicBalance(UndampedLinear(), c.omega, options);
  EXPECT_TRUE(AllFinite(r.point)) << c.name << ": " << r.summary.BriefReport();
  if (c.singular) {
    EXPECT_NE(r.summary.status, Status::kSuccess) << c.name << ": " << r.summary.BriefReport();
    EXPECT_FALSE(r.summary.message.empty());
    return;
  }
  ASSERT_TRUE(r.summary.ok()) << c.name << ": " << r.summary.BriefReport();
  bool warned = false;
  for (const std::string& w : r.summary.warnings)
    warned |= w.find("not unique") != std::string::npos;
  EXPECT_EQ(warned, c.non_unique) << c.name << ": " << ::testing::PrintToString(r.summary.warnings);
  const double A = 0.05 / std::abs(1.0 - c.omega * c.omega);
  EXPECT_NEAR(r.point.mean[0], 0.1, 1e-10) << c.name;
  EXPECT_NEAR(r.point.rms[0], A / std::sqrt(2.0), 1e-9 * A) << c.name;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, NonlinearHbUndampedStress,
    ::testing::Values(UndampedCase{"exactly_at_resonance", 1.0, true},
                      UndampedCase{"third_harmonic_at_resonance", 1.0 / 3.0, false, true},
                      UndampedCase{"below_resonance", 0.7, false},
                      UndampedCase{"above_resonance", 1.9, false},
                      UndampedCase{"just_1e6th_below_resonance", 1.0 - 1e-6, false}),
    [](const ::testing::TestParamInfo<UndampedCase>& param_info) { return param_info.param.name; });

// Continuation of the undamped linear oscillator across Ω = 1: the branch goes vertical; the trace
// must stop there and say so (kNotConverged, undamped_resonance_omega ≈ 1), not step over it.
TEST(NonlinearHbStress, UndampedTraceStopsAtTheResonanceWithAStatus) {
  NhbOptions options;
  options.harmonics = 4;
  options.stability = NhbStabilityMethod::kNone;
  NhbContinuationOptions c;
  c.omega_start = 0.6;
  c.omega_end = 1.4;
  const NhbCurve curve = TraceNonlinearHarmonicBalance(UndampedLinear(), options, c);
  EXPECT_EQ(curve.summary.status, Status::kNotConverged) << curve.summary.BriefReport();
  EXPECT_NEAR(curve.undamped_resonance_omega, 1.0, 2e-3);
  for (const NhbPoint& p : curve.points) {
    ASSERT_TRUE(AllFinite(p));
    // Every point is on the closed form (the trace never passes Ω = 1).
    EXPECT_LT(p.omega, 1.0);
    const double A = 0.05 / std::abs(1.0 - p.omega * p.omega);
    EXPECT_NEAR(p.rms[0], A / std::sqrt(2.0), 1e-7 * A) << p.omega;
  }
}

// Zero damping with contact loss (the single-sided B&K set, ζ = 0) at a frequency inside the
// softened resonance: the answer is a periodic orbit (checked by one period of time
// integration) or a status — never garbage reported as success.
TEST(NonlinearHbStress, UndampedClearanceOscillatorIsAnOrbitOrAStatus) {
  ClearanceOscillatorParameters params = testing::BkSingleSidedSet();
  params.zeta = 0.0;
  for (const double omega : {0.7, 0.85, 1.1}) {
    NhbOptions options;
    options.harmonics = 32;
    const NhbSolveResult r =
        SolveNonlinearHarmonicBalance(MakeClearanceOscillator(params), omega, options);
    EXPECT_TRUE(AllFinite(r.point)) << omega;
    if (!r.summary.ok()) {
      EXPECT_FALSE(r.summary.message.empty()) << omega;
      continue;
    }
    const BkState start = StartOf(r.point);
    BkState s = start;
    testing::BkIntegrate(Bk(params), omega, 1, 1, s, nullptr);
    const double scale = std::max(r.point.peak_to_peak[0], 1e-3);
    EXPECT_NEAR(s.x, start.x, 1e-4 * scale) << omega;
    EXPECT_NEAR(s.v, start.v, 1e-4 * scale * omega) << omega;
  }
}

// ---------------------------------------------------------------- very large clearances

// K = 0 outside the law: a front gap b only shifts the solution by b − 1 (translation
// invariance). Ω = 0.5 stays in contact (|y| amplitude 0.04 < F_m = 0.1): the shifted linear
// closed form; Ω = 0.9 loses contact (amplitude 0.14 > F_m): the gap-1 solution shifted. The
// offset must not eat the amplitude's digits.
void CheckShifted(double gap, double omega) {
  ClearanceOscillatorParameters p;
  p.zeta = 0.05;
  p.alpha = 0.0;
  p.mean_force = 0.1;
  p.alternating_force = 0.03;
  NhbOptions options;
  options.harmonics = 16;
  const NhbSolveResult r = SolveNonlinearHarmonicBalance(WithGaps(p, gap, kInf), omega, options);
  const NhbSolveResult unit = SolveNonlinearHarmonicBalance(WithGaps(p, 1.0, kInf), omega, options);
  ASSERT_TRUE(unit.summary.ok()) << unit.summary.BriefReport();
  ASSERT_TRUE(r.summary.ok()) << "gap " << gap << ", Ω = " << omega << ": "
                              << r.summary.BriefReport();
  EXPECT_TRUE(AllFinite(r.point));
  EXPECT_NEAR(r.point.mean[0] - gap, unit.point.mean[0] - 1.0, 1e-12 * gap);
  EXPECT_NEAR(r.point.rms[0], unit.point.rms[0], 1e-6 * unit.point.rms[0]);
  const double A = LinearAmplitude(p, omega);
  if (A < p.mean_force) {
    EXPECT_NEAR(r.point.rms[0], A / std::sqrt(2.0), 1e-6 * A);
  }
}

TEST(NonlinearHbStress, LargeFrontGapInContactIsTheShiftedLinearAnswer) { CheckShifted(1e3, 0.5); }
TEST(NonlinearHbStress, HugeFrontGapInContactIsTheShiftedLinearAnswer) { CheckShifted(1e6, 0.5); }
// Issue 16 (docs/stress/part-b.md): these ended kNotConverged after 830 iterations — and so did
// the gap-1 reference itself at H = 16: Ω = 0.9 is past the contact branch's fold and Newton
// from the contact guess stalls next to grazing whatever the gap. Fixed in
// nonlinear_hb/solve.cpp (restarts from scaled contact guesses).
TEST(NonlinearHbStress, LargeFrontGapWithContactLossIsTheShiftedAnswer) { CheckShifted(1e3, 0.9); }
TEST(NonlinearHbStress, HugeFrontGapWithContactLossIsTheShiftedAnswer) { CheckShifted(1e6, 0.9); }

// A back gap of 1e12 is never reached: the same answer as no back flank at all, on the
// back-contact B&K set traced through its resonance (where the finite back gap 1 is reached).
TEST(NonlinearHbStress, HugeBackGapEqualsNoBackFlank) {
  const ClearanceOscillatorParameters p = testing::BkBackContactSet();
  NhbOptions options;
  options.harmonics = 16;
  for (const double omega : {0.45, 0.7, 1.2}) {
    const NhbSolveResult huge =
        SolveNonlinearHarmonicBalance(WithGaps(p, 1.0, 1e12), omega, options);
    const NhbSolveResult none =
        SolveNonlinearHarmonicBalance(WithGaps(p, 1.0, kInf), omega, options);
    ASSERT_EQ(huge.summary.status, none.summary.status) << omega;
    EXPECT_TRUE(AllFinite(huge.point));
    if (!none.summary.ok()) continue;
    EXPECT_NEAR(huge.point.rms[0], none.point.rms[0], 1e-9 * none.point.rms[0]) << omega;
    EXPECT_NEAR(huge.point.mean[0], none.point.mean[0], 1e-9 * std::abs(none.point.mean[0]));
  }
}

}  // namespace
}  // namespace geardyn
