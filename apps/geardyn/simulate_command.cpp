// `geardyn simulate SCENE`: time integration of the scene's system (time_response.hpp) — the
// model harmonic balance solves for LTV and slice meshes, and the tooth-contact model — at one
// speed to steady state (default: the scene's operating point), at independent speeds in
// parallel, or as stepped up/down sweeps that carry the state from point to point (both branches
// of a jump); per mean torque (--torque). --quasi-static instead exports the loaded K(θ) and STE
// as a [mesh.parameters] table (quasi_static.hpp, mesh_parameters_export.hpp).
//
// Files in --out (simulate_report.hpp): one run: simulate.json, simulate_dte.csv,
// simulate_energy.csv, simulate_element_forces.csv and simulate_channels.csv (when the model
// gives them); several: simulate.json, simulate_sweep.csv, simulate_rms_dte.svg (with
// --overlay-hb the harmonic-balance curve of the same scene, one panel per torque). The files are
// written whatever the outcome: a failed run (status ≠ success, exit 1) or one interrupted by
// SIGINT (exit 130) keeps what was computed before.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <sstream>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "geardyn/analysis_runs.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/hb_report.hpp"
#include "geardyn/interrupt.hpp"
#include "geardyn/mesh_parameters_export.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/output_files.hpp"
#include "geardyn/overlay_match.hpp"
#include "geardyn/progress_stream.hpp"
#include "geardyn/quasi_static.hpp"
#include "geardyn/simulate_report.hpp"

