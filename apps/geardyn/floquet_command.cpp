// `geardyn floquet SCENE`: the Floquet multipliers of the scene's LTV system at its operating
// point (ComputeFloquet on MakeSystemModel at the first mesh's frequency), printed as text or
// JSON, and written to --out as floquet.json and multipliers.csv.
#include <cmath>
#include <iomanip>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analysis_runs.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

struct FloquetCommandOptions {
  SceneCommandOptions scene;
  FloquetSettings settings;
};

nlohmann::json MakeFloquetReport(const Scene& scene, const std::string& requested,
                                 double mesh_frequency_hz, int num_dofs, const FloquetResult& r,
                                 const std::vector<std::string>& scene_warnings) {
  nlohmann::json multipliers = nlohmann::json::array();
  for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
    const std::complex<double> l = r.multipliers[k];
    const std::complex<double> mu = k < r.exponents.size() ? r.exponents[k] : 0.0;
    multipliers.push_back({{"re", l.real()},
                           {"im", l.imag()},
                           {"abs", std::abs(l)},
                           {"exponent_re", mu.real()},
                           {"exponent_im", mu.imag()}});
  }
  nlohmann::json undamped = nlohmann::json::array();
  for (const UndampedMode& m : r.undamped_modes) {
    undamped.push_back({{"mode", m.index},
                        {"frequency_hz", m.frequency_hz},
                        {"damping_ratio", m.damping_ratio},
                        {"dominant_dof", m.dominant_dof}});
  }
  nlohmann::json approximants = nlohmann::json::array();
  for (const FloquetApproximant& a : r.approximants) {
    approximants.push_back({{"period_meshes", a.period_meshes},
                            {"ratios", a.ratios},
                            {"ratio_error", a.ratio_error},
                            {"max_real_exponent", a.max_real_exponent},
                            {"verdict", ToString(a.verdict)},
                            {"error_estimate", a.error_estimate}});
  }
  nlohmann::json warnings = scene_warnings;
  for (const std::string& w : r.summary.warnings) warnings.push_back(w);
  return {{"scene", scene.source},
          {"num_dofs", num_dofs},
          {"mesh_frequency_hz", mesh_frequency_hz},
          {"period_meshes", r.period_meshes},
          {"period_s", r.period_s},
          {"method_requested", requested},
          {"method_used", ToString(r.method_used)},
          {"max_abs_multiplier", r.max_abs_multiplier},
          {"stability_margin", r.stability_margin},
          // Three-valued like the nonlinear HB's points: null when undetermined, so a script
          // testing `not stable` cannot read an unknown verdict as "unstable".
          {"stable", r.verdict == FloquetVerdict::kUndetermined ? nlohmann::json(nullptr)
                                                                : nlohmann::json(r.stable())},
          {"verdict", ToString(r.verdict)},
          {"marginal", r.marginal},
          {"undamped_modes", undamped},
          {"error_estimate", r.summary.error_estimate},
          {"status", StatusName(r.summary.status)},
          {"message", r.summary.message},
          {"wall_time_s", r.summary.wall_time_s},
          {"counters", r.summary.counters},
          {"warnings", warnings},
          {"approximants", approximants},
          {"multipliers", multipliers}};
}

