/// @file
/// @brief The nonlinear `geardyn hb` report (TraceSystemNonlinearHb, contact loss and back-flank
/// contact of slice meshes): the traced frequency-response curve as JSON, CSV, a decimated text
/// table with the jump list, and an SVG plot of the first mesh's RMS DTE vs mesh frequency
/// (stable branch solid, unstable dashed, jumps marked and labelled).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/analyses/system_nonlinear_hb.hpp"

namespace geardyn::app {

/// What the nonlinear run was asked for (echoed in the JSON).
struct NhbRunInfo {
  double start_hz = 0.0;        ///< first mesh frequency of --mesh-frequency [Hz]
  double end_hz = 0.0;          ///< last mesh frequency [Hz] (= start_hz for a single solve)
  int resolution = 1;           ///< n of lo:hi:n: the trace has at least about n points
  int harmonics_requested = 0;  ///< H asked for (0: from the tolerance)
  double tolerance = 0.0;       ///< harmonic tolerance when harmonics_requested = 0 [-]
  std::string stability;        ///< "none", "monodromy" or "hill"
};

/// Number of DTE harmonic amplitudes per mesh in the CSV and the text (a1 … a5).
inline constexpr int kNhbCsvHarmonics = 5;

/// @brief The JSON report: "scene", "mode" ("nonlinear"), "mesh_frequency" {start_hz, end_hz,
/// resolution}, "harmonics" (H used), "harmonics_requested", "tolerance", "period_multiple" (p:
/// amplitudes are of harmonics of f_m/p), "stability", "status", "message", "error_estimate",
/// "warnings" (scene warnings prefixed "scene: "), "meshes", "elements" (names), "points": [{
/// mesh_frequency_hz, branch, stable, max_multiplier, error_estimate, status, meshes: [{name,
/// rms_dte_m, peak_to_peak_dte_m, mean_dte_m, dte_amplitudes_m (all H+1: |mean| then harmonics
/// 1…H [m]), mean_force_n, rms_force_n, min_force_n, max_force_n, contact_loss_fraction,
/// back_contact}], elements: [{name, mean_force, rms_force} (6 components, N and N·m)]}],
/// "folds_hz", "fold_errors_hz" (estimated error of locating each fold [Hz]), "jumps": [{direction
/// ("up"/"down"), mesh_frequency_hz, rms_dte_before_m, rms_dte_after_m (null when no landing branch
/// was traced)}], "wall_time_s". Non-finite numbers are written as null.
nlohmann::json MakeNhbReport(const std::string& scene_source, const NhbRunInfo& info,
                             const SystemNhbCurve& curve,
                             const std::vector<std::string>& scene_warnings);

/// @brief One row per traced point (arclength order): mesh_frequency_hz, branch, stable (0/1),
/// max_multiplier, error_estimate, status, then per mesh "<mesh>:rms_dte_m", ":peak_to_peak_dte_m",
/// ":mean_dte_m", ":a1_m" … ":a5_m" (harmonics 1…5 of f_m/p; empty beyond H), ":mean_force_n",
/// ":rms_force_n", ":min_force_n", ":max_force_n", ":contact_loss_fraction", ":back_contact" (0/1),
/// then per element "<element>:mean_fx_n" … ":mean_mz_nm" and ":rms_fx_n" … ":rms_mz_nm".
/// stable, max_multiplier and error_estimate are empty when !stability_computed (--stability none);
/// stable is nan when undetermined.
std::string FormatNhbCsv(const SystemNhbCurve& curve, bool stability_computed = true);

/// @brief A text table of at most ~60 points (evenly decimated, the last point always kept; one
/// line per mesh), the folds, the jump list and the warnings.
std::string FormatNhbText(const nlohmann::json& report);

/// @brief SVG: RMS DTE [µm] of the first mesh vs mesh frequency [Hz]: runs of stable points as
/// solid segments, unstable as dashed (neighbouring runs share their boundary point), every
/// jump a grey vertical segment from the RMS before to the RMS after with circles, the one
/// before labelled "up"/"down" and its frequency. Points without converged status are left out.
std::string RenderNhbPlot(const SystemNhbCurve& curve, const std::string& title,
                          bool stability_computed = true);

}  // namespace geardyn::app