namespace geardyn::app {
namespace {

// Minimum time between two --progress lines [s].
constexpr double kProgressInterval = 0.5;
// Harmonics of the --overlay-hb nonlinear HB curve (as `geardyn hb`'s nonlinear default).
constexpr int kOverlayHarmonics = 24;
// Points of the --overlay-hb linear HB curve over the sweep's range.
constexpr int kOverlayLinearPoints = 200;
// Low-speed warning: a run that must follow more oscillations of the highest mode than this
// within its fewest periods (EstimateTimeRun: f_max × min_simulated_time_s). Measured on the rig
// at 20 Hz (docs/benchmarks.md "Low speeds"): generalized-α, 902 030 steps for 2 periods, 3.4 s
// user ≈ 1.4 ms per highest-mode cycle, so 1e4 cycles ≈ 14 s before any steady-state test —
// and 1/f_m more below (0.5 Hz: 2.5e5 cycles, minutes).
constexpr double kLowSpeedModeCycles = 1e4;
// High-speed warning: f_m above this multiple of the highest natural frequency.
constexpr double kHighSpeedFactor = 100.0;
// Load warning: a static deflection δ_η above this fraction of the normal base pitch p_bn (rated
// loads give δ ≲ 1e-3 p_bn: ≈ 10–30 µm on module 3–10 mm teeth).
constexpr double kDeflectionPitchFraction = 0.02;

// The command's options: SimulateSettings (analysis_runs.hpp) and the scene's.
struct SimulateOptions : SimulateSettings {
  SceneCommandOptions scene;
  /// The scene's TOML text when it was not read from scene.scene (the Python package); the
  /// --overlay-hb slice matching reloads the scene with overrides.
  std::string scene_text;
};

// The SceneSystemOptions of the time-domain runs: analysis "simulate", and tooth-contact meshes
// (model = "contact", time-domain only) allowed where the scene builder knows them (the field
// arrives with the contact model; the requires-clause keeps this file building without it).
template <typename Options>
void AllowContactMeshes(Options& so) {
  if constexpr (requires { so.allow_contact_meshes = true; }) so.allow_contact_meshes = true;
}
SceneSystemOptions TimeDomainSystemOptions() {
  SceneSystemOptions so;
  so.analysis = "simulate";
  AllowContactMeshes(so);
  return so;
}

void Validate(const SimulateOptions& o) {
  TimeIntegrator integrator;
  GEARDYN_THROW_UNLESS(
      ParseTimeIntegrator(o.integrator, &integrator),
      "--integrator: '" << o.integrator << "' is not one of auto, generalized_alpha, runge_kutta");
  GEARDYN_THROW_UNLESS(std::isfinite(o.tolerance) && o.tolerance >= 1e-14 && o.tolerance <= 1e-2,
                       "--tolerance: the local relative error per step must be in [1e-14, 1e-2], "
                       "got "
                           << o.tolerance);
  GEARDYN_THROW_UNLESS(
      std::isfinite(o.steady_tolerance) && o.steady_tolerance >= 1e-14 && o.steady_tolerance <= 1,
      "--steady-tolerance: the period-to-period change must be in [1e-14, 1], got "
          << o.steady_tolerance);
  GEARDYN_THROW_UNLESS(o.max_periods >= 1 && o.max_periods <= 10000000,
                       "--max-periods: must be in [1, 10000000], got " << o.max_periods);
  GEARDYN_THROW_UNLESS(o.record_periods >= 1 && o.record_periods <= 1000,
                       "--record-periods: must be in [1, 1000], got " << o.record_periods);
  GEARDYN_THROW_UNLESS(o.samples_per_period >= 4 && o.samples_per_period <= 65536,
                       "--samples-per-period: must be in [4, 65536], got " << o.samples_per_period);
  // Below 1e-6 a period needs more than 1e6 steps: the run exhausts max_steps (1e8) after
  // minutes of silence instead of giving a result (1e-9 tried: a 10-minute hang, then a failure).
  GEARDYN_THROW_UNLESS(std::isfinite(o.max_step) && o.max_step >= 1e-6 && o.max_step <= 1.0,
                       "--max-step: the largest time step as a fraction of the mesh period must "
                       "be in [1e-6, 1] (at most 1e6 steps per period; tighten --tolerance for "
                       "accuracy instead), got "
                           << o.max_step);
  GEARDYN_THROW_UNLESS(o.threads >= 0 && o.threads <= 1024,
                       "--threads: must be in [0, 1024] (0: OpenMP's default), got " << o.threads);
  for (const double t : o.torques) {
    GEARDYN_THROW_UNLESS(std::isfinite(t), "--torque: " << t << " is not a finite torque [N·m]");
  }
  GEARDYN_THROW_UNLESS(o.torques.size() <= 100,
                       "--torque: at most 100 torques, got " << o.torques.size());
  GEARDYN_THROW_UNLESS(!(o.quasi_static && (!o.sweep.empty() || o.overlay_hb)),
                       "--quasi-static: a static slow roll; --sweep and --overlay-hb do not apply");
  GEARDYN_THROW_UNLESS(!(o.quasi_static && !o.mesh_frequency.empty()),
                       "--quasi-static: a static slow roll has no mesh frequency; drop "
                       "--mesh-frequency");
}

// The scene at mean torque T [N·m]: the operating-point torque set to T and every [[load]]
// torque scaled by T/T₀ (T₀ the scene's), so that a balanced scene stays balanced.
Scene AtTorque(const Scene& scene, double torque) {
  Scene out = scene;
  const double t0 = scene.operating_point.torque;
  if (torque == t0) return out;
  const bool has_loads =
      std::any_of(scene.loads.begin(), scene.loads.end(), [](const auto& l) { return l.torque; });
  GEARDYN_THROW_UNLESS(t0 != 0.0 || !has_loads,
                       "--torque: the scene's operating_point.torque is 0, so its [[load]] "
                       "torques cannot be scaled to "
                           << torque << " N·m; set them with --set");
  for (auto& load : out.loads) load.torque *= torque / t0;
  out.operating_point.torque = torque;
  return out;
}

TimeResponseOptions MakeResponseOptions(const SimulateOptions& o) {
  TimeResponseOptions r;
  ParseTimeIntegrator(o.integrator, &r.integration.integrator);
  r.integration.relative_tolerance = o.tolerance;
  r.integration.samples_per_period = o.samples_per_period;
  r.integration.max_step_fraction = o.max_step;
  r.steady.tolerance = o.steady_tolerance;
  r.steady.max_periods = o.max_periods;
  r.steady.min_periods = std::min(r.steady.min_periods, o.max_periods);
  r.steady.record_periods = o.record_periods;
  r.steady.use_symmetry = !o.full_period;
  std::string why;
  GEARDYN_THROW_UNLESS(r.IsValid(&why), why);
  return r;
}

std::string TorqueSuffix(const std::vector<double>& torques, double torque) {
  if (torques.size() <= 1) return "";
  char text[48];
  std::snprintf(text, sizeof(text), "_%gNm", torque);
  return text;
}

// The model with every contact (NonlinearMeshCore) mesh replaced by the slice model of the same
// pair, for the HB overlay; nullopt (and a warning) when the scene cannot be built that way.
bool HasNonlinearCore(const SystemModel& model) {
  for (const SystemMesh& m : model.meshes()) {
    if (std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(m.core)) return true;
  }
  return false;
}

// The HB curve of one torque over [lo, hi]: nonlinear HB (slice meshes) or linear HB.
HbOverlay ComputeOverlay(const SimulateOptions& o, const Scene& scene_t, double torque,
                         const std::vector<double>& frequencies, std::vector<std::string>* warnings,
                         std::ostream& err) {
  HbOverlay overlay;
  overlay.torque_nm = torque;
  SceneSystemOptions so;
  so.analysis = "hb";
  SystemModel model = BuildSceneSystem(scene_t, TimeDomainSystemOptions()).model;
  if (HasNonlinearCore(model)) {
    // The slice model of the same pair matched to the contact model at this load
    // (overlay_match.hpp: K̄ from both quasi-static rolls, c_m from the contact law's damping at
    // the mean contact load), as the issue's Kim figures compare.
    const auto build = [&](const std::vector<std::string>& extra) {
      std::vector<std::string> overrides = o.scene.overrides;
      overrides.insert(overrides.end(), extra.begin(), extra.end());
      const Scene variant = o.scene_text.empty()
                                ? LoadScene(o.scene.scene, overrides)
                                : ParseScene(o.scene_text, o.scene.scene, overrides);
      return BuildSceneSystem(AtTorque(variant, torque), so).model;
    };
    try {
      if (o.progress) err << "geardyn simulate: --overlay-hb: matching the slice model\n";
      overlay.matches = MatchSlicesToContact(model, scene_t, build, warnings);
      model = build(MatchedSliceOverrides(overlay.matches));
    } catch (const InvalidInput& e) {
      warnings->push_back(std::string("--overlay-hb: the slice model matched to the contact "
                                      "model cannot be built, no overlay: ") +
                          e.what());
      return overlay;
    }
  }
  const double lo = *std::min_element(frequencies.begin(), frequencies.end());
  const double hi = *std::max_element(frequencies.begin(), frequencies.end());
  if (o.progress) err << "geardyn simulate: --overlay-hb at " << torque << " N·m\n";
  if (model.time_dependence() == TimeDependence::kNonlinear) {
    overlay.label = overlay.matches.empty() ? "nonlinear HB" : "nonlinear HB (matched slices)";
    SystemNhbOptions nhb;
    nhb.hb.harmonics = kOverlayHarmonics;
    nhb.start_hz = lo;
    nhb.end_hz = hi;
    nhb.continuation.max_omega_step = 2.0 * std::numbers::pi * (hi - lo) / kOverlayLinearPoints;
    const SystemNhbCurve curve = TraceSystemNonlinearHb(model, nhb);
    for (const SystemNhbPoint& p : curve.points) {
      overlay.frequency.push_back(p.mesh_frequency_hz);
      const bool ok = p.point.status == Status::kSuccess && !p.meshes.empty();
      overlay.rms_dte.push_back(ok ? p.meshes.front().rms_dte : std::nan(""));
    }
    if (!curve.summary.ok()) {
      warnings->push_back("--overlay-hb: nonlinear HB at " + std::to_string(torque) + " N·m: " +
                          StatusName(curve.summary.status) + ": " + curve.summary.message);
    }
  } else {
    overlay.label = "linear HB";
    std::vector<double> grid(kOverlayLinearPoints);
    for (int i = 0; i < kOverlayLinearPoints; ++i) {
      grid[i] = lo + (hi - lo) * i / (kOverlayLinearPoints - 1);
    }
    const HbSweepResult sweep = SweepHarmonicBalance(model, grid, HbOptions{});
    for (const HbResult& p : sweep.points) {
      overlay.frequency.push_back(p.mesh_frequency_hz);
      const bool ok = p.summary.ok() && !p.meshes.empty();
      overlay.rms_dte.push_back(ok ? p.meshes.front().rms_dte : std::nan(""));
    }
  }
  return overlay;
}

// Without --progress, a run still reports on `err` once it has been quiet this long, and then
// at this interval [s]: a run of minutes (a 100-DOF scene at 3000 periods) must not look hung.
constexpr double kQuietProgressInterval = 10.0;

// Progress lines on `err`: with --progress at most one per kProgressInterval; without, at most
// one per kQuietProgressInterval, the first kQuietProgressInterval after the command started.
TimeProgress MakeProgress(const SimulateOptions& o, std::ostream& err, double torque,
                          std::chrono::steady_clock::time_point start) {
  const double interval = o.progress ? kProgressInterval : kQuietProgressInterval;
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(
      o.progress ? start - std::chrono::hours(1) : start);
  const bool verbose = o.progress;
  return [&err, last, torque, interval, verbose](double fraction, const std::string& note) {
    const auto now = std::chrono::steady_clock::now();
    if ((fraction < 1.0 || !verbose) &&
        std::chrono::duration<double>(now - *last).count() < interval) {
      return;
    }
    *last = now;
    char line[64];
    std::snprintf(line, sizeof(line), "geardyn simulate: %g N·m: %5.1f %% ", torque,
                  100.0 * fraction);
    err << line << note << "\n";
  };
}

// The pre-run checks of one torque (EstimateTimeRun at the lowest and highest mesh frequency):
// a run too long for its speed, a speed far above every mode, a load beyond the teeth's scale.
std::vector<std::string> PreRunWarnings(const Scene& scene_t, const SystemModel& model,
                                        const std::vector<double>& frequencies,
                                        const TimeResponseOptions& options, double torque) {
  const double lo = *std::min_element(frequencies.begin(), frequencies.end());
  const double hi = *std::max_element(frequencies.begin(), frequencies.end());
  const TimeRunEstimate e = EstimateTimeRun(model, lo, options);
  std::vector<std::string> out;
  char text[640];
  if (!e.summary.ok()) {
    std::snprintf(text, sizeof(text),
                  "%g N·m: the pre-run checks could not solve the static state: %s", torque,
                  e.summary.message.c_str());
    out.emplace_back(text);
    return out;
  }
  if (e.highest_mode_cycles > kLowSpeedModeCycles) {
    std::snprintf(text, sizeof(text),
                  "mesh frequency %g Hz is very low: a run to steady state integrates at least "
                  "%ld periods (%.3g s) holding %.3g oscillations of the highest mode (%.4g Hz), "
                  "more than %.0e — expect minutes or more; at such speeds the response is "
                  "quasi-static: `geardyn simulate --quasi-static` gives that limit (f_m → 0) in "
                  "seconds",
                  lo, e.min_periods, e.min_simulated_time_s, e.highest_mode_cycles,
                  e.highest_frequency_hz, kLowSpeedModeCycles);
    out.emplace_back(text);
  }
  if (hi > kHighSpeedFactor * e.highest_frequency_hz) {
    std::snprintf(text, sizeof(text),
                  "mesh frequency %g Hz is %.3g times the highest natural frequency of the "
                  "system (%.4g Hz): every mode responds quasi-statically to its inertia, the "
                  "teeth barely move — far outside any gear's operating range (check the units: "
                  "mesh frequency in Hz)",
                  hi, hi / e.highest_frequency_hz, e.highest_frequency_hz);
    out.emplace_back(text);
  }
  for (std::size_t k = 0; k < e.static_deflection.size(); ++k) {
    const std::string& name = model.meshes()[k].name;
    const auto def = std::find_if(scene_t.meshes.begin(), scene_t.meshes.end(),
                                  [&](const MeshDef& m) { return m.name == name; });
    if (def == scene_t.meshes.end()) continue;
    const double pitch = def->geometry.normal_base_pitch;
    const double delta = std::abs(e.static_deflection[k]);
    if (pitch > 0.0 && delta > kDeflectionPitchFraction * pitch) {
      const double backlash = def->geometry.backlash_normal;
      std::snprintf(text, sizeof(text),
                    "%g N·m: mesh %s deflects %.4g µm statically, %.3g %% of its normal base "
                    "pitch (%.4g mm)%s — beyond the elastic range of gear teeth (rated loads give "
                    "≲ 0.1 %%); the results are not physical (check the torque's units: N·m)",
                    torque, name.c_str(), 1e6 * delta, 100.0 * delta / pitch, 1e3 * pitch,
                    backlash > 0.0 && delta > backlash ? " and exceeds the backlash" : "");
      out.emplace_back(text);
    }
  }
  return out;
}

int RunQuasiStatic(const SimulateOptions& o, const Scene& scene, const std::vector<double>& torques,
                   std::string* text_out, std::ostream& out) {
  nlohmann::json report = {{"scene", scene.source}, {"mode", "quasi_static"}};
  nlohmann::json runs = nlohmann::json::array();
  std::string text;
  std::vector<std::pair<std::string, std::string>> files;
  bool ok = true;
  for (const double torque : torques) {
    const Scene scene_t = AtTorque(scene, torque);
    const SceneSystem built = BuildSceneSystem(scene_t, TimeDomainSystemOptions());
    std::vector<double> b;
    for (const MeshDef& m : scene_t.meshes) b.push_back(m.geometry.face_width / 2.0);
    const QuasiStaticResult qs = ComputeQuasiStatic(built.model, b, o.samples_per_period);
    ok = ok && qs.summary.ok();
    std::string toml, set, csv = "theta_rad";
    nlohmann::json meshes = nlohmann::json::array();
    for (const QuasiStaticMesh& m : qs.meshes) {
      const MeshParameterSamples& p = m.parameters;
      if (p.stiffness.empty()) {  // a failed roll: this mesh was not reached
        meshes.push_back({{"name", p.mesh}, {"samples", 0}});
        continue;
      }
      // A table holds one whole mesh cycle: a failed (partial) roll writes none.
      if (static_cast<int>(p.stiffness.size()) == o.samples_per_period) {
        std::ostringstream head;
        head << "geardyn simulate --quasi-static " << scene.source << " at " << torque << " N·m";
        toml += FormatMeshParametersToml(p, {head.str()}) + "\n";
        set += FormatMeshParametersOverride(p) + "\n";
      }
      const auto [kmin, kmax] = std::minmax_element(p.stiffness.begin(), p.stiffness.end());
      const auto [smin, smax] = std::minmax_element(m.loaded_ste.begin(), m.loaded_ste.end());
      double kmean = 0.0;
      for (const double k : p.stiffness) kmean += k / static_cast<double>(p.stiffness.size());
      meshes.push_back({{"name", p.mesh},
                        {"mean_stiffness_n_per_m", kmean},
                        {"min_stiffness_n_per_m", *kmin},
                        {"max_stiffness_n_per_m", *kmax},
                        {"peak_to_peak_loaded_ste_m", *smax - *smin},
                        {"stiffness_n_per_m", p.stiffness},
                        {"loaded_ste_m", m.loaded_ste},
                        {"transmission_error_m", p.transmission_error},
                        {"force_n", m.force}});
      char line[200];
      std::snprintf(line, sizeof(line),
                    "%g N·m, mesh %s: K mean %.6g N/m (min %.6g, max %.6g), loaded STE p-p "
                    "%.6g µm\n",
                    torque, p.mesh.c_str(), kmean, *kmin, *kmax, 1e6 * (*smax - *smin));
      text += line;
      csv += "," + p.mesh + ":stiffness_n_per_m," + p.mesh + ":stiffness_h_n," + p.mesh +
             ":stiffness_mu_b2_nm," + p.mesh + ":loaded_ste_m," + p.mesh + ":te_eta_m," + p.mesh +
             ":force_n";
    }
    csv += "\n";
    // Rows: the samples every mesh has (all of them unless the roll failed).
    int s_count = o.samples_per_period;
    for (const QuasiStaticMesh& m : qs.meshes) {
      s_count = std::min(s_count, static_cast<int>(m.loaded_ste.size()));
    }
    for (int s = 0; s < s_count; ++s) {
      char cell[40];
      std::snprintf(cell, sizeof(cell), "%.17g", 2.0 * std::numbers::pi * s / o.samples_per_period);
      csv += cell;
      for (const QuasiStaticMesh& m : qs.meshes) {
        const MeshParameterSamples& p = m.parameters;
        for (const double v : {p.stiffness[s], p.stiffness_h[s], p.stiffness_mu_b2[s],
                               m.loaded_ste[s], p.transmission_error[s], m.force[s]}) {
          std::snprintf(cell, sizeof(cell), ",%.17g", v);
          csv += cell;
        }
      }
      csv += "\n";
    }
    std::vector<std::string> warnings = built.warnings;
    warnings.insert(warnings.end(), qs.summary.warnings.begin(), qs.summary.warnings.end());
    runs.push_back({{"torque_nm", torque},
                    {"status", StatusName(qs.summary.status)},
                    {"message", qs.summary.message},
                    {"samples", o.samples_per_period},
                    {"wall_time_s", qs.summary.wall_time_s},
                    {"warnings", warnings},
                    {"meshes", meshes}});
    if (!qs.summary.ok()) {
      text += "status: " + std::string(StatusName(qs.summary.status)) + " (" + qs.summary.message +
              ")\n";
    }
    for (const std::string& w : warnings) text += "warning: " + w + "\n";
    const std::string suffix = TorqueSuffix(torques, torque);
    files.push_back({"mesh_parameters" + suffix + ".toml", toml});
    files.push_back({"mesh_parameters_set" + suffix + ".txt", set});
    files.push_back({"quasi_static" + suffix + ".csv", csv});
  }
  report["runs"] = runs;
  report["status"] = ok ? "success" : "not_converged";
  const std::string json_text = report.dump(2) + "\n";
  files.push_back({"quasi_static.json", json_text});
  out << (o.scene.json ? json_text : text);
  if (text_out != nullptr) *text_out = text;
  if (!o.scene.out_dir.empty()) {
    for (const auto& [name, content] : files) WriteOutputFile(o.scene.out_dir, name, content);
    if (!o.scene.json) out << "written to " << o.scene.out_dir << "\n";
  }
  return ok ? int{kExitOk} : int{kExitNumericalIssue};
}

// The run on a loaded scene; `text_out` and `history_out` (may be null) receive the text report
// and a single run's response (its histories).
int RunSimulateScene(const SimulateOptions& o, const Scene& scene, std::ostream& out,
                     std::ostream& err, std::string* text_out,
                     std::shared_ptr<const TimeResponse>* history_out) {
  Validate(o);
  const auto start = std::chrono::steady_clock::now();
  GEARDYN_THROW_UNLESS(!scene.oscillator || (o.torques.empty() && !o.quasi_static),
                       (o.quasi_static ? "--quasi-static" : "--torque")
                           << ": an oscillator scene has no torque or slow roll (its load is "
                              "oscillator.mean_force and alternating_force; set them with --set)");
  const std::vector<double> torques =
      o.torques.empty() ? std::vector<double>{scene.operating_point.torque} : o.torques;
  if (o.quasi_static) return RunQuasiStatic(o, scene, torques, text_out, out);

  std::vector<double> frequencies;
  if (o.mesh_frequency.empty()) {
    const double nominal = scene.NominalMeshFrequencyHz();
    GEARDYN_THROW_UNLESS(nominal > 0.0,
                         "--mesh-frequency: required (the scene's operating speed is 0)");
    frequencies = {nominal};
  } else {
    frequencies = ParseMeshFrequencies(o.mesh_frequency, 0.0);
  }
  SimulateMode mode = SimulateMode::kSingle;
  if (frequencies.size() > 1)
    mode = o.sweep.empty() ? SimulateMode::kIndependent : SimulateMode::kSweep;
  GEARDYN_THROW_UNLESS(o.sweep.empty() || mode == SimulateMode::kSweep,
                       "--sweep: needs a range of mesh frequencies, --mesh-frequency lo:hi:n with "
                       "n >= 2");
  GEARDYN_THROW_UNLESS(!o.overlay_hb || mode != SimulateMode::kSingle,
                       "--overlay-hb: draws the HB curve over a range of mesh frequencies; give "
                       "--mesh-frequency lo:hi:n with n >= 2");
  const TimeResponseOptions response_options = MakeResponseOptions(o);

  SimulateRunInfo info;
  info.scene = scene.source;
  info.mode = mode;
  info.integrator = o.integrator;
  info.tolerance = o.tolerance;
  info.steady_tolerance = o.steady_tolerance;
  info.max_periods = o.max_periods;
  info.record_periods = o.record_periods;

  std::vector<std::string> mesh_names;
  std::vector<SimulatePoint> points;
  std::vector<std::string> warnings;
  std::vector<HbOverlay> overlays;
  std::unique_ptr<TimeResponse> single;
  std::unique_ptr<SystemModel> single_model;
  std::vector<std::pair<double, Summary>> summaries;
  for (const double torque : torques) {
    if (Interrupted()) break;
    const Scene scene_t = AtTorque(scene, torque);
    const SceneSystem built = BuildSceneSystem(scene_t, TimeDomainSystemOptions());
    for (const std::string& w : built.warnings) {
      if (std::find(warnings.begin(), warnings.end(), "scene: " + w) == warnings.end()) {
        warnings.push_back("scene: " + w);
      }
    }
    mesh_names.clear();
    for (const SystemMesh& m : built.model.meshes()) mesh_names.push_back(m.name);
    for (const std::string& w :
         PreRunWarnings(scene_t, built.model, frequencies, response_options, torque)) {
      // Printed before the run starts (a long run must not be silent about why).
      if (!o.scene.json) err << "geardyn simulate: warning: " << w << "\n";
      warnings.push_back(w);
    }
    const TimeProgress progress = MakeProgress(o, err, torque, start);
    if (mode == SimulateMode::kSingle) {
      TimeResponse r = SimulateSteadyState(built.model, frequencies.front(), response_options,
                                           progress, CancelFlag());
      SimulatePoint p{torque,  "single", ToSweepPoint(r), ToString(r.integrator_used),
                      r.steps, r.events};
      points.push_back(p);
      for (const std::string& w : r.summary.warnings) warnings.push_back(w);
      summaries.emplace_back(torque, r.summary);
      if (torques.size() == 1) {
        single = std::make_unique<TimeResponse>(std::move(r));
        single_model = std::make_unique<SystemModel>(built.model);
      }
    } else if (mode == SimulateMode::kIndependent) {
      const std::vector<TimeResponse> runs = SimulateSpeeds(
          built.model, frequencies, response_options, o.threads, progress, CancelFlag());
      for (const TimeResponse& r : runs) {
        points.push_back({torque, "independent", ToSweepPoint(r), ToString(r.integrator_used),
                          r.steps, r.events});
        for (const std::string& w : r.summary.warnings) {
          if (std::find(warnings.begin(), warnings.end(), w) == warnings.end()) {
            warnings.push_back(w);
          }
        }
      }
    } else {
      TimeSweepOptions sweep_options;
      sweep_options.response = response_options;
      sweep_options.up = o.sweep != "down";
      sweep_options.down = o.sweep != "up";
      const TimeSweep sweep =
          SimulateSweep(built.model, frequencies, sweep_options, progress, CancelFlag());
      for (const TimeSweepPoint& p : sweep.points) {
        points.push_back({torque, ToString(p.branch), p, "", -1, -1});
      }
      for (const std::string& w : sweep.summary.warnings) warnings.push_back(w);
      summaries.emplace_back(torque, sweep.summary);
    }
    if (o.overlay_hb && !Interrupted()) {
      overlays.push_back(ComputeOverlay(o, scene_t, torque, frequencies, &warnings, err));
    }
  }
  info.interrupted = Interrupted();
  info.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json report =
      MakeSimulateReport(info, mesh_names, points, warnings, single.get(), summaries);
  if (single != nullptr) {
    // Where the histories come from (a failed or cancelled run keeps its last transient period).
    report["run"]["history"] = single->history_from_transient
                                   ? "last_transient_period (not steady: the run failed or was "
                                     "cancelled before steady state)"
                               : single->steady == SteadyVerdict::kSteady ? "steady"
                               : single->time.size() > 0                  ? "not_steady"
                                                                          : "none";
  }
  if (!overlays.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const HbOverlay& ov : overlays) {
      nlohmann::json matched = nlohmann::json::array();
      for (const SliceMatch& m : ov.matches) {
        matched.push_back({{"mesh", m.mesh},
                           {"contact_mean_stiffness_n_per_m", m.contact_mean_stiffness},
                           {"mean_force_n", m.mean_force},
                           {"mean_contacts", m.mean_contacts},
                           {"stiffness_per_length_n_per_m2", m.stiffness_per_length},
                           {"damping_n_s_per_m", m.damping}});
      }
      list.push_back({{"torque_nm", ov.torque_nm},
                      {"label", ov.label},
                      {"points", ov.frequency.size()},
                      {"matched_slice_model", matched}});
    }
    report["overlays"] = list;
  }
  const std::string json_text = report.dump(2) + "\n";
  const std::string text = FormatSimulateText(report);
  out << (o.scene.json ? json_text : text);
  if (text_out != nullptr) *text_out = text;
  if (!o.scene.out_dir.empty()) {
    const std::string& dir = o.scene.out_dir;
    WriteOutputFile(dir, "simulate.json", json_text);
    if (single != nullptr) {
      WriteOutputFile(dir, "simulate_dte.csv",
                      FormatDteHistoryCsv(*single, response_options.initial_phase));
      WriteOutputFile(dir, "simulate_energy.csv", FormatEnergyCsv(*single));
      const std::string elements = FormatElementForceCsv(*single_model, *single);
      if (!elements.empty()) WriteOutputFile(dir, "simulate_element_forces.csv", elements);
      const std::string channels =
          FormatChannelHistoryCsv(*single, response_options.integration.channel_decimation);
      if (!channels.empty()) WriteOutputFile(dir, "simulate_channels.csv", channels);
    } else {
      WriteOutputFile(dir, "simulate_sweep.csv", FormatSimulateSweepCsv(mesh_names, points));
      WriteOutputFile(dir, "simulate_rms_dte.svg",
                      RenderSimulatePlot("RMS DTE (time integration): " + scene.source, mesh_names,
                                         points, overlays));
    }
    if (!o.scene.json) out << "written to " << dir << "\n";
  }
  if (history_out != nullptr && single != nullptr) *history_out = std::move(single);
  if (info.interrupted) {
    err << "geardyn simulate: interrupted (SIGINT); the results computed so far were "
        << (o.scene.out_dir.empty() ? std::string("printed") : "written to " + o.scene.out_dir)
        << "\n";
    return kExitInterrupted;
  }
  return report["status"] == "success" ? int{kExitOk} : int{kExitNumericalIssue};
}

int RunSimulate(const SimulateOptions& o, std::ostream& out, std::ostream& err) {
  Validate(o);  // bad options fail before the scene is read
  const Scene scene = LoadScene(o.scene.scene, o.scene.overrides);
  return RunSimulateScene(o, scene, out, err, nullptr, nullptr);
}

}  // namespace

