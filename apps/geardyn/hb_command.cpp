// `geardyn hb SCENE`: the steady-state DTE of the scene over mesh frequency, printed as a table or
// JSON and written to --out.
//
// * Nonlinear (the default when the built model has slice meshes, model.time_dependence() ==
//   kNonlinear; forced by --nonlinear): TraceSystemNonlinearHb (contact loss and back-flank
//   contact) by pseudo-arclength continuation over lo..hi of --mesh-frequency; the n of lo:hi:n
//   is the resolution: a continuation step changes the mesh frequency by at most 1/n of the
//   range (NhbContinuationOptions::max_omega_step), so the curve has at least about n points;
//   along resonances and folds the tangent angle and the corrector place more. One frequency: a
//   single periodic solution. Files nhb.json, nhb.csv, nhb_rms_dte.svg (nhb_report.hpp).
// * Linear (--linear, or no slice mesh): SweepHarmonicBalance on the listed frequencies (slice
//   meshes linearized with every slice loaded). Files hb.json, hb.csv, hb_rms_dte.svg. Unless
//   --stability none, every point carries the Floquet verdict of the homogeneous system at its
//   mesh frequency (ComputeHbStability, hb_stability.hpp): unstable points are flagged, the
//   unstable ranges are warnings, and an undetermined verdict gives exit code 1
//   (docs/design.md "Linear HB stability").
// * Several mesh frequencies (a multi-stage train, HasSeveralMeshFrequencies): the quasi-periodic
//   HB on the torus of the mesh frequencies (hb_quasi_periodic.hpp), nonlinear with slice meshes
//   unless --linear, no Floquet verdicts.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/hb_stability.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/analysis_runs.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/hb_quasi_periodic.hpp"
#include "geardyn/hb_report.hpp"
#include "geardyn/interrupt.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/oscillator_system.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/nhb_report.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

constexpr int kNonlinearDefaultHarmonics = 24;
// Error target of the linear path's Floquet verdicts [-] (on the multipliers): a verdict needs
// |λ| − 1 resolved, not 1e-10 (`geardyn floquet`'s default); a growth below 1e-6 per period
// e-folds over 10⁶ periods. Exact steps (piecewise-constant K) are round-off accurate anyway;
// Magnus (smooth K) needs 3–8× fewer steps than at 1e-10 (docs/benchmarks.md).
constexpr double kLinearStabilityTolerance = 1e-6;
// Minimum time between two --progress lines of the nonlinear trace [s].
constexpr double kProgressInterval = 0.5;

struct HbCommandOptions {
  SceneCommandOptions scene;
  HbRunSettings run;
  CLI::Option* tolerance_option = nullptr;
  CLI::Option* harmonics_option = nullptr;
};

// The scene's first mesh frequency [Hz], 0 when it has no meshes or no speed; an oscillator
// scene's natural frequency (1 Hz: the default range is then 0.2 to 2.5 times it).
double NominalMeshFrequency(const Scene& scene) {
  if (scene.oscillator) return kOscillatorNaturalFrequencyHz;
  return scene.NominalMeshFrequencyHz();
}

NhbStabilityMethod StabilityMethod(const std::string& name) {
  if (name == "none") return NhbStabilityMethod::kNone;
  if (name == "hill") return NhbStabilityMethod::kHill;
  return NhbStabilityMethod::kMonodromy;
}

// The run's report and text; the files written to `out_dir` unless it is empty.
void Finish(HbRun* run, nlohmann::json report, std::string text, const std::string& out_dir,
            const std::vector<std::pair<std::string, std::string>>& files) {
  for (const auto& [name, content] : files) {
    if (!out_dir.empty()) WriteOutputFile(out_dir, name, content);
  }
  run->report = std::move(report);
  run->text = std::move(text);
}

