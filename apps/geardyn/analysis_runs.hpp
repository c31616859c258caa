/// @file
/// @brief The analyses of the `geardyn` subcommands as functions of a loaded Scene: what a
/// command computes, reports (the JSON of --json, the text) and writes to --out, without its
/// argument parsing. The commands and the Python package (python/src/) both call these, so a
/// Python result's `report` is the command's JSON for the same input.
///
/// Every function throws InvalidInput (SceneError) on bad settings, naming the command-line flag
/// the setting comes from, and reports numerical trouble in the report's status (exit_code 1).
#pragma once

#include <functional>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "geardyn/campbell_report.hpp"
#include "geardyn/compare_runner.hpp"
#include "geardyn/hb_report.hpp"
#include "geardyn/models/scene/scene.hpp"
#include "geardyn/modes_report.hpp"
#include "geardyn/stability_chart_runner.hpp"

namespace geardyn::app {

/// Receives one progress line (ending in '\n'); may be empty (no progress).
using ProgressLine = std::function<void(const std::string& line)>;

/// What every run returns besides its result.
struct RunReport {
  nlohmann::json report;  ///< the command's --json output
  std::string text;       ///< the command's text output (without "written to")
  int exit_code = 0;      ///< kExitOk, or kExitNumericalIssue on a status other than success
};

/// `geardyn modes`: the modes of the mean (LTI) system. Writes modes.json, modes.csv (and
/// mode_shapes.csv with settings.shapes) to `out_dir` unless it is empty.
struct ModesRun : RunReport {
  ModalResult result;
};
ModesRun RunModesAnalysis(const Scene& scene, const ModesSettings& settings,
                          const std::string& out_dir = {});

/// `geardyn campbell`: the modes of the speed-dependent mean system over a speed grid, tracked,
/// with the excitation orders, crossings and instabilities (campbell_report.hpp). Writes
/// campbell.json, campbell.csv, crossings.csv and campbell.svg to `out_dir` unless it is empty.
struct CampbellRun : RunReport {
  CampbellResult result;
};
CampbellRun RunCampbellAnalysis(const Scene& scene, const CampbellSettings& settings,
                                const std::string& out_dir = {});

/// The settings of `geardyn floquet`.
struct FloquetSettings {
  std::string method = "auto";  ///< --method (kFloquetMethods' names)
  double tolerance = 1e-10;     ///< --tolerance on the multipliers, in (0, 1)
  int nev = 6;                  ///< --nev, arpack_monodromy only, 1 … 2n
  /// --max-approximant-period: incommensurate mesh frequencies, the longest common period of the
  /// rational approximants analysed [mesh cycles], 0 … 10⁴ (0 refuses such a scene).
  long max_approximant_period = 1000;
};

/// `geardyn floquet`: the multipliers at the operating point. Writes floquet.json and
/// multipliers.csv to `out_dir` unless it is empty. exit_code 1 also on an undetermined verdict.
struct FloquetRun : RunReport {
  FloquetResult result;
  double mesh_frequency_hz = 0.0;  ///< where the multipliers were computed [Hz]
};
FloquetRun RunFloquetAnalysis(const Scene& scene, const FloquetSettings& settings,
                              const std::string& out_dir = {});

/// The settings of `geardyn hb` beyond HbSettings.
struct HbRunSettings {
  HbSettings settings;                  ///< --mesh-frequency, --harmonics, --tolerance, --linear
  bool nonlinear = false;               ///< --nonlinear
  std::string stability = "monodromy";  ///< --stability none|monodromy|hill
  int monodromy_steps = 0;              ///< --monodromy-steps (0: automatic)
  int branch_search = SystemNhbOptions{}.continuation.branch_search;  ///< --branch-search (0: off)
  bool harmonics_given = false;  ///< --harmonics was given (0 is then an error)
  bool tolerance_given = false;  ///< --tolerance was given
};

/// `geardyn hb`: linear HB sweep (with Floquet verdicts) or nonlinear continuation. Writes
/// hb.json/hb.csv/hb_rms_dte.svg or nhb.json/nhb.csv/nhb_rms_dte.svg to `out_dir` unless empty.
/// Progress lines go to `progress` when settings.settings.progress is set.
struct HbRun : RunReport {
  bool nonlinear = false;  ///< which of the two the scene and settings chose
};
HbRun RunHbAnalysis(const Scene& scene, const HbRunSettings& settings,
                    const std::string& out_dir = {}, const ProgressLine& progress = {});

/// The settings of `geardyn stability-chart` (on top of SceneChartSettings' scene, overrides).
struct ChartRunSettings {
  std::string x, y;  ///< --x, --y PATH=LO:HI:N
  int threads = 0;
  std::string method = "auto";
  double tolerance = 1e-6;
  double boundary_tolerance = 1e-3;
  int max_order = 3;
  bool difference = false;
  bool curves = true;  ///< not --no-curves
};

/// `geardyn stability-chart`: max|λ| over two scene parameters. `scene` is the path or builtin
/// name; `scene_text` its TOML text when it was not read from a file (empty: read `scene`).
/// Writes stability_chart.json/.csv/.svg and transition_curves.csv to `out_dir` unless empty.
struct ChartRun : RunReport {
  SceneChart run;
};
ChartRun RunChartAnalysis(const std::string& scene, const std::string& scene_text,
                          const std::vector<std::string>& overrides,
                          const ChartRunSettings& settings, const std::string& out_dir = {},
                          const ProgressLine& progress = {});

/// `geardyn compare` without --vary: the scene at several model levels. `settings` is complete
/// (levels and analyses parsed, scene_path, scene_text and overrides set for the charts and the
/// contact matching). Writes compare.json and the CSV/SVG files to `out_dir` unless it is empty;
/// progress lines go to `progress` when settings.progress (may be null).
struct CompareRun : RunReport {};
CompareRun RunCompareAnalysis(const Scene& scene, const CompareSettings& settings,
                              const std::string& out_dir = {}, std::ostream* progress = nullptr);

/// The settings of `geardyn simulate` (its options but the scene's).
struct SimulateSettings {
  std::string mesh_frequency;   ///< --mesh-frequency ("" = the operating point)
  std::string sweep;            ///< --sweep up|down|both ("" = independent speeds)
  std::vector<double> torques;  ///< --torque [N·m]
  std::string integrator = "auto";
  double tolerance = TimeIntegrationOptions{}.relative_tolerance;
  double steady_tolerance = SteadyStateOptions{}.tolerance;
  int max_periods = SteadyStateOptions{}.max_periods;
  int record_periods = SteadyStateOptions{}.record_periods;
  int samples_per_period = TimeIntegrationOptions{}.samples_per_period;
  double max_step = TimeIntegrationOptions{}.max_step_fraction;
  int threads = 0;
  bool quasi_static = false;
  bool full_period = false;  ///< --full-period: no symmetry shift in the steady test
  bool overlay_hb = false;
  bool progress = false;
};

/// `geardyn simulate`: time integration to steady state (one speed, several, sweeps) or the
/// quasi-static export. Writes the command's files to `out_dir` unless empty; the progress lines
/// go to `progress` (the pre-run warnings only to the report's warnings). exit_code as the
/// command's (130 when interrupted). `scene_text`: the scene's TOML text when it was not read
/// from scene.source (empty: the --overlay-hb matching reloads scene.source).
struct SimulateRun : RunReport {
  /// A single run's response (time, DTE and force histories of the recorded periods); null for
  /// sweeps, several torques and the quasi-static export.
  std::shared_ptr<const TimeResponse> history;
  double initial_phase = 0.0;  ///< θ at t = 0 [rad] (the DTE history's phase origin)
};
SimulateRun RunSimulateAnalysis(const Scene& scene, const std::string& scene_text,
                                const SimulateSettings& settings, const std::string& out_dir = {},
                                const ProgressLine& progress = {});

}  // namespace geardyn::app
