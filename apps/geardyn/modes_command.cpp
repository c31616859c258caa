// `geardyn modes SCENE`: the modes of the scene's mean (LTI) system (ComputeModes on
// MakeSystemModel), printed as a mode-type table or JSON, and written to --out as modes.json,
// modes.csv and (with --shapes) mode_shapes.csv.
#include <cstddef>
#include <memory>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/analysis_runs.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/modes_report.hpp"
#include "geardyn/output_files.hpp"
#include "geardyn/shaft_report.hpp"

namespace geardyn::app {
namespace {

struct ModesCommandOptions {
  SceneCommandOptions scene;
  ModesSettings settings;
};

int RunModes(const ModesCommandOptions& opts, std::ostream& out) {
  const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
  const ModesRun run = RunModesAnalysis(scene, opts.settings, opts.scene.out_dir);
  out << (opts.scene.json ? run.report.dump(2) + "\n" : run.text);
  if (!opts.scene.out_dir.empty() && !opts.scene.json) {
    out << "written to " << opts.scene.out_dir << "\n";
  }
  return run.exit_code;
}

}  // namespace

ModesRun RunModesAnalysis(const Scene& scene, const ModesSettings& settings,
                          const std::string& out_dir) {
  // Modes use the mean operator only: ε (a table over the hunting period with tooth errors)
  // is not built.
  SceneSystemOptions system_options;
  system_options.transmission_error = false;
  system_options.analysis = "modes";  // named if a mass is missing
  system_options.mesh_preload = settings.loaded;
  const SceneSystem built = BuildSceneSystem(scene, system_options);
  const int n = built.model.num_dofs();
  const ModalOptions options = MakeModesOptions(settings, n);
  ModesRun run;
  run.result = ComputeModes(built.model, options);
  ModalResult& result = run.result;
  // --modes N applies to the damped modes too: the dense state-space solve gives all of them
  // (geared-shafts --modes 8 --damped listed 108). Both lists are sorted by natural frequency
  // (rigid-body modes first), so the first N damped modes sit beside the N undamped ones.
  const auto wanted = static_cast<std::size_t>(settings.num_modes);
  if (result.damped_modes.size() > wanted) result.damped_modes.resize(wanted);
  run.report = MakeModesReport(scene.source, n, result, built.warnings);
  if (settings.loaded) AddMeshPreloadReport(built, &run.report);
  GroupShaftStrain(scene, &run.report);
  run.text = FormatModesText(run.report);
  if (!out_dir.empty()) {
    WriteOutputFile(out_dir, "modes.json", run.report.dump(2) + "\n");
    WriteOutputFile(out_dir, "modes.csv", ModalResultToCsv(result));
    if (settings.shapes) WriteOutputFile(out_dir, "mode_shapes.csv", FormatModeShapesCsv(result));
  }
  run.exit_code = result.summary.ok() ? int{kExitOk} : int{kExitNumericalIssue};
  return run;
}

Command AddModesCommand(CLI::App& app) {
  auto opts = std::make_shared<ModesCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "modes",
      "natural frequencies, mode types and energy fractions of the mean (LTI) system of a scene");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option("--modes", opts->settings.num_modes,
                  "number of lowest modes (default 20; all when the system has fewer DOFs)");
  cmd->add_option("--method", opts->settings.method,
                  "eigen solver: auto (dense below 200 DOFs, else ARPACK), dense or arpack")
      ->check(CLI::IsMember({"auto", "dense", "arpack"}));
  cmd->add_flag("--shapes", opts->settings.shapes,
                "include the mode shapes (JSON; mode_shapes.csv with --out)");
  cmd->add_flag("--damped", opts->settings.damped,
                "also compute the damped complex modes (frequency, damping ratio; the --modes "
                "lowest by natural frequency)");
  cmd->add_flag("--loaded", opts->settings.loaded,
                "modes about the loaded operating point: add each mesh's tangent (geometric) "
                "stiffness under its static mesh force (softening across an external mesh's line "
                "of action, stiffening across an internal one)");
  return {cmd, [opts](std::ostream& out) { return RunModes(*opts, out); }};
}

}  // namespace geardyn::app