SimulateRun RunSimulateAnalysis(const Scene& scene, const std::string& scene_text,
                                const SimulateSettings& settings, const std::string& out_dir,
                                const ProgressLine& progress) {
  SimulateOptions o;
  static_cast<SimulateSettings&>(o) = settings;
  o.scene.scene = scene.source;
  o.scene_text = scene_text;
  o.scene.out_dir = out_dir;
  o.scene.json = true;  // `out` receives the report JSON alone
  std::ostringstream out;
  ProgressStream err(progress);
  SimulateRun run;
  run.exit_code = RunSimulateScene(o, scene, out, err, &run.text, &run.history);
  run.initial_phase = MakeResponseOptions(o).initial_phase;
  run.report = nlohmann::json::parse(out.str());
  return run;
}

Command AddSimulateCommand(CLI::App& app) {
  auto opts = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "time integration to steady state: DTE, contact and bearing forces, energy balance; "
      "stepped up/down sweeps; quasi-static K(θ) export");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option("--mesh-frequency", opts->mesh_frequency,
                  "tooth-mesh frequency [Hz]: one value, or lo:hi:n for n evenly spaced ones "
                  "(default: the scene's operating point, one run)");
  cmd->add_option("--sweep", opts->sweep,
                  "with lo:hi:n: a stepped sweep carrying the state from point to point (up = "
                  "increasing, down = decreasing, both); default: independent runs from the "
                  "static equilibrium, in parallel")
      ->check(CLI::IsMember({"up", "down", "both"}));
  cmd->add_option("--torque", opts->torques,
                  "mean torques T [N·m] of the operating point, comma-separated (default: the "
                  "scene's); each [[load]] torque is scaled by T over the scene's torque")
      ->delimiter(',');
  cmd->add_option("--integrator", opts->integrator,
                  "auto (default: explicit runge_kutta unless the system is stiff, then "
                  "generalized_alpha), generalized_alpha (implicit, Newton), runge_kutta (GSL "
                  "rk8pd)");
  cmd->add_option("--tolerance", opts->tolerance,
                  "local relative error per time step [-], in [1e-14, 1e-2] (default 1e-8)");
  cmd->add_option("--steady-tolerance", opts->steady_tolerance,
                  "steady state: relative period-to-period change of the state and of the RMS "
                  "DTE, 3 periods in a row [-], in [1e-14, 1] (default 1e-6)");
  cmd->add_option("--max-periods", opts->max_periods,
                  "periods integrated at most before steady state, in [1, 10000000] (default "
                  "3000; reached: status not_converged, exit 1, files kept)");
  cmd->add_option("--record-periods", opts->record_periods,
                  "periods recorded after steady state, in [1, 1000] (default 1)");
  cmd->add_flag("--full-period", opts->full_period,
                "steady test over the model's full period (identical tooth bodies: lcm(z1, z2) "
                "mesh cycles) instead of the symmetry period with the tooth shift (1 cycle)");
  cmd->add_option("--samples-per-period", opts->samples_per_period,
                  "output samples per mesh period, in [4, 65536] (default 64); --quasi-static: "
                  "the mesh phases of the table, at most 4096");
  cmd->add_option("--max-step", opts->max_step,
                  "largest time step as a fraction of the mesh period [-], in [1e-6, 1] (default "
                  "0.05)");
  cmd->add_option("--threads", opts->threads,
                  "threads of independent speeds (OpenMP), 0 = all cores (default)");
  cmd->add_flag("--quasi-static", opts->quasi_static,
                "slow roll under load: the loaded STE and K(θ) of every mesh, written as "
                "[mesh.parameters] tables (mesh_parameters.toml) for an LTV mesh");
  cmd->add_flag("--overlay-hb", opts->overlay_hb,
                "with a range: draw the harmonic-balance curve of the same scene in the SVG "
                "(nonlinear HB for slice meshes and, via model = \"slices\", for contact "
                "meshes; linear HB otherwise)");
  cmd->add_flag(
      "--progress", opts->progress,
      "print the progress on the error stream every 0.5 s (without it: every 10 s once a run "
      "has taken 10 s)");
  Command command{cmd, nullptr};
  command.run_with_err = [opts](std::ostream& out, std::ostream& err) {
    return RunSimulate(*opts, out, err);
  };
  return command;
}

}  // namespace geardyn::app
