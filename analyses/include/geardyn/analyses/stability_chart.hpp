/// @file
/// @brief Stability charts over two parameters, `ComputeStabilityChart` (spec 02 "Floquet",
/// issue 5): max|λ| on a grid, the transition curves max|λ| = 1 traced by bisection, and the
/// unstable regions labelled by the nearest parametric resonance.
///
/// **Independent of models.** The chart engine only sees a ChartEvaluator: (x, y) → max|λ| of the
/// Floquet multipliers (plus its error estimate and the mesh frequency f_m at that point). Who
/// builds systems from which parameters (a scene front end, a closed form in a test) is the
/// caller's business.
///
/// **Verdict.** A point is unstable when max|λ| > 1 + max(instability_threshold,
/// error_estimate): an undamped (Hamiltonian) system has |λ| = 1 up to round-off in its stable
/// regions, so a strict test against 1 would flip on noise.
///
/// **Algorithm.**
/// 1. Grid: the evaluator at every (x_i, y_j), OpenMP-parallel over all points (dynamic
///    schedule); results stored by index, so the result does not depend on the thread count.
/// 2. Transition curves: on every grid edge whose two (successfully evaluated) ends have
///    different verdicts, bisection on the verdict (the sign of max|λ| − 1 − threshold) until the
///    bracket is ≤ boundary_tolerance·(hi − lo) of that axis; the crossing is the bracket's
///    midpoint (error ≤ half of it). Bisection, not regula falsi: at an undamped boundary
///    max|λ| − 1 grows like √distance, where secant steps stall. Edges are bisected in
///    parallel. The crossings are joined cell by cell (marching squares; a saddle cell — equal
///    verdicts on its diagonals — is resolved by the mean of the corners' max|λ| − 1 −
///    threshold) and chained into polylines, open ones (ending on the chart's border or at a
///    failed point) first, then closed ones.
/// 3. Regions: 4-connected components of unstable grid points. Each is labelled by the
///    parametric resonance of the mean LTI system (natural frequencies f_p of its row, numbered
///    from options.first_mode_index, zero frequencies skipped) that is nearest to the points'
///    f_m, by a vote of its points weighted by their growth max|λ| − 1 (the core of a tongue,
///    where the growth is largest, sits on the resonance): principal f_m = 2 f_p / k, label
///    "2f_p/k"; sum combination f_m = (f_p + f_q)/k, "(f_p+f_q)/k"; optionally difference
///    combination f_m = (f_q − f_p)/k, "(f_q-f_p)/k", k = 1 … max_resonance_order. Difference
///    resonances are off by default: for M, K(t) symmetric (no gyroscopic or circulatory terms)
///    they do not destabilize at first order (Hsu 1963, J. Appl. Mech. 30(3) 367–372), and
///    listing them only adds wrong candidates near every region.
///
/// Never prints: progress goes to the optional callback (called only from the calling thread).
/// An evaluator that reports failure (or an undetermined verdict, or a non-finite max|λ| or
/// estimate) marks its point as undetermined (not in any region, no curve through it) and the
/// summary says how many (counter "undetermined_points", status kNumericalIssue); an exception
/// thrown by an evaluator is rethrown after the parallel loop (the one of the lowest point index).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "geardyn/common/summary.hpp"

