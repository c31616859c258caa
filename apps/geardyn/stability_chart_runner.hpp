/// @file
/// @brief The scene front end of the stability chart: axes given as `--x path=lo:hi:n` over any
/// `--set`-able scene path, one SystemModel per value of the non-speed parameter, and a
/// ComputeFloquet evaluator per thread for ComputeStabilityChart (stability_chart.hpp).
///
/// **Speed is cheap.** `operating_point.speed_rpm` only changes the mesh frequency
/// (f_m = z_pinion·n/60 of the first mesh, Scene::MeshFrequencyHz), not the SystemModel: when one
/// axis is that path, the model is built once per value of the other axis (cached for the grid
/// rows, built on the fly between grid values while a transition curve is bisected) and every
/// point is one ComputeFloquet at another mesh_frequency_hz. Without a speed axis every point
/// loads the scene with both overrides and builds its model.
///
/// **Verdict tolerance.** Every point is a ComputeFloquet at `floquet.tolerance` (the CLI's
/// default 1e-6: a verdict, not 1e-10 multipliers, is what a chart needs; 10–16× fewer Magnus
/// steps on the helical pair than 1e-10), with the measured-order Magnus step control
/// (FloquetOptions::magnus_measured_order: its estimate is tight where the default one is ≈ 63×
/// pessimistic, so it stops ≈ 2× earlier) and without the undamped-mode list. A point whose growth
/// g = max|λ| − 1 − threshold is positive but ≤ 2·error_estimate — a verdict the screening error
/// could flip either way — is recomputed at `verdict_tolerance` (1e-10, same step control) and
/// charted with that result. Damped stable points (g < 0) and marginal ones (|λ| = 1 to round-off:
/// undamped modes) need no refinement; unstable points beyond twice the estimate keep their
/// screening values.
///
/// **Prepared rows.** With `prepare_rows` (the default) every row's model is wrapped in a
/// PreparedFloquet (prepared_floquet.hpp): the scaled state system and A(θ) as its Fourier series
/// in the phase, verified against the model's assembly, are built once per row, so a point costs
/// the Magnus runs and the eigen-solve only. Points between rows (bisection) build their model and
/// call ComputeFloquet.
///
/// **Labels.** Natural frequencies of the mean LTI system (ComputeModes of the model, mode
/// numbers from 0 as `geardyn modes` prints them): per grid row when the speed is on x, otherwise
/// those of the scene at the lower ends of the axes.
#pragma once

#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/stability_chart.hpp"

namespace geardyn::app {

/// The scene path whose axis only changes the mesh frequency.
inline constexpr const char* kSpeedPath = "operating_point.speed_rpm";

/// @brief One chart axis as given on the command line: `path=lo:hi:n`.
struct ChartAxisSpec {
  std::string path;
  double lo = 0.0;
  double hi = 0.0;
  int num_points = 0;
};

/// @brief Parses `path=lo:hi:n` (n ≥ 2 integer, lo < hi finite).
/// @throws InvalidInput naming `option` (e.g. "--x"), the text and what is wrong.
ChartAxisSpec ParseChartAxis(const std::string& option, const std::string& text);

/// @brief Everything the chart needs besides the scene.
struct SceneChartSettings {
  std::string scene;  ///< file or builtin:NAME (the name errors use)
  /// The scene's TOML text when it is not read from `scene` (the Python package's scenes from
  /// a string or a dict); empty: LoadScene(scene).
  std::string scene_text;
  std::vector<std::string> overrides;  ///< --set, applied before the axis values
  ChartAxisSpec x;
  ChartAxisSpec y;
  FloquetOptions floquet;  ///< method, tolerance (mesh_frequency_hz is set per point)
  /// Floquet tolerance of the points whose verdict the screening estimate leaves open (see the
  /// @file); ≤ floquet.tolerance to have an effect [-].
  double verdict_tolerance = 1e-10;
  /// Screen with the measured-order Magnus step control (FloquetOptions::magnus_measured_order:
  /// a tight estimate at ≈ 2× fewer A(t) evaluations); false: the default control (benchmarks
  /// compare).
  bool measured_order = true;
  /// Prepare every grid row's model once for Floquet at any speed (PreparedFloquet: the state
  /// system and A(θ)'s Fourier series built once; same results to round-off); false: every point
  /// calls ComputeFloquet on the row's model (benchmarks compare).
  bool prepare_rows = true;
  StabilityChartOptions chart;  ///< threads, tolerances, progress (frequencies are set here)
};

/// @brief The chart and what the front end decided.
struct SceneChart {
  StabilityChartResult chart;
  /// "x", "y" or "" (no speed axis): which axis is operating_point.speed_rpm.
  std::string speed_axis;
  /// f_m per rpm of the first mesh [Hz/rpm] at the axes' lower ends (0 without a speed axis).
  double mesh_hz_per_rpm = 0.0;
  /// Natural frequencies of the mean system at the axes' lower ends [Hz].
  std::vector<double> natural_frequencies_hz;
  long model_builds = 0;    ///< SystemModels built (rows + points + bisection steps)
  long refined_points = 0;  ///< evaluations repeated at verdict_tolerance
  /// Grid rows whose model is prepared for Floquet at any speed (PreparedFloquet::prepared()).
  long prepared_rows = 0;
  std::vector<std::string> warnings;
};

/// @brief Validates the axes against the scene (both ends must load; a speed axis must stay
/// > 0), then computes the chart (see the @file).
/// @throws InvalidInput (SceneError) naming the axis option and path on an unknown or invalid
///   path or value.
SceneChart ComputeSceneStabilityChart(const SceneChartSettings& settings);

struct RegionPlotSpec;  // region_plot.hpp

/// @brief The chart's grid in a region plot: axis names and values, max|λ|, verdicts (no curves,
/// labels or markers).
RegionPlotSpec MakeRegionPlotGrid(const StabilityChartResult& chart, const std::string& title);

}  // namespace geardyn::app
