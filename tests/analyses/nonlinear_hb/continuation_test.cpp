/// @file
/// @brief Continuation semantics (issue 13): a sweep over [a, b] ends at exactly b (both
/// directions), and folds are located to NhbContinuationOptions::fold_tolerance whatever the
/// step.
///
/// Truth for the folds: the single-harmonic (H = 1) balance of the one-sided clearance
/// oscillator x'' + 2ζx' + [x − 1]₊ = F_m + F_a cos(Ωt) in closed form (the describing
/// function). With x = U₀ + A cos θ in contact where cos θ > c = (1 − U₀)/A, φ = acos c:
///   N₀ = (φ(U₀ − 1) + A sin φ)/π,  N₁ = (2(U₀ − 1) sin φ + A(φ + sin φ cos φ))/π,
/// the mean balance N₀(U₀, A) = F_m (monotone in U₀: GSL Brent root) and the first harmonic
/// (N₁ − Ω²A)² + (2ζΩA)² = F_a², a quadratic in Ω², give Ω(A) on two branches; the folds are
/// the extrema of Ω(A) (GSL Brent minimiser). The engine's exact integration at H = 1 computes
/// the same N₀, N₁, so the two differ only by the fold location and round-off.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

constexpr double kZeta = 0.05, kMean = 0.1, kAlternating = 0.02;

ClearanceOscillatorParameters OneSided() {
  ClearanceOscillatorParameters p;
  p.zeta = kZeta;
  p.alpha = 0.0;
  p.mean_force = kMean;
  p.alternating_force = kAlternating;
  p.back_contact = false;
  return p;
}

/// N₀ and N₁ of [x − 1]₊ for x = U₀ + A cos θ (file comment).
void DescribingFunction(double u0, double a, double* n0, double* n1) {
  const double c = (1.0 - u0) / a;
  if (c <= -1.0) {
    *n0 = u0 - 1.0;
    *n1 = a;
  } else if (c >= 1.0) {
    *n0 = 0.0;
    *n1 = 0.0;
  } else {
    const double phi = std::acos(c), s = std::sin(phi);
    *n0 = (phi * (u0 - 1.0) + a * s) / std::numbers::pi;
    *n1 = (2.0 * (u0 - 1.0) * s + a * (phi + s * c)) / std::numbers::pi;
  }
}

double MeanResidual(double u0, void* params) {
  const double a = *static_cast<double*>(params);
  double n0 = 0, n1 = 0;
  DescribingFunction(u0, a, &n0, &n1);
  return n0 - kMean;
}

/// Ω on branch `sign` (+1: larger root of the quadratic in Ω²) at amplitude A; NaN if none.
double BranchOmega(double a, int sign) {
  gsl_function f{&MeanResidual, &a};
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(solver, &f, 1.0 - a, 1.0 + kMean + a);
  double u0 = 0.0;
  for (int i = 0; i < 200; ++i) {
    gsl_root_fsolver_iterate(solver);
    u0 = gsl_root_fsolver_root(solver);
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver),
                               0.0, 1e-15) == GSL_SUCCESS)
      break;
  }
  gsl_root_fsolver_free(solver);
  double n0 = 0, n1 = 0;
  DescribingFunction(u0, a, &n0, &n1);
  const double qa = a * a, qb = 4.0 * kZeta * kZeta * a * a - 2.0 * n1 * a,
               qc = n1 * n1 - kAlternating * kAlternating;
  const double disc = qb * qb - 4.0 * qa * qc;
  if (disc < 0) return std::nan("");
  const double w = (-qb + sign * std::sqrt(disc)) / (2.0 * qa);
  return w > 0 ? std::sqrt(w) : std::nan("");
}

struct Extremum {
  int sign;
  double scale;  // +1: minimise Ω (a minimum), −1: maximise
};

double Objective(double a, void* params) {
  const Extremum* e = static_cast<Extremum*>(params);
  return e->scale * BranchOmega(a, e->sign);
}

/// Extremum of Ω on branch `sign` for A in [lo, hi] around `guess` (GSL Brent minimiser).
double FoldOmega(int sign, double scale, double lo, double guess, double hi) {
  Extremum e{sign, scale};
  gsl_function f{&Objective, &e};
  gsl_min_fminimizer* m = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
  gsl_min_fminimizer_set(m, &f, guess, lo, hi);
  for (int i = 0; i < 200; ++i) {
    gsl_min_fminimizer_iterate(m);
    if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(m), gsl_min_fminimizer_x_upper(m), 0.0,
                              1e-10) == GSL_SUCCESS)
      break;
  }
  const double omega = scale * gsl_min_fminimizer_f_minimum(m);
  gsl_min_fminimizer_free(m);
  return omega;
}

NhbCurve Trace(double start, double end, double max_step, double fold_tolerance) {
  NhbOptions options;
  options.harmonics = 1;
  options.force_integration = NhbForceIntegration::kExact;
  options.newton_tolerance = 1e-13;
  options.stability = NhbStabilityMethod::kMonodromy;
  NhbContinuationOptions c;
  c.omega_start = start;
  c.omega_end = end;
  c.max_step = max_step;
  c.initial_step = std::min(c.initial_step, max_step);
  c.fold_tolerance = fold_tolerance;
  return TraceNonlinearHarmonicBalance(MakeClearanceOscillator(OneSided()), options, c);
}