HbRun RunNonlinearHb(const HbRunSettings& opts, const Scene& scene, const SceneSystem& built,
                     const std::vector<double>& frequencies, const std::string& out_dir,
                     const ProgressLine& err) {
  const HbSettings& settings = opts.settings;
  GEARDYN_THROW_UNLESS(
      settings.harmonics >= 0,
      "--harmonics: must be >= 1 (or 0 for --tolerance), got " << settings.harmonics);
  GEARDYN_THROW_UNLESS(std::isfinite(settings.tolerance) && settings.tolerance > 0.0,
                       "--tolerance: must be > 0, got " << settings.tolerance);
  const bool by_tolerance = settings.harmonics == 0 && opts.tolerance_given;
  SystemNhbOptions options;
  options.hb.harmonics =
      settings.harmonics > 0 ? settings.harmonics : (by_tolerance ? 0 : kNonlinearDefaultHarmonics);
  options.hb.harmonic_tolerance = settings.tolerance;
  // With tooth errors the period is P = period_meshes mesh cycles and H counts harmonics of
  // f_mesh/P, so H < P leaves out the mesh frequency itself (issue 12, fixed for the linear HB;
  // on this path the rig with a 5 µm runout at 1800 Hz and the default H = 24 of f_mesh/50
  // returned the runout alone, RMS DTE 3.54 µm = 5/√2 µm, with status success). The
  // --tolerance loop starts at H = 8 and would stop there for the same reason.
  const std::int64_t period = built.model.period_meshes();
  GEARDYN_THROW_UNLESS(
      period == 1 || options.hb.harmonics >= period,
      "--harmonics: the nonlinear harmonic balance of this scene counts harmonics of f_mesh/"
          << period << " (the tooth errors repeat every " << period << " mesh cycles), so H = "
          << (options.hb.harmonics > 0 ? std::to_string(options.hb.harmonics)
                                       : std::string("8, 16, … (--tolerance)"))
          << " does not contain the mesh frequency (harmonic " << period << "); give --harmonics k·"
          << period
          << " for k mesh orders, or drop the tooth errors, or use --linear (mesh orders and "
             "their sidebands, no contact loss)");
  // Folds are located to the tighter of the engine default and the user's tolerance.
  options.continuation.fold_tolerance =
      std::min(options.continuation.fold_tolerance, settings.tolerance);
  options.hb.stability = StabilityMethod(opts.stability);
  options.hb.monodromy_steps = opts.monodromy_steps;
  options.continuation.branch_search = opts.branch_search;
  options.start_hz = frequencies.front();
  options.end_hz = frequencies.back();
  const int n = static_cast<int>(frequencies.size());

  std::vector<std::string> warnings = built.warnings;
  if (options.hb.stability == NhbStabilityMethod::kHill &&
      !MakeSystemNhbProblem(built.model).problem.IsUncondensed()) {
    warnings.push_back(
        "--stability hill: Hill's method needs the uncondensed problem, but the linear DOFs "
        "are condensed onto the mesh coordinates; the monodromy matrix is used instead");
  }

  SystemNhbCurve curve;
  if (n == 1 || options.start_hz == options.end_hz) {
    Summary summary;
    curve.points.push_back(
        SolveSystemNonlinearHb(built.model, options.start_hz, options, &summary));
    curve.harmonics_used = static_cast<int>(curve.points.front().point.harmonics.cols()) - 1;
    curve.period_multiple = static_cast<int>(built.model.period_meshes());
    curve.summary = summary;
  } else {
    // n sets the resolution (see the file comment): ΔΩ per step ≤ (Ω_hi − Ω_lo)/n. The
    // arclength step itself keeps the engine's default bound: a cap of 1/n on the scaled
    // arclength (which counts the change of every harmonic too) put 5 000–7 000 points on the
    // rig's 200-point request (issue 13).
    options.continuation.max_omega_step =
        2.0 * std::numbers::pi * std::abs(options.end_hz - options.start_hz) / n;
    options.continuation.initial_step = std::min(options.continuation.initial_step, 1.0 / n);
    options.continuation.max_points = std::max(options.continuation.max_points, 20 * n);
    auto last_line = std::chrono::steady_clock::now() - std::chrono::hours(1);
    int last_points = 0;
    double last_hz = 0.0;
    if (settings.progress && err) {
      options.continuation.progress = [&](int points, double omega) {
        last_points = points;
        last_hz = omega / (2.0 * std::numbers::pi);
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last_line).count() < kProgressInterval) return;
        last_line = now;
        char line[96];
        std::snprintf(line, sizeof(line), "geardyn hb: %d points, f_m = %.1f Hz\n", points,
                      last_hz);
        err(line);
      };
    }
    options.continuation.cancel = CancelFlag();
    curve = TraceSystemNonlinearHb(built.model, options);
    if (settings.progress && err) {
      char line[96];
      std::snprintf(line, sizeof(line), "geardyn hb: %d points, f_m = %.1f Hz (done)\n",
                    last_points, last_hz);
      err(line);
    }
  }

  NhbRunInfo info;
  info.start_hz = options.start_hz;
  info.end_hz = options.end_hz;
  info.resolution = n;
  info.harmonics_requested = options.hb.harmonics;
  info.tolerance = settings.tolerance;
  info.stability = opts.stability;
  nlohmann::json report = MakeNhbReport(scene.source, info, curve, warnings);
  HbRun run;
  run.nonlinear = true;
  std::vector<std::pair<std::string, std::string>> files;
  if (!out_dir.empty()) {
    files = {{"nhb.json", report.dump(2) + "\n"},
             {"nhb.csv", FormatNhbCsv(curve, opts.stability != "none")},
             {"nhb_rms_dte.svg",
              RenderNhbPlot(curve, "RMS DTE (nonlinear harmonic balance): " + scene.source,
                            opts.stability != "none")}};
  }
  std::string text = FormatNhbText(report);
  Finish(&run, std::move(report), std::move(text), out_dir, files);
  run.exit_code = curve.summary.ok() ? int{kExitOk} : int{kExitNumericalIssue};
  return run;
}

