/// @file
/// @brief The outputs of `geardyn compare` (compare_runner.hpp): JSON, a text report, CSV tables
/// and the SVG figure of the DTE of every level with its difference to the reference; and the
/// summary of a parameter sweep (`--vary`): the error of every level against the parameter.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/compare_runner.hpp"

namespace geardyn::app {

/// @brief The JSON report: "scene", "mesh", "operating_mesh_frequency_hz", "settings",
/// "references" {modes, floquet, dte}, "frequencies_hz", "levels": [{level, description, num_dofs,
/// skipped {analysis: reason}, warnings, modes {frequencies_hz, labels, status, wall_time_s},
/// floquet {max_abs_multiplier, verdict, method, status, message, wall_time_s}, dte {source,
/// status, message, wall_time_s, rms_up_m, rms_down_m, peak_to_peak_up_m, peak_to_peak_down_m,
/// jumps_hz, curve {hz, rms_m, stable, segment}}, comparison {verdict {modes, floquet, dte}, notes,
/// modes [{reference_mode, reference_hz, type, mode, hz, relative_difference, mac}], absent,
/// extra, floquet_difference, dte {max_abs, max_at_hz, max_where, rms, peak_hz,
/// reference_peak_hz, peak_ratio, missing, disagree_ranges_hz, difference_up, difference_down}}}],
/// "status" ("success" or "numerical_issue"), "wall_time_s". Non-finite numbers are null.
nlohmann::json MakeCompareReport(const CompareResult& result);

/// @brief The text report: the level table (verdicts and wall times), the mode table (Δf/f and MAC
/// per reference mode and level), the DTE summary, and the verdict notes.
std::string FormatCompareText(const CompareResult& result);

/// compare_levels.csv: one row per level (verdicts, errors, wall times).
std::string FormatCompareLevelsCsv(const CompareResult& result);
/// compare_modes.csv: one row per (level, reference mode).
std::string FormatCompareModesCsv(const CompareResult& result);
/// compare_dte.csv: one row per mesh frequency, RMS/p-p up/down and d per level.
std::string FormatCompareDteCsv(const CompareResult& result);
/// compare_dte.svg: RMS DTE of every level, and its difference to the reference.
std::string RenderCompareDtePlot(const CompareResult& result);

/// compare_chart.svg: the reference level's stability chart (regions) with every level's
/// transition curves in its colour.
std::string RenderCompareChartPlot(const CompareResult& result);
/// compare_chart.csv: level, x, y, max|λ|, stable (1/0, nan when undetermined) per grid point.
std::string FormatCompareChartCsv(const CompareResult& result);

/// @brief One value of a `--vary` sweep and its comparison.
struct CompareVaryPoint {
  double value = 0.0;
  CompareResult result;
};

/// compare_vary.csv: value, level, max |Δf/f|, absent modes, Floquet difference, DTE max |d|,
/// DTE RMS d, peak shift.
std::string FormatCompareVaryCsv(const std::string& key, const std::vector<CompareVaryPoint>& v);
/// The JSON of a sweep: key, values, and per value the levels' summary numbers.
nlohmann::json MakeCompareVaryReport(const std::string& key,
                                     const std::vector<CompareVaryPoint>& v);
/// The text table of a sweep.
std::string FormatCompareVaryText(const std::string& key, const std::vector<CompareVaryPoint>& v);
/// compare_vary.svg: the errors of every level against the parameter.
std::string RenderCompareVaryPlot(const std::string& key, const std::vector<CompareVaryPoint>& v);

}  // namespace geardyn::app