namespace geardyn {

/// @brief One axis of a chart: num_points uniformly spaced values from lo to hi.
struct ChartAxis {
  std::string name;    ///< free text, e.g. the scene path "operating_point.speed_rpm"
  double lo = 0.0;     ///< first value (finite, < hi) [unit of the parameter]
  double hi = 1.0;     ///< last value (finite) [unit of the parameter]
  int num_points = 2;  ///< in [2, kMaxChartAxisPoints]
  /// The i-th value lo + (hi − lo)·i/(n − 1), exactly lo and hi at the ends.
  double Value(int i) const;
  /// False (with the field and value in `why`, prefixed by `what`) when invalid.
  bool IsValid(const std::string& what, std::string* why) const;
};

/// Largest number of points on one chart axis: a row of the y axis builds its own model when x
/// is the speed, and 10⁴ points resolve a parameter to 10⁻⁴ of its range (the transition curves
/// are then bisected further, to boundary_tolerance) [-].
inline constexpr int kMaxChartAxisPoints = 10000;
/// Largest number of grid points x.num_points·y.num_points: each is one Floquet solve (ms to s
/// on the built-in scenes), so 10⁶ points are hours of work already [-].
inline constexpr long kMaxChartGridPoints = 1000000;

/// @brief False (with both counts, the limit and the cost in `why`) when the grid x × y has
/// more than kMaxChartGridPoints points. Checked by ComputeStabilityChart and, before any model
/// is built, by the CLI.
bool IsValidChartGrid(const ChartAxis& x, const ChartAxis& y, std::string* why);

/// @brief Where the evaluator is called: the parameters, and the grid indices when the
/// coordinate is a grid value (−1 between grid values, during the bisection).
struct ChartPoint {
  double x = 0.0;
  double y = 0.0;
  int ix = -1;  ///< index on the x axis, or −1
  int iy = -1;  ///< index on the y axis, or −1
};

/// @brief What the evaluator returns for one point.
struct ChartPointResult {
  double max_abs_multiplier = 0.0;  ///< max|λ| [-]
  double error_estimate = 0.0;      ///< error estimate of max|λ| [-] (≥ 0)
  double mesh_frequency_hz = 0.0;   ///< f_m at this point [Hz] (for the labels; 0 = unknown)
  /// false: undetermined (a failed evaluation or an undetermined Floquet verdict); the point
  /// is left out of the regions and curves and counted in "undetermined_points".
  bool ok = true;
};

/// Evaluates one point. One instance is used by one thread at a time.
using ChartEvaluator = std::function<ChartPointResult(const ChartPoint&)>;
/// Makes one evaluator per thread (called num_threads times by the calling thread before the
/// parallel work starts), so each can own its workspace.
using ChartEvaluatorFactory = std::function<ChartEvaluator()>;

/// @brief Progress of a running chart: phase "grid" or "boundaries", done of total evaluations
/// (the boundary total is an upper bound).
struct ChartProgress {
  const char* phase = "grid";
  long done = 0;
  long total = 0;
};
using ChartProgressCallback = std::function<void(const ChartProgress&)>;

/// @brief Options of ComputeStabilityChart.
struct StabilityChartOptions {
  /// Threads (0 = all cores, omp_get_max_threads()). ≥ 0. Clamped to the hardware threads
  /// (omp_get_num_procs()) and to the grid points, with a warning when a request is reduced.
  int num_threads = 0;
  /// Unstable when max|λ| > 1 + max(instability_threshold, error_estimate) [-]. ≥ 0, < 1.
  double instability_threshold = 1e-9;
  /// Trace the transition curves (bisection on the grid edges).
  bool trace_curves = true;
  /// Bisection stops when the bracket is ≤ boundary_tolerance·(hi − lo) of its axis [-].
  /// In (0, 1).
  double boundary_tolerance = 1e-6;
  /// Natural frequencies f_p [Hz] of the mean (LTI) system for the region labels: one list per
  /// y row (size y.num_points), or one list for all rows (size 1); empty: no labels.
  std::vector<std::vector<double>> natural_frequencies_hz;
  /// Largest k of the resonances f_m = 2f_p/k, (f_p ± f_q)/k. ≥ 1.
  int max_resonance_order = 3;
  /// Also label difference combinations (f_q − f_p)/k (see the @file).
  bool difference_combinations = false;
  /// Mode number of the first natural frequency in the labels (1: "f_1" is the first entry; 0
  /// matches `geardyn modes`, which numbers from 0). ≥ 0.
  int first_mode_index = 1;
  /// Called from the calling thread about every percent of the work; may be empty.
  ChartProgressCallback progress;
  /// Optional cancel flag (e.g. set by a SIGINT handler), polled before every grid point: once
  /// true the remaining points are skipped (undetermined, ok = 0) and the summary says
  /// Status::kInterrupted with the count computed. Not owned; must outlive the chart.
  const std::atomic<bool>* cancel = nullptr;
  /// False (with the field and value in `why`) on an invalid value.
  bool IsValid(std::string* why) const;
};

/// @brief Kind of a parametric resonance.
enum class ResonanceKind { kPrincipal, kSumCombination, kDifferenceCombination };
/// "principal", "sum_combination", "difference_combination".
const char* ToString(ResonanceKind kind);

/// @brief One parametric resonance of the mean LTI system.
struct Resonance {
  ResonanceKind kind = ResonanceKind::kPrincipal;
  int p = 0;  ///< mode number (first_mode_index + position in the frequency list)
  int q = 0;  ///< second mode number (combinations; q > p), unused (0) for principal
  int k = 1;  ///< order
  double mesh_frequency_hz = 0.0;  ///< f_m at the resonance [Hz]
  std::string label;               ///< "2f_3/1", "(f_2+f_5)/2", "(f_5-f_2)/1"
};

/// @brief One connected unstable region of the grid.
struct ChartRegion {
  int num_points = 0;               ///< grid points in the region
  double centroid_x = 0.0;          ///< mean x of its points
  double centroid_y = 0.0;          ///< mean y of its points
  double max_abs_multiplier = 0.0;  ///< largest max|λ| in it
  /// Growth-weighted mean of f_m over its points [Hz] (0 when f_m is unknown).
  double mean_mesh_frequency_hz = 0.0;
  bool labelled = false;  ///< false when no frequencies were given or f_m is unknown
  Resonance resonance;    ///< the nearest resonance (when labelled)
  /// Share of the region's growth-weighted vote won by `resonance` [-], in (0, 1].
  double vote_share = 0.0;
};

/// @brief A transition curve max|λ| = 1 (the bisected crossings of the grid edges, joined).
struct TransitionCurve {
  std::vector<double> x;
  std::vector<double> y;
  bool closed = false;  ///< the last point joins the first
};

/// @brief The chart. Point arrays are row-major: index = iy·n_x + ix.
struct StabilityChartResult {
  Summary summary;  ///< counters "evaluations", "grid_points", "undetermined_points", "regions",
                    ///< "curve_points", "threads"; error_estimate = largest crossing error as a
                    ///< fraction of its axis span
  ChartAxis x_axis;
  ChartAxis y_axis;
  std::vector<double> max_abs_multiplier;  ///< max|λ| per point
  std::vector<double> error_estimate;      ///< per point
  std::vector<double> mesh_frequency_hz;   ///< per point [Hz]
  /// 1 when the point has a verdict; 0 undetermined (the evaluator's ok is false, or max|λ| or
  /// its estimate is not finite): neither stable nor unstable, in no region and no curve.
  std::vector<std::uint8_t> ok;
  std::vector<std::uint8_t> stable;  ///< 1 stable, 0 unstable or undetermined (see ok)
  std::vector<int> region;           ///< index into regions, −1 if not unstable
  std::vector<ChartRegion> regions;
  std::vector<TransitionCurve> curves;
  int index(int ix, int iy) const { return iy * x_axis.num_points + ix; }
};

/// @brief The chart over x × y (see the @file).
/// @throws InvalidInput on invalid axes or options; rethrows an evaluator's exception.
StabilityChartResult ComputeStabilityChart(const ChartAxis& x, const ChartAxis& y,
                                           const ChartEvaluatorFactory& make_evaluator,
                                           const StabilityChartOptions& options = {});

/// @brief The resonances of natural frequencies f (entry i is mode first_mode_index + i; f ≤ 0
/// skipped), k = 1 … max_order, sorted by mesh frequency (see the @file for kinds and labels).
std::vector<Resonance> ListResonances(const std::vector<double>& natural_frequencies_hz,
                                      int max_order, bool difference_combinations,
                                      int first_mode_index = 1);

}  // namespace geardyn