HbRun RunLinearHb(const HbRunSettings& opts, const Scene& scene, const SceneSystem& built,
                  const std::vector<double>& frequencies, const std::string& out_dir,
                  const ProgressLine& err) {
  GEARDYN_THROW_UNLESS(opts.settings.harmonics == 0 || !opts.tolerance_given,
                       "--tolerance: chooses H (H = 8, 16, ... until the RMS DTE changes by at "
                       "most the tolerance) and is not used with a fixed --harmonics "
                           << opts.settings.harmonics << "; give one of them");
  HbOptions options = MakeHbOptions(opts.settings);
  options.cancel = CancelFlag();
  HbProgress progress;
  if (opts.settings.progress && err) {
    progress = [&err](int done, int total) {
      if (done == total || done % std::max(1, total / 20) == 0) {
        err("geardyn hb: " + std::to_string(done) + "/" + std::to_string(total) +
            " mesh frequencies\n");
      }
    };
  }
  const HbSweepResult sweep = SweepHarmonicBalance(built.model, frequencies, options, progress);
  // The Floquet verdict of every point (--stability none: skipped). monodromy → kAuto (exact
  // steps for piecewise-constant K, C; Magnus for smooth ones), hill → Hill's method.
  std::unique_ptr<HbStabilitySweep> stability;
  if (opts.stability != "none" && !Interrupted()) {
    FloquetOptions floquet;
    floquet.method = opts.stability == "hill" ? FloquetMethod::kHill : FloquetMethod::kAuto;
    floquet.tolerance = kLinearStabilityTolerance;
    if (opts.settings.progress && err) err("geardyn hb: Floquet verdicts of the points\n");
    stability =
        std::make_unique<HbStabilitySweep>(ComputeHbStability(built.model, frequencies, floquet));
  }
  nlohmann::json report =
      MakeHbReport(scene.source, opts.settings, sweep, built.warnings, stability.get());
  std::vector<std::pair<std::string, std::string>> files;
  if (!out_dir.empty()) {
    files = {
        {"hb.json", report.dump(2) + "\n"},
        {"hb.csv", FormatHbCsv(sweep, stability.get())},
        {"hb_rms_dte.svg", RenderHbPlot(sweep, "RMS DTE (linear harmonic balance): " + scene.source,
                                        stability.get())}};
  }
  HbRun run;
  std::string text = FormatHbText(report);
  Finish(&run, std::move(report), std::move(text), out_dir, files);
  // An unstable point is a result, not a numerical problem; an undetermined verdict is.
  const bool stability_ok = stability == nullptr || stability->summary.ok();
  run.exit_code = sweep.summary.ok() && stability_ok ? int{kExitOk} : int{kExitNumericalIssue};
  return run;
}