std::string FormatFloquetText(const nlohmann::json& j) {
  std::ostringstream s;
  s << std::setprecision(10);
  s << "Floquet: " << j["scene"].get<std::string>() << ", " << j["num_dofs"].get<int>()
    << " DOFs, f_m = " << j["mesh_frequency_hz"].get<double>() << " Hz, period "
    << j["period_meshes"].get<long>() << " mesh cycle(s) = " << j["period_s"].get<double>()
    << " s\n"
    << "method: " << j["method_used"].get<std::string>() << " (requested "
    << j["method_requested"].get<std::string>() << "), error estimate "
    << j["error_estimate"].get<double>() << ", status " << j["status"].get<std::string>();
  if (!j["message"].get<std::string>().empty()) s << ": " << j["message"].get<std::string>();
  s << "\nmax|λ| = " << j["max_abs_multiplier"].get<double>() << ", margin "
    << j["stability_margin"].get<double>() << " → " << j["verdict"].get<std::string>();
  if (j["marginal"].get<bool>()) {
    s << ", marginal (undamped modes";
    const nlohmann::json& modes = j["undamped_modes"];
    if (modes.empty()) s << " or a multiplier on the unit circle within the error estimate";
    std::size_t k = 0;
    for (const nlohmann::json& m : modes) {
      if (k == 8) {
        s << ", … " << modes.size() - 8 << " more";
        break;
      }
      s << (k++ == 0 ? ": " : ", ") << "mode " << m["mode"].get<int>() << " "
        << std::setprecision(6) << m["frequency_hz"].get<double>() << " Hz ("
        << m["dominant_dof"].get<std::string>() << ")" << std::setprecision(10);
    }
    s << ")";
  }
  if (j["verdict"].get<std::string>() == "undetermined") {
    s << " (the multipliers or their error estimate cannot be trusted; see the status and "
         "warnings)";
  }
  s << "\n";
  if (!j["approximants"].empty()) {
    s << "incommensurate mesh frequencies, rational approximants (the multipliers are the "
         "last one's):\n  period [cycles]   ratio error   max Re μ [1/s]   verdict\n";
    for (const nlohmann::json& a : j["approximants"]) {
      s << "  " << std::setw(15) << a["period_meshes"].get<long>() << "   " << std::setw(11)
        << std::setprecision(3) << a["ratio_error"].get<double>() << "   " << std::setw(14)
        << std::setprecision(8) << a["max_real_exponent"].get<double>() << "   "
        << a["verdict"].get<std::string>() << "\n"
        << std::setprecision(10);
    }
  }
  s << "  #   Re λ              Im λ              |λ|\n";
  int k = 1;
  for (const nlohmann::json& m : j["multipliers"]) {
    s << std::setw(3) << k++ << "   " << std::setw(16) << m["re"].get<double>() << "  "
      << std::setw(16) << m["im"].get<double>() << "  " << m["abs"].get<double>() << "\n";
  }
  for (const nlohmann::json& w : j["warnings"]) s << "warning: " << w.get<std::string>() << "\n";
  return s.str();
}

std::string MultipliersCsv(const FloquetResult& r) {
  std::ostringstream s;
  s << std::setprecision(17) << "index,re,im,abs,exponent_re,exponent_im\n";
  for (Eigen::Index k = 0; k < r.multipliers.size(); ++k) {
    const std::complex<double> mu = k < r.exponents.size() ? r.exponents[k] : 0.0;
    s << k + 1 << "," << r.multipliers[k].real() << "," << r.multipliers[k].imag() << ","
      << std::abs(r.multipliers[k]) << "," << mu.real() << "," << mu.imag() << "\n";
  }
  return s.str();
}

int RunFloquet(const FloquetCommandOptions& opts, std::ostream& out) {
  // --nev is checked before the scene is read, naming the flag.
  GEARDYN_THROW_UNLESS(opts.settings.nev >= 1, "--nev: must be >= 1, got " << opts.settings.nev);
  const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
  const FloquetRun run = RunFloquetAnalysis(scene, opts.settings, opts.scene.out_dir);
  out << (opts.scene.json ? run.report.dump(2) + "\n" : run.text);
  if (!opts.scene.out_dir.empty() && !opts.scene.json) {
    out << "written to " << opts.scene.out_dir << "\n";
  }
  return run.exit_code;
}

}  // namespace

