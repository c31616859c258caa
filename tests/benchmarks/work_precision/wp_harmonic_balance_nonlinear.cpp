/// @file
/// @brief Work-precision of the nonlinear harmonic balance on the B&K (1995) oscillator
/// (ζ = 0.05, α = 0.1, F_m = 0.1, F_a = 0.03, single-sided impacts, Ω ∈ [0.65, 1.05]).
/// Reference: the curve traced with H = 128, S = 2048 and the AFT switch correction (max_step
/// 0.01, ≈ 350 points). Error of H: max over every 2nd reference point
/// (all branches) of |RMS_H − RMS_ref| / RMS_ref, RMS_H from Newton at that Ω started from the
/// truncated reference harmonics. Rows (wp_common.hpp CSV):
///   point,H,time per Newton solve,error,Newton iterations
///   curve,H,time of a ≥ 1000-point continuation (no stability),error,points
///   curve+stability,H,same with monodromy stability of every point,error,points
///   curve_switch_correction[+stability],H,the same two with NhbOptions::switch_correction
///   tolerance,tol,time of TraceNonlinearHarmonicBalance with automatic H,error,H chosen
/// Run: ./tests/benchmarks/wp_harmonic_balance_nonlinear (Release build).
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
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

VectorX ToUnknowns(const NhbPoint& pt, int H) {
  VectorX x = VectorX::Zero(2 * H + 1);
  const int Hr = static_cast<int>(pt.harmonics.cols()) - 1;
  x[0] = pt.harmonics(0, 0).real();
  for (int k = 1; k <= std::min(H, Hr); ++k) {
    x[2 * k - 1] = pt.harmonics(0, k).real();
    x[2 * k] = pt.harmonics(0, k).imag();
  }
  return x;
}

/// Max relative RMS error of H at the reference points; also the mean Newton iterations.
double ErrorOf(int H, const std::vector<NhbPoint>& ref, double* iterations,
               bool correction = false) {
  NhbOptions o;
  o.harmonics = H;
  o.switch_correction = correction;
  o.stability = NhbStabilityMethod::kNone;
  NhbSolver solver(MakeClearanceOscillator(Params()), o, H);
  double err = 0.0;
  long its = 0;
  for (const NhbPoint& r : ref) {
    VectorX x = ToUnknowns(r, H);
    Status st;
    double rn;
    its += solver.Newton(x, r.omega, &st, &rn);
    NhbPoint pt;
    solver.Describe(x, r.omega, pt);
    err = std::max(err, st == Status::kSuccess ? std::abs(pt.rms[0] - r.rms[0]) / r.rms[0] : 1.0);
  }
  if (iterations) *iterations = double(its) / static_cast<double>(ref.size());
  return err;
}

}  // namespace

int main() {
  const NhbProblem problem = MakeClearanceOscillator(Params());
  Eigen::setNbThreads(1);  // m ≤ 257: Eigen's OpenMP GEMM only adds contention here
  NhbOptions ref_options;
  ref_options.harmonics = 128;
  ref_options.switch_correction = true;  // S = 2048 with the kink correction: error < 1e-7
  ref_options.stability = NhbStabilityMethod::kNone;
  const NhbCurve ref_curve = TraceNonlinearHarmonicBalance(problem, ref_options, Range(0.01));
  std::vector<NhbPoint> ref;
  for (size_t i = 0; i < ref_curve.points.size(); i += 2) ref.push_back(ref_curve.points[i]);
  std::printf("# reference: H = 128, %zu points, %zu folds, status %s\n", ref_curve.points.size(),
              ref_curve.folds.size(), StatusName(ref_curve.summary.status));
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  for (int H : {4, 8, 12, 16, 24, 32, 48, 64}) {
    double its = 0;
    const double err = ErrorOf(H, ref, &its);
    NhbOptions o;
    o.harmonics = H;
    o.stability = NhbStabilityMethod::kNone;
    NhbSolver solver(problem, o, H);
    const double t_point = wp::TimeIt([&] {
                             for (const NhbPoint& r : ref) {
                               VectorX x = ToUnknowns(r, H);
                               Status st;
                               double rn;
                               solver.Newton(x, r.omega, &st, &rn);
                             }
                           }) /
                           static_cast<double>(ref.size());
    wp::Row("point", H, t_point, err, its);
    // ≥ 1000-point continuation over the whole curve.
    const NhbContinuationOptions c = Range(0.0008);
    size_t points = 0;
    const double t_curve =
        wp::TimeIt([&] { points = TraceNonlinearHarmonicBalance(problem, o, c).points.size(); });
    wp::Row("curve", H, t_curve, err, double(points));
    o.stability = NhbStabilityMethod::kMonodromy;
    const double t_stab =
        wp::TimeIt([&] { points = TraceNonlinearHarmonicBalance(problem, o, c).points.size(); });
    wp::Row("curve+stability", H, t_stab, err, double(points));
    // The same with the AFT switch correction (S = 16H).
    const double err_sc = ErrorOf(H, ref, nullptr, true);
    o.switch_correction = true;
    o.stability = NhbStabilityMethod::kNone;
    const double t_sc =
        wp::TimeIt([&] { points = TraceNonlinearHarmonicBalance(problem, o, c).points.size(); });
    wp::Row("curve_switch_correction", H, t_sc, err_sc, double(points));
    o.stability = NhbStabilityMethod::kMonodromy;
    const double t_sc_stab =
        wp::TimeIt([&] { points = TraceNonlinearHarmonicBalance(problem, o, c).points.size(); });
    wp::Row("curve_switch_correction+stability", H, t_sc_stab, err_sc, double(points));
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