int RunHb(HbCommandOptions& opts, std::ostream& out, std::ostream& err) {
  opts.run.harmonics_given = opts.harmonics_option->count() > 0;
  opts.run.tolerance_given = opts.tolerance_option->count() > 0;
  const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
  const HbRun run = RunHbAnalysis(scene, opts.run, opts.scene.out_dir,
                                  [&err](const std::string& line) { err << line; });
  out << (opts.scene.json ? run.report.dump(2) + "\n" : run.text);
  if (!opts.scene.out_dir.empty() && !opts.scene.json) {
    out << "written to " << opts.scene.out_dir << "\n";
  }
  return run.exit_code;
}

}  // namespace

HbRun RunHbAnalysis(const Scene& scene, const HbRunSettings& opts, const std::string& out_dir,
                    const ProgressLine& progress) {
  // The command line checks these with CLI11; the library API (Python) reaches here directly.
  GEARDYN_THROW_UNLESS(
      opts.stability == "none" || opts.stability == "monodromy" || opts.stability == "hill",
      "--stability: must be none, monodromy or hill, got \"" << opts.stability << "\"");
  GEARDYN_THROW_UNLESS(opts.monodromy_steps >= 0,
                       "--monodromy-steps: must be >= 0, got " << opts.monodromy_steps);
  GEARDYN_THROW_UNLESS(
      opts.branch_search >= 0 && opts.branch_search <= NhbContinuationOptions::kMaxBranchSearch,
      "--branch-search: must be in [0, " << NhbContinuationOptions::kMaxBranchSearch << "], got "
                                         << opts.branch_search);
  // HbSettings::harmonics = 0 means "choose H" (from --tolerance, or the nonlinear default):
  // given on the command line, 0 used to fall silently to that default (issue 16).
  GEARDYN_THROW_UNLESS(!opts.harmonics_given || opts.settings.harmonics >= 1,
                       "--harmonics: must be >= 1 (omit it to choose H from --tolerance), got "
                           << opts.settings.harmonics);
  GEARDYN_THROW_UNLESS(!(opts.nonlinear && opts.settings.linear),
                       "--nonlinear and --linear: give at most one of them");
  const std::vector<double> frequencies =
      ParseMeshFrequencies(opts.settings.mesh_frequency, NominalMeshFrequency(scene));
  SceneSystemOptions system_options;
  system_options.analysis = "hb";  // named if a mass is missing
  // The linear HB takes a runout over a hunting period too long to tabulate as sidebands (sparse
  // harmonics); the nonlinear one samples ε over the period and keeps the table's refusal.
  system_options.runout_form = opts.nonlinear ? RunoutForm::kTable : RunoutForm::kAuto;
  const SceneSystem built = BuildSceneSystem(scene, system_options);
  const bool has_slices = built.model.time_dependence() == TimeDependence::kNonlinear;
  if (HasSeveralMeshFrequencies(built.model)) {
    // A two-stage train: the quasi-periodic HB on the torus of the mesh frequencies, nonlinear
    // (contact loss) with slice meshes unless --linear.
    const std::string name = scene.meshes.empty() ? "NAME" : scene.meshes.front().name;
    GEARDYN_THROW_UNLESS(!opts.nonlinear || has_slices,
                         "--nonlinear: the scene has no slice mesh (contact loss needs the slice "
                         "model); use model = \"slices\" on a mesh, e.g. --set mesh."
                             << name << ".model=\"slices\"");
    return RunQuasiPeriodicHb(opts, scene, built, frequencies, out_dir, progress,
                              has_slices && !opts.settings.linear);
  }
  if (opts.nonlinear) {
    GEARDYN_THROW_UNLESS(has_slices || !scene.oscillator,
                         "--nonlinear: the oscillator has the linear model \""
                             << ToString(scene.oscillator->model)
                             << "\"; the clearance needs backlash = true and model = \"slices\" "
                                "(--set oscillator.model=slices)");
    const std::string name = scene.meshes.empty() ? "NAME" : scene.meshes.front().name;
    GEARDYN_THROW_UNLESS(has_slices,
                         "--nonlinear: the scene has no slice mesh (contact loss needs the slice "
                         "model); use model = \"slices\" on a mesh, e.g. --set mesh."
                             << name << ".model=\"slices\"");
  }
  if (has_slices && !opts.settings.linear) {
    return RunNonlinearHb(opts, scene, built, frequencies, out_dir, progress);
  }
  return RunLinearHb(opts, scene, built, frequencies, out_dir, progress);
}

