/// @file
/// @brief The `geardyn hb` report: settings → HbOptions and the list of mesh frequencies, and the
/// sweep result as JSON, text table, CSV and an SVG plot of the RMS DTE vs mesh frequency.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/hb_stability.hpp"

namespace geardyn::app {

/// Number of DTE harmonic amplitudes per mesh in the CSV (a1 … a5).
inline constexpr int kCsvHarmonics = 5;

/// The command-line settings of `geardyn hb`.
struct HbSettings {
  /// --mesh-frequency "lo:hi:n" [Hz] (n ≥ 1 points, linear spacing) or a single value; empty:
  /// 0.2 … 2.5 × the scene's mesh frequency, 200 points.
  std::string mesh_frequency;
  int harmonics = 0;        ///< --harmonics H (0: from --tolerance)
  double tolerance = 1e-4;  ///< --tolerance: relative change of the RMS DTE (H/2 → H)
  bool linear = false;      ///< --linear (linear model even with slice meshes)
  bool progress = false;    ///< --progress: a progress line on stderr
};

/// @brief The mesh frequencies of "lo:hi:n" or "f" [Hz]; `nominal_hz` (the scene's) for the
/// default range when `spec` is empty.
/// @throws InvalidInput naming --mesh-frequency: malformed text, lo ≤ 0, hi < lo, n < 1,
///   n > 100000, or an empty spec with nominal_hz ≤ 0 (operating speed 0).
std::vector<double> ParseMeshFrequencies(const std::string& spec, double nominal_hz);

/// @brief HbOptions of the settings.
/// @throws InvalidInput naming --harmonics (< 0) or --tolerance (≤ 0).
HbOptions MakeHbOptions(const HbSettings& settings);

/// @brief The JSON report: "scene", "mode" ("linear"), "harmonics" (requested, 0 = tolerance),
/// "tolerance", "status", "message", "warnings" (scene warnings prefixed "scene: "), "meshes"
/// (names), "elements" (names), "points": [{mesh_frequency_hz, harmonics, method,
/// error_estimate, status, meshes: [{name, rms_dte_m, peak_to_peak_dte_m, mean_dte_m,
/// dte_amplitudes_m, mean_force_n, rms_force_n, peak_to_peak_force_n}], elements: [{name,
/// mean_force, rms_force}], stability}], "stability" ("floquet" or "none"), "unstable_ranges"
/// ([{lo_hz, hi_hz, points, max_abs_multiplier}]), "wall_time_s", "stability_wall_time_s".
/// With `stability` (one verdict per point, hb_stability.hpp) each point's "stability" is
/// {verdict, max_abs_multiplier, error_estimate, marginal, method, status[, message]} (null
/// without), its warnings follow the sweep's, and "status"/"message" are the stability's when
/// the sweep succeeded but a verdict is undetermined.
nlohmann::json MakeHbReport(const std::string& scene_source, const HbSettings& settings,
                            const HbSweepResult& sweep,
                            const std::vector<std::string>& scene_warnings,
                            const HbStabilitySweep* stability = nullptr);

/// @brief One row per mesh frequency: mesh_frequency_hz, harmonics, error_estimate, status, then
/// per mesh "<mesh>:rms_dte_m", ":peak_to_peak_dte_m", ":mean_dte_m", ":a1_m" … ":a5_m",
/// ":rms_force_n" (amplitudes of system harmonics 1 … 5; empty beyond H). With `stability`,
/// two more columns after status: "stability" (stable / unstable / undetermined) and
/// "max_abs_multiplier".
std::string FormatHbCsv(const HbSweepResult& sweep, const HbStabilitySweep* stability = nullptr);

/// @brief A short text table (every ~20th point for long sweeps; unstable and undetermined
/// points are always listed, with "unstable (parametric, max|λ| = x)") and the warnings.
std::string FormatHbText(const nlohmann::json& report);

/// @brief SVG: RMS DTE [µm] vs mesh frequency [Hz], one curve per mesh (points whose status is
/// not success are left out); with `stability`, dashed over the runs of parametrically unstable
/// points (as the nonlinear plot) and broken at undetermined ones.
std::string RenderHbPlot(const HbSweepResult& sweep, const std::string& title,
                         const HbStabilitySweep* stability = nullptr);

}  // namespace geardyn::app
