/// @file
/// @brief Work-precision of the nonlinear harmonic balance on the B&K (1995) oscillator
/// (ζ = 0.05, α = 0.1, F_m = 0.1, F_a = 0.03, single-sided impacts, Ω ∈ [0.65, 1.05]).
/// Reference: the curve traced with H = 256 by exact integration (max_step 0.0016, ≈ 1 100
/// points, both folds; H = 128 differs from it by 3e-8). Error of H: max over every 4th reference
/// point (all branches) off the folds (|dΩ/ds| ≥ kFoldZone) of |RMS_H − RMS_ref| / RMS_ref,
/// RMS_H from Newton at that Ω started from the truncated reference harmonics; the folds are
/// compared by frequency. Rows (wp_common.hpp CSV):
///   point,H,time per Newton solve (exact integration),error,Newton iterations
///   curve,H,best-of-5 time of a ≥ 1000-point continuation (max_step 0.0016, no stability),
///       error,points
///   folds,H,0,max relative error of the fold frequencies of that curve,folds
///   curve+stability,H,the same with monodromy stability of every point,error,points
///   curve_sampled,H,the same curve with the sampled AFT (S = 16H), its error,points
///   tolerance,tol,time of TraceNonlinearHarmonicBalance with automatic H,error,H chosen
/// Run: ./tests/benchmarks/wp_harmonic_balance_nonlinear (Release build).
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "../../analyses/nonlinear_hb/bk_parameter_sets.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"
#include "wp_common.hpp"

using namespace geardyn;

