// `geardyn campbell SCENE --speed lo:hi:n`: natural frequencies against speed with the gyroscopic
// and carrier-frame terms (speed_terms.hpp, campbell.hpp), tracked by MAC, with the excitation
// orders of every mesh and shaft, their crossings and the divergence and flutter speeds.
#include <cmath>
#include <memory>
#include <sstream>

#include "geardyn/analyses/campbell.hpp"
#include "geardyn/analyses/mean_system.hpp"
#include "geardyn/analysis_runs.hpp"
#include "geardyn/campbell_report.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/models/system/speed_terms.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

struct CampbellCommandOptions {
  SceneCommandOptions scene;
  CampbellSettings settings;
};

int RunCampbell(const CampbellCommandOptions& opts, std::ostream& out) {
  const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
  const CampbellRun run = RunCampbellAnalysis(scene, opts.settings, opts.scene.out_dir);
  out << (opts.scene.json ? run.report.dump(2) + "\n" : run.text);
  if (!opts.scene.out_dir.empty() && !opts.scene.json) {
    out << "written to " << opts.scene.out_dir << "\n";
  }
  return run.exit_code;
}

}  // namespace

CampbellRun RunCampbellAnalysis(const Scene& scene, const CampbellSettings& settings,
                                const std::string& out_dir) {
  const CampbellSweep sweep = MakeCampbellSweep(scene, settings);
  const std::vector<CampbellExcitation> excitations =
      MakeCampbellExcitations(scene, settings.orders);
  GEARDYN_THROW_UNLESS(
      std::isfinite(settings.max_frequency_hz) && settings.max_frequency_hz >= 0,
      "--max-frequency: must be a finite frequency >= 0 [Hz], got " << settings.max_frequency_hz);
  SceneSystemOptions system_options;
  system_options.transmission_error = false;
  system_options.analysis = "campbell";
  system_options.mesh_preload = settings.loaded;
  const SceneSystem built = BuildSceneSystem(scene, system_options);
  const MeanSystemMatrices mean = AssembleMeanSystemMatrices(built.model);
  CampbellProblem problem;
  problem.mass = MatrixX(mean.mass);
  problem.stiffness = MatrixX(mean.stiffness);
  problem.damping = settings.undamped ? MatrixX::Zero(problem.mass.rows(), problem.mass.cols())
                                      : MatrixX(mean.damping);
  SpeedTermsOptions terms_options;
  terms_options.carrier_frame = !settings.no_carrier_frame;
  terms_options.spin_gyroscopics = !settings.no_spin;
  const SpeedTerms terms =
      BuildSpeedTerms(scene, built, problem.stiffness, MatrixX(mean.damping), terms_options);
  problem.gyroscopic = terms.gyroscopic;
  problem.speed_stiffness = terms.stiffness;
  problem.dofs = built.model.dof_map();
  problem.excitations = excitations;
  CampbellOptions options;
  options.speeds = sweep.reference_speeds;
  CampbellRun run;
  run.result = ComputeCampbell(problem, options);
  std::vector<int> kept;
  for (int t = 0; t < static_cast<int>(run.result.tracks.size()); ++t) {
    const double f0 = run.result.tracks[static_cast<std::size_t>(t)].frequency_hz.front();
    if (settings.max_frequency_hz == 0.0 || f0 <= settings.max_frequency_hz) kept.push_back(t);
  }
  std::vector<std::string> notes = terms.notes;
  if (settings.undamped) notes.push_back("no damping (--undamped)");
  for (const MeshPreload& p : built.mesh_preloads) {
    std::ostringstream note;
    note << "mesh preload (--loaded) of mesh '" << p.mesh << "': F̄ = " << p.force
         << " N, κ = " << p.coefficient << " N/m";
    notes.push_back(note.str());
  }
  for (const std::string& w : built.warnings) run.result.summary.warnings.push_back("scene: " + w);
  for (const std::string& w : mean.warnings) run.result.summary.warnings.push_back("scene: " + w);
  run.report = MakeCampbellReport(scene.source, sweep, excitations, notes, kept, run.result);
  run.text = FormatCampbellText(run.report);
  if (!out_dir.empty()) {
    WriteOutputFile(out_dir, "campbell.json", run.report.dump(2) + "\n");
    WriteOutputFile(out_dir, "campbell.csv", FormatCampbellCsv(run.report));
    WriteOutputFile(out_dir, "crossings.csv", FormatCrossingsCsv(run.report));
    WriteOutputFile(out_dir, "campbell.svg", RenderCampbellSvg(run.report));
  }
  run.exit_code = run.result.summary.ok() ? int{kExitOk} : int{kExitNumericalIssue};
  return run;
}

Command AddCampbellCommand(CLI::App& app) {
  auto opts = std::make_shared<CampbellCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "campbell",
      "natural frequencies against speed (gyroscopic and rotating-carrier terms), tracked by mode "
      "shape, with the mesh and shaft orders, their crossings and divergence/flutter speeds");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option("--speed", opts->settings.speed,
                  "lo:hi:n speeds of the operating point's body [rpm] (n >= 2 points)");
  cmd->add_option("--carrier-speed", opts->settings.carrier_speed,
                  "lo:hi:n speeds of the planetary carrier [rpm], instead of --speed");
  cmd->add_option("--orders", opts->settings.orders,
                  "mesh orders 1 … K drawn and crossed (default 3; shaft orders: 1)");
  cmd->add_option("--max-frequency", opts->settings.max_frequency_hz,
                  "leave out modes above this frequency at the first speed [Hz] (default: all)");
  cmd->add_flag("--undamped", opts->settings.undamped,
                "drop the damping (the conservative gyroscopic system)");
  cmd->add_flag("--no-carrier-frame", opts->settings.no_carrier_frame,
                "no Coriolis/centripetal terms of rotating planetary carriers");
  cmd->add_flag("--no-spin-gyroscopics", opts->settings.no_spin,
                "no gyroscopic moments of the spinning gears");
  cmd->add_flag("--loaded", opts->settings.loaded,
                "about the loaded operating point: add each mesh's tangent (geometric) stiffness "
                "under its static mesh force (as modes --loaded)");
  return {cmd, [opts](std::ostream& out) { return RunCampbell(*opts, out); }};
}

}  // namespace geardyn::app