Command AddHbCommand(CLI::App& app) {
  auto opts = std::make_shared<HbCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "hb", "steady-state DTE, mesh and bearing forces over mesh frequency (harmonic balance)");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option("--mesh-frequency", opts->run.settings.mesh_frequency,
                  "tooth-mesh frequencies [Hz] as lo:hi:n or one value (default 0.2 to 2.5 "
                  "times the scene's, n = 200). Linear: n evenly spaced points. Nonlinear: the "
                  "continuation range; n is its resolution (each step advances at most 1/n of "
                  "the range: at least about n points, more near resonances and folds)");
  opts->harmonics_option =
      cmd->add_option("--harmonics", opts->run.settings.harmonics,
                      "number of harmonics H of the mesh frequency (linear: each with the "
                      "sidebands of the tooth errors, at most 2048; default: from --tolerance; "
                      "nonlinear default: 24; nonlinear with tooth errors repeating every P mesh "
                      "cycles: harmonics of f_mesh/P, at least P)");
  opts->tolerance_option = cmd->add_option(
      "--tolerance", opts->run.settings.tolerance,
      "linear, without --harmonics: relative change of the RMS DTE from H/2 to H accepted "
      "(default 1e-4; meshes at several frequencies: the total order, default 2e-2, the search "
      "stopping before 0.5 GB of factors; an error with --harmonics); "
      "nonlinear, when given without --harmonics: H = 8, 16, ... until the RMS of the top "
      "quarter of the harmonics relative to the RMS is below it");
  cmd->add_flag("--linear", opts->run.settings.linear,
                "linear model even with slice meshes (linearized with every slice loaded, no "
                "contact loss); the only mode for scenes without slice meshes");
  cmd->add_flag("--nonlinear", opts->run.nonlinear,
                "nonlinear model with contact loss and back-flank contact (the default when a "
                "mesh has model = \"slices\"; an error without one)");
  cmd->add_option("--stability", opts->run.stability,
                  "stability of every point. Nonlinear: monodromy (Floquet multipliers of the "
                  "linearization, default), hill (uncondensed problems only, else monodromy) or "
                  "none. Linear: the Floquet verdict of the homogeneous LTV system at each mesh "
                  "frequency (parametric instability), monodromy = the automatic Floquet method "
                  "(default), hill = Hill's method, none = skipped")
      ->check(CLI::IsMember({"none", "monodromy", "hill"}));
  cmd->add_option("--monodromy-steps", opts->run.monodromy_steps,
                  "nonlinear: Magnus steps of the monodromy per period (default max(64, 4H)); "
                  "no effect on spur slice meshes without tooth errors (constant or stepwise "
                  "stiffness), whose monodromy is the exact product over the contact switches "
                  "and stiffness steps; elsewhere |mu| near 1 is first-order in the step: raise "
                  "it (e.g. 256) when the stable/unstable flag flickers")
      ->check(FiniteNumberIn(0, std::numeric_limits<int>::max()));
  cmd->add_option("--branch-search", opts->run.branch_search,
                  "nonlinear: frequencies inside the range (default 8, 0: off, at most 1000) "
                  "where Newton starts from four scaled contact guesses; a solution off the "
                  "traced curve (a detached branch or an isola) is traced both ways and added as "
                  "a new segment (JSON 'segment', new branch numbers)")
      ->check(CLI::Range(0, NhbContinuationOptions::kMaxBranchSearch));
  cmd->add_flag("--progress", opts->run.settings.progress,
                "print the progress on the error stream");
  Command command{cmd, nullptr};
  command.run_with_err = [opts](std::ostream& out, std::ostream& err) {
    return RunHb(*opts, out, err);
  };
  return command;
}

}  // namespace geardyn::app