namespace {

ClearanceOscillatorParameters Params() { return testing::BkSingleSidedSet(); }

NhbContinuationOptions Range(double max_step) {
  NhbContinuationOptions c;
  c.omega_start = 0.65;
  c.omega_end = 1.05;
  c.initial_step = std::min(0.01, max_step);
  c.max_step = max_step;
  c.max_tangent_angle = 0.5;
  return c;
}

/// Best of five single runs [s] (the machine is shared: the minimum is the least disturbed).
double BestOfFive(const std::function<void()>& fn) {
  double best = 1e300;
  for (int r = 0; r < 5; ++r) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

/// Newton tolerance of the reference and of the error solves (not of the timed runs).
constexpr double kErrorNewtonTolerance = 1e-13;

/// Reference points with |dΩ/ds| below this (scaled tangent) are near a fold.
constexpr double kFoldZone = 0.05;

/// Max relative RMS error of H at the reference points; also the mean Newton iterations.
double ErrorOf(int H, const std::vector<NhbPoint>& ref, double* iterations,
               NhbForceIntegration integration = NhbForceIntegration::kExact) {
  NhbOptions o;
  o.harmonics = H;
  o.force_integration = integration;
  o.stability = NhbStabilityMethod::kNone;
  o.newton_tolerance = kErrorNewtonTolerance;
  NhbSolver solver(MakeClearanceOscillator(Params()), o, H);
  double err = 0.0;
  long its = 0;
  long count = 0;
  for (const NhbPoint& r : ref) {
    // At a fold dΩ/ds = 0 and the comparison at a fixed Ω is ill-conditioned (an O(ε) shift
    // of the fold moves the RMS there by O(√ε)); the folds are compared by position instead.
    if (std::abs(r.tangent_omega) < kFoldZone) continue;
    ++count;
    VectorX x = testing::PointUnknowns(r, H);
    Status st;
    double rn;
    its += solver.Newton(x, r.omega, &st, &rn);
    NhbPoint pt;
    solver.Describe(x, r.omega, pt);
    err = std::max(err, st == Status::kSuccess ? std::abs(pt.rms[0] - r.rms[0]) / r.rms[0] : 1.0);
  }
  if (iterations) *iterations = double(its) / static_cast<double>(count);
  return err;
}

/// Largest relative difference of the fold frequencies (1 when the fold count differs).
double FoldError(const NhbCurve& curve, const NhbCurve& reference) {
  if (curve.folds.size() != reference.folds.size()) return 1.0;
  double err = 0.0;
  for (size_t i = 0; i < curve.folds.size(); ++i) {
    err = std::max(
        err, std::abs(curve.folds[i].omega - reference.folds[i].omega) / reference.folds[i].omega);
  }
  return err;
}

}  // namespace

int main() {
  const NhbProblem problem = MakeClearanceOscillator(Params());
  Eigen::setNbThreads(1);  // m ≤ 513: Eigen's OpenMP GEMM only adds contention here
  NhbOptions ref_options;
  ref_options.harmonics = 256;
  // Near the resonance ‖J⁻¹‖ is large: the default Newton tolerance 1e-10 leaves ~1e-7 in the
  // RMS, so the reference (and the error solves) converge to 1e-13.
  ref_options.newton_tolerance = kErrorNewtonTolerance;
  ref_options.stability = NhbStabilityMethod::kNone;
  // The same steps as the timed curves, so that the fold interpolation error (≈ 6e-6 with
  // max_step 0.01) cancels in the fold comparison.
  const NhbCurve ref_curve = TraceNonlinearHarmonicBalance(problem, ref_options, Range(0.0016));
  std::vector<NhbPoint> ref;
  for (size_t i = 0; i < ref_curve.points.size(); i += 4) ref.push_back(ref_curve.points[i]);
  std::printf("# reference: H = 256, %zu points (every 4th compared), %zu folds at",
              ref_curve.points.size(), ref_curve.folds.size());
  for (const NhbFold& f : ref_curve.folds) std::printf(" %.9f", f.omega);
  std::printf(", status %s\n", StatusName(ref_curve.summary.status));
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  for (int H : {4, 8, 12, 16, 20, 24, 28, 32, 48, 64}) {
    double its = 0;
    const double err = ErrorOf(H, ref, &its);
    NhbOptions o;
    o.harmonics = H;
    o.stability = NhbStabilityMethod::kNone;
    NhbSolver solver(problem, o, H);
    const double t_point = wp::TimeIt([&] {
                             for (const NhbPoint& r : ref) {
                               VectorX x = testing::PointUnknowns(r, H);
                               Status st;
                               double rn;
                               solver.Newton(x, r.omega, &st, &rn);
                             }
                           }) /
                           static_cast<double>(ref.size());
    wp::Row("point", H, t_point, err, its);
    // ≥ 1000-point continuation over the whole curve.
    const NhbContinuationOptions c = Range(0.0016);
    size_t points = 0;
    const double t_curve =
        BestOfFive([&] { points = TraceNonlinearHarmonicBalance(problem, o, c).points.size(); });
    wp::Row("curve", H, t_curve, err, double(points));
    const NhbCurve curve = TraceNonlinearHarmonicBalance(problem, o, c);
    wp::Row("folds", H, 0.0, FoldError(curve, ref_curve), double(curve.folds.size()));
    o.stability = NhbStabilityMethod::kMonodromy;
    const double t_stab =
        BestOfFive([&] { points = TraceNonlinearHarmonicBalance(problem, o, c).points.size(); });
    wp::Row("curve+stability", H, t_stab, err, double(points));
    // The same curve with the sampled AFT (S = 16H), for comparison.
    if (H <= 32) {
      const double err_sampled = ErrorOf(H, ref, nullptr, NhbForceIntegration::kSampled);
      o.force_integration = NhbForceIntegration::kSampled;
      o.stability = NhbStabilityMethod::kNone;
      const double t_sampled =
          BestOfFive([&] { points = TraceNonlinearHarmonicBalance(problem, o, c).points.size(); });
      wp::Row("curve_sampled", H, t_sampled, err_sampled, double(points));
    }
  }
  for (double tol : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    NhbOptions o;
    o.harmonics = 0;
    o.harmonic_tolerance = tol;
    o.stability = NhbStabilityMethod::kNone;
    int H = 0;
    const double t = wp::TimeIt(
        [&] { H = TraceNonlinearHarmonicBalance(problem, o, Range(0.05)).harmonics_used; });
    wp::Row("tolerance", tol, t, ErrorOf(H, ref, nullptr), H);
  }
  return 0;
}
