/// @file
/// @brief `geardyn campbell`: the scene front end of ComputeCampbell (campbell.hpp) — the speed
/// grid, the speed terms (speed_terms.hpp), the excitation orders of every mesh frequency and
/// shaft speed — and its reports: JSON, text, campbell.csv, crossings.csv and campbell.svg.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {

/// The command-line settings of `geardyn campbell`.
struct CampbellSettings {
  /// --speed "lo:hi:n" [rpm] of the operating point's body (n ≥ 2 points, linear spacing).
  std::string speed;
  /// --carrier-speed "lo:hi:n" [rpm] of the carrier of the first planetary set with a rotating
  /// carrier, instead of --speed.
  std::string carrier_speed;
  int orders = 3;                 ///< --orders K: mesh orders 1 … K (shaft orders: 1)
  double max_frequency_hz = 0;    ///< --max-frequency: tracks whose first frequency is above it
                                  ///< are left out (0: all)
  bool undamped = false;          ///< --undamped: C̄ = 0 (the conservative gyroscopic system)
  bool no_carrier_frame = false;  ///< --no-carrier-frame: planetary sets in a fixed frame
  bool no_spin = false;           ///< --no-spin-gyroscopics
  bool loaded = false;  ///< --loaded: each mesh's preload stiffness K_g(F̄_η) added to K̄
};

/// The swept speeds: `values_rpm` of `body` (the reference or the carrier) and the reference
/// speeds s [rad/s] they give.
struct CampbellSweep {
  std::string body;
  std::string kind;  ///< "operating_point" or "carrier"
  std::vector<double> values_rpm;
  std::vector<double> reference_speeds;  ///< s [rad/s]
  double rpm_per_reference = 0.0;        ///< swept rpm per rad/s of reference speed (> 0)
};

/// @brief The sweep of the settings.
/// @throws InvalidInput naming --speed or --carrier-speed: both or neither given, malformed
///   "lo:hi:n", lo < 0, hi ≤ lo, n not in 2 … 10000; a carrier speed on a scene without a
///   rotating planetary carrier; an oscillator scene.
CampbellSweep MakeCampbellSweep(const Scene& scene, const CampbellSettings& settings);

/// @brief Mesh orders 1 … orders of each distinct mesh frequency and order 1 of each distinct
/// shaft speed, per rad/s of the reference speed.
std::vector<CampbellExcitation> MakeCampbellExcitations(const Scene& scene, int orders);

/// @brief The JSON report: "scene", "sweep" {body, kind, speeds_rpm}, "terms" (what is modelled),
/// "status", "message", "warnings", "num_rigid_body_modes", "deflated", "tracks" [{index, label,
/// planetary_label, frequency_hz[], growth_rate[], mac[], unstable[]}], "excitations" [{name, kind,
/// order, hz_per_rpm}], "crossings" [{track, label, excitation, speed_rpm, frequency_hz}],
/// "instabilities" [{modes, kind, speed_begin_rpm, speed_end_rpm, max_growth_rate}],
/// "static_critical_speeds_rpm", "counters", "wall_time_s".
nlohmann::json MakeCampbellReport(const std::string& scene_source, const CampbellSweep& sweep,
                                  const std::vector<CampbellExcitation>& excitations,
                                  const std::vector<std::string>& notes,
                                  const std::vector<int>& kept_tracks,
                                  const CampbellResult& result);

/// The text summary of a report.
std::string FormatCampbellText(const nlohmann::json& report);

/// campbell.csv: one row per (speed, track).
std::string FormatCampbellCsv(const nlohmann::json& report);

/// crossings.csv: one row per crossing.
std::string FormatCrossingsCsv(const nlohmann::json& report);

/// campbell.svg: the tracks (unstable points dashed), the excitation lines (grey) and the
/// crossings (circles).
std::string RenderCampbellSvg(const nlohmann::json& report);

}  // namespace geardyn::app
