/// @file
/// @brief The `geardyn simulate` report: the time-domain runs (one speed, independent speeds or
/// stepped up/down sweeps, per mean torque) as JSON, a text table, CSV files (the DTE, channel,
/// element-force and energy histories of one run; RMS and peak-to-peak DTE vs mesh frequency of
/// many) and an SVG of the RMS DTE with the up and down branches distinguished and an optional
/// harmonic-balance overlay.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/overlay_match.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn::app {

/// How the points of a run set were computed.
enum class SimulateMode {
  kSingle,       ///< one speed to steady state (histories kept)
  kIndependent,  ///< independent speeds, each from the static equilibrium (in parallel)
  kSweep,        ///< stepped sweep carrying the state from point to point (up and/or down)
};
/// "single", "independent", "sweep".
const char* ToString(SimulateMode mode);

/// One point: a mean torque, a branch ("up", "down", "independent"/"single") and its statistics.
struct SimulatePoint {
  double torque_nm = 0.0;  ///< mean torque of the operating point [N·m]
  std::string branch;      ///< "up", "down", "independent", "single"
  TimeSweepPoint point;    ///< mesh frequency, per-mesh RMS / p-p / mean DTE, status, …
  std::string integrator;  ///< the integrator used ("" when not known, e.g. a sweep point)
  long steps = -1;         ///< accepted steps (−1: not known)
  long events = -1;        ///< located switching events (−1: not known)
};

/// @brief The sweep-point form of a single response (its recorded-period statistics).
TimeSweepPoint ToSweepPoint(const TimeResponse& response);

/// What the command was asked (echoed in the JSON).
struct SimulateRunInfo {
  std::string scene;
  SimulateMode mode = SimulateMode::kSingle;
  std::string integrator = "auto";  ///< requested
  double tolerance = 0.0;           ///< local relative error per step [-]
  double steady_tolerance = 0.0;    ///< period-to-period change [-]
  int max_periods = 0;
  int record_periods = 0;
  bool interrupted = false;  ///< SIGINT: the results are those computed before it
  double wall_time_s = 0.0;
};

/// The harmonic-balance curve of one torque overlaid on the sweep plot (--overlay-hb).
struct HbOverlay {
  double torque_nm = 0.0;
  std::string label;              ///< legend, e.g. "nonlinear HB"
  std::vector<double> frequency;  ///< [Hz]
  std::vector<double> rms_dte;    ///< first mesh [m]; non-finite: a break
  /// Contact meshes: the slice model matched to them (overlay_match.hpp); empty otherwise.
  std::vector<SliceMatch> matches;
};

/// @brief The JSON report: "scene", "mode", "integrator" (requested), "tolerance",
/// "steady_tolerance", "max_periods", "record_periods", "status" (the worst point's), "message",
/// "interrupted", "warnings", "meshes" (names), "points": [{torque_nm, branch, mesh_frequency_hz,
/// status, message, steady, periods, max_energy_error, integrator, steps, events, meshes: [{name,
/// rms_dte_m, peak_to_peak_dte_m, mean_dte_m, contact_loss_fraction}]}], "wall_time_s"; with
/// `single` (one run) also "run": {integrator, steps, events, periods, period_meshes, steady,
/// max_energy_error, summary: {status, message, error_estimate, wall_time_s, counters,
/// warnings}}; "summaries": the library's Summary of each run set (a sweep, an independent run),
/// [{torque_nm, status, message, error_estimate, wall_time_s, counters}].
nlohmann::json MakeSimulateReport(const SimulateRunInfo& info,
                                  const std::vector<std::string>& mesh_names,
                                  const std::vector<SimulatePoint>& points,
                                  const std::vector<std::string>& warnings,
                                  const TimeResponse* single = nullptr,
                                  const std::vector<std::pair<double, Summary>>& summaries = {});

/// @brief Text: one line per point (RMS and peak-to-peak DTE in µm, periods, energy error), for
/// one run also the integrator and its step statistics, then the warnings.
std::string FormatSimulateText(const nlohmann::json& report);

/// @brief One row per point: torque_nm, branch, mesh_frequency_hz, status, steady, periods,
/// max_energy_error, then per mesh "<mesh>:rms_dte_m", ":peak_to_peak_dte_m", ":mean_dte_m",
/// ":contact_loss_fraction".
std::string FormatSimulateSweepCsv(const std::vector<std::string>& mesh_names,
                                   const std::vector<SimulatePoint>& points);

/// @brief The DTE history: time_s, theta_rad (the system mesh phase θ = θ₀ + 2π f_m t, t from the
/// start of the run), then per mesh "<mesh>:dte_m" and, when recorded, "<mesh>:force_n".
/// @param[in] initial_phase θ₀ [rad] of the run.
std::string FormatDteHistoryCsv(const TimeResponse& response, double initial_phase);

/// @brief The nonlinear cores' channels (per-tooth contact forces, status, deflections): time_s,
/// then "<mesh>:<channel>" per channel; "" when no mesh has channels.
/// @param[in] decimation the channel_decimation of the run (sample k is time k·decimation).
std::string FormatChannelHistoryCsv(const TimeResponse& response, int decimation);

/// @brief The element (bearing, shaft, coupling, spring) forces: time_s, then
/// "<element>:<component>" (fx, fy, fz, mx, my, mz of each body: "b0:fx" … ); "" when none.
std::string FormatElementForceCsv(const SystemModel& model, const TimeResponse& response);

/// @brief The energy balance per integrated period: period, input_work_j, stored_change_j,
/// dissipated_j, gross_flow_j, relative_error.
std::string FormatEnergyCsv(const TimeResponse& response);

/// @brief SVG: RMS DTE [µm] of the first mesh vs mesh frequency, one panel per torque; the up
/// branch solid with circles, the down branch dashed, independent points solid; the overlays
/// (one per torque) in grey. Points whose status is not success are left out (a break).
std::string RenderSimulatePlot(const std::string& title, const std::vector<std::string>& mesh_names,
                               const std::vector<SimulatePoint>& points,
                               const std::vector<HbOverlay>& overlays);

}  // namespace geardyn::app
