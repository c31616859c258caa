// `geardyn hb SCENE`: the steady-state DTE of the scene's linear model over a list of mesh
// frequencies (SweepHarmonicBalance on MakeSystemModel), printed as a table or JSON, and written
// to --out as hb.json, hb.csv and hb_rms_dte.svg.
//
// Nonlinear hook: when the nonlinear engine (contact loss, analyses/nonlinear_hb*.hpp) exists,
// RunHb should call it for scenes whose model has slice or nonlinear cores
// (model.time_dependence() == kNonlinear) unless --linear is given. Until then slice meshes use
// their all-loaded linearization and the library reports that in the warnings.
#include <memory>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/hb_report.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

struct HbCommandOptions {
  SceneCommandOptions scene;
  HbSettings settings;
};

// The scene's first mesh frequency [Hz], 0 when it has no meshes or no speed.
double NominalMeshFrequency(const Scene& scene) {
  if (scene.meshes.empty()) return 0.0;
  return scene.MeshFrequencyHz(scene.meshes.front());
}

int RunHb(const HbCommandOptions& opts, std::ostream& out, std::ostream& err) {
  const HbOptions options = MakeHbOptions(opts.settings);
  const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
  const std::vector<double> frequencies =
      ParseMeshFrequencies(opts.settings.mesh_frequency, NominalMeshFrequency(scene));
  const SceneSystem built = BuildSceneSystem(scene);
  std::vector<std::string> warnings = built.warnings;
  if (built.model.time_dependence() == TimeDependence::kNonlinear && !opts.settings.linear) {
    warnings.push_back(
        "the nonlinear harmonic balance is not available yet: solving the linear "
        "model (slice meshes linearized with every slice loaded)");
  }
  HbProgress progress;
  if (opts.settings.progress) {
    progress = [&err](int done, int total) {
      if (done == total || done % std::max(1, total / 20) == 0) {
        err << "geardyn hb: " << done << "/" << total << " mesh frequencies\n";
      }
    };
  }
  const HbSweepResult sweep = SweepHarmonicBalance(built.model, frequencies, options, progress);
  const nlohmann::json report = MakeHbReport(scene.source, opts.settings, sweep, warnings);
  const std::string json_text = report.dump(2) + "\n";
  out << (opts.scene.json ? json_text : FormatHbText(report));
  const std::string& dir = opts.scene.out_dir;
  if (!dir.empty()) {
    WriteOutputFile(dir, "hb.json", json_text);
    WriteOutputFile(dir, "hb.csv", FormatHbCsv(sweep));
    WriteOutputFile(dir, "hb_rms_dte.svg",
                    RenderHbPlot(sweep, "RMS DTE (linear harmonic balance): " + scene.source));
    if (!opts.scene.json) out << "written to " << dir << "\n";
  }
  return sweep.summary.ok() ? int{kExitOk} : int{kExitNumericalIssue};
}

}  // namespace

Command AddHbCommand(CLI::App& app) {
  auto opts = std::make_shared<HbCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "hb", "steady-state DTE, mesh and bearing forces over mesh frequency (harmonic balance)");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option("--mesh-frequency", opts->settings.mesh_frequency,
                  "tooth-mesh frequencies [Hz] as lo:hi:n (n points) or one value (default "
                  "0.2 to 2.5 times the scene's, 200 points)");
  cmd->add_option("--harmonics", opts->settings.harmonics,
                  "number of harmonics H of the mesh frequency (default: from --tolerance)");
  cmd->add_option("--tolerance", opts->settings.tolerance,
                  "relative change of the RMS DTE from H/2 to H accepted (default 1e-4)");
  cmd->add_flag("--linear", opts->settings.linear,
                "linear model (the only mode for now; slice meshes linearized, all loaded)");
  cmd->add_flag("--progress", opts->settings.progress, "print the progress on the error stream");
  Command command{cmd, nullptr};
  command.run_with_err = [opts](std::ostream& out, std::ostream& err) {
    return RunHb(*opts, out, err);
  };
  return command;
}

}  // namespace geardyn::app