TEST(NhbContinuation, FoldsWithinTheRequestedToleranceOfTheClosedForm) {
  // The branch Ω₋(A) has a maximum near A = 0.105 and a minimum near A = 0.263 (scan of the
  // closed form on 3000 amplitudes).
  const double fold_max = FoldOmega(-1, -1.0, 0.03, 0.105, 0.2);
  const double fold_min = FoldOmega(-1, 1.0, 0.15, 0.26, 0.2646);
  ASSERT_GT(fold_max, fold_min);
  for (double tolerance : {1e-6, 1e-10}) {
    for (double max_step : {0.05, 0.004}) {
      const NhbCurve curve = Trace(0.6, 1.2, max_step, tolerance);
      ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
      ASSERT_EQ(curve.folds.size(), 2u) << "max_step " << max_step;
      for (const NhbFold& fold : curve.folds) {
        const double truth = fold.omega_maximum ? fold_max : fold_min;
        EXPECT_TRUE(fold.located);
        EXPECT_LE(fold.omega_error, tolerance * fold.omega);
        // Closed form to ~1e-15 (Brent on a flat extremum: Ω error ∝ (A error)²).
        EXPECT_NEAR(fold.omega, truth, tolerance * truth + 1e-13)
            << "tolerance " << tolerance << ", max_step " << max_step;
      }
    }
  }
}

TEST(NhbContinuation, SweepEndsAtTheRequestedFrequencyInBothDirections) {
  // Truth: the requested end and a single-frequency solve there (a different path: Newton from
  // the contact-branch guess, not the continuation).
  NhbOptions options;
  options.harmonics = 1;
  options.force_integration = NhbForceIntegration::kExact;
  options.newton_tolerance = 1e-13;
  for (auto [start, end] : {std::pair{0.3, 1.5}, std::pair{1.5, 0.3}}) {
    const NhbCurve curve = Trace(start, end, 0.05, 1e-8);
    ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
    EXPECT_EQ(curve.points.front().omega, start);
    EXPECT_EQ(curve.points.back().omega, end);
    // Every point inside the range.
    for (const NhbPoint& p : curve.points) {
      EXPECT_GE(p.omega, std::min(start, end));
      EXPECT_LE(p.omega, std::max(start, end));
    }
    const NhbSolveResult r =
        SolveNonlinearHarmonicBalance(MakeClearanceOscillator(OneSided()), end, options);
    ASSERT_TRUE(r.summary.ok());
    // The end point is off the multi-valued range (0.75..0.91), so the solution is unique.
    EXPECT_NEAR(curve.points.back().rms[0], r.point.rms[0], 1e-10 * r.point.rms[0]);
  }
}

// An undamped resonance: the B&K oscillator x'' + 2ζx' + g(x) = F_m + F_a cos Ωt with the
// dead zone |x| ≤ 1 (contact on both sides) is linear with natural frequency 1 at amplitudes
// A ≫ 1: its backbone tends to Ω = 1 from below (Ω ≈ 1 − O(1/A), the dead zone's share of the
// period; closed form of the linear limit). At ζ = 0 the branch climbs towards it without
// bound: the trace stops with not_converged and names the frequency instead of climbing to
// max_points; at ζ = 10⁻³ the peak is bounded and it traces the whole range.
TEST(NhbContinuation, UndampedResonanceIsDetectedAtTheNaturalFrequency) {
  for (double zeta : {0.0, 1e-3}) {
    ClearanceOscillatorParameters p;
    p.zeta = zeta;
    p.mean_force = 0.1;
    p.alternating_force = 0.1;
    NhbOptions options;
    options.harmonics = 2;
    options.stability = NhbStabilityMethod::kNone;
    NhbContinuationOptions c;
    c.omega_start = 0.5;
    c.omega_end = 1.5;
    const NhbCurve curve = TraceNonlinearHarmonicBalance(MakeClearanceOscillator(p), options, c);
    if (zeta == 0.0) {
      EXPECT_EQ(curve.summary.status, Status::kNotConverged);
      EXPECT_NE(curve.summary.message.find("undamped resonance"), std::string::npos)
          << curve.summary.message;
      EXPECT_NEAR(curve.undamped_resonance_omega, 1.0, 5e-3);
      EXPECT_LT(curve.points.size(), 20000u);
    } else {
      ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
      EXPECT_EQ(curve.points.back().omega, 1.5);
      EXPECT_EQ(curve.undamped_resonance_omega, 0.0);
    }
  }
}

TEST(NhbContinuation, BranchSearchCountIsBounded) {
  NhbContinuationOptions c;
  std::string why;
  c.branch_search = 1000;
  EXPECT_TRUE(c.IsValid(&why)) << why;
  c.branch_search = 1001;
  EXPECT_FALSE(c.IsValid(&why));
  EXPECT_NE(why.find("branch_search"), std::string::npos) << why;
  c.branch_search = -1;
  EXPECT_FALSE(c.IsValid(&why));
}

TEST(NhbContinuation, FoldToleranceIsValidated) {
  NhbContinuationOptions c;
  std::string why;
  c.fold_tolerance = 0.0;
  EXPECT_FALSE(c.IsValid(&why));
  EXPECT_NE(why.find("fold_tolerance"), std::string::npos);
  c.fold_tolerance = 1e-8;
  EXPECT_TRUE(c.IsValid(&why));
}

}  // namespace
}  // namespace geardyn