FloquetRun RunFloquetAnalysis(const Scene& scene, const FloquetSettings& settings,
                              const std::string& out_dir) {
  FloquetOptions options;
  options.method = ParseFloquetMethod(settings.method, "--method");
  GEARDYN_THROW_UNLESS(
      std::isfinite(settings.tolerance) && settings.tolerance > 0.0 && settings.tolerance < 1.0,
      "--tolerance: must be a finite number in (0, 1), got " << settings.tolerance);
  options.tolerance = settings.tolerance;
  options.arpack_nev = settings.nev;
  options.max_approximant_period_meshes = settings.max_approximant_period;
  // --nev is checked here, naming the flag: FloquetOptions names its own field (arpack_nev).
  GEARDYN_THROW_UNLESS(settings.nev >= 1, "--nev: must be >= 1, got " << settings.nev);
  if (scene.meshes.empty() && !scene.oscillator) {
    throw InvalidInput(scene.source + ": the scene has no mesh");
  }
  SceneSystemOptions system_options;
  system_options.analysis = "floquet";  // named if a mass is missing
  // The homogeneous problem M q̈ + C q̇ + K(θ) q = 0 has the period of K and C only: ε is forcing
  // (with coprime tooth counts its table would span the whole hunting period).
  system_options.transmission_error = false;
  const SceneSystem built = BuildSceneSystem(scene, system_options);
  // An oscillator scene: its frequency_ratio Ω (the model's natural frequency is 1 Hz).
  options.mesh_frequency_hz = scene.NominalMeshFrequencyHz();
  if (!(options.mesh_frequency_hz > 0.0)) {
    throw InvalidInput(scene.source +
                       ": the mesh frequency is 0 (operating_point.speed_rpm must be > 0)");
  }
  GEARDYN_THROW_UNLESS(
      options.method != FloquetMethod::kArpackMonodromy ||
          settings.nev <= 2 * built.model.num_dofs(),
      "--nev: must be <= 2n = " << 2 * built.model.num_dofs() << " (the multipliers of the "
                                << built.model.num_dofs() << "-DOF system), got " << settings.nev);
  FloquetRun run;
  run.mesh_frequency_hz = options.mesh_frequency_hz;
  run.result = ComputeFloquet(built.model, options);
  const FloquetResult& result = run.result;
  run.report = MakeFloquetReport(scene, settings.method, options.mesh_frequency_hz,
                                 built.model.num_dofs(), result, built.warnings);
  run.text = FormatFloquetText(run.report);
  if (!out_dir.empty()) {
    WriteOutputFile(out_dir, "floquet.json", run.report.dump(2) + "\n");
    WriteOutputFile(out_dir, "multipliers.csv", MultipliersCsv(result));
  }
  // Exit 1 on any status but success and on an undetermined verdict (scripts test the code).
  run.exit_code = result.summary.ok() && result.verdict != FloquetVerdict::kUndetermined
                      ? int{kExitOk}
                      : int{kExitNumericalIssue};
  return run;
}

Command AddFloquetCommand(CLI::App& app) {
  auto opts = std::make_shared<FloquetCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "floquet",
      "Floquet multipliers, max|λ|, stability margin and verdict of the scene's LTV system");
  AddSceneOptions(cmd, &opts->scene);
  std::vector<std::string> names;
  for (FloquetMethod m : kFloquetMethods) names.push_back(ToString(m));
  cmd->add_option(
         "--method", opts->settings.method,
         "auto, exact_steps, magnus, ode_stepper, hill, modal_projection or arpack_monodromy "
         "(default auto: exact_steps for piecewise-constant stiffness, else magnus on the full "
         "system or modal_projection on the mesh-driven modes, whichever costs less; the "
         "projection is kept only when its max|λ| estimate cannot change the verdict)")
      ->check(CLI::IsMember(names));
  cmd->add_option("--tolerance", opts->settings.tolerance,
                  "error target on the multipliers (default 1e-10; not used by exact_steps)")
      ->check(FiniteNumberIn(0.0, 1.0, true, true));  // FloquetOptions::tolerance's bound
  cmd->add_option("--nev", opts->settings.nev,
                  "arpack_monodromy: number of largest-|λ| multipliers (default 6, <= 2n)");
  cmd->add_option("--max-approximant-period", opts->settings.max_approximant_period,
                  "meshes at incommensurate frequencies (no common period of at most 10^4 "
                  "cycles): the longest common period of the rational approximants analysed "
                  "instead, in mesh cycles (default 1000; 0 refuses such a scene)")
      ->check(CLI::Range(0L, 10000L));
  return {cmd, [opts](std::ostream& out) { return RunFloquet(*opts, out); }};
}

}  // namespace geardyn::app
