// `geardyn matrices SCENE --out DIR`: the scene's system matrices as MatrixMarket files and a
// JSON DOF map (matrices_export.hpp), for checking geardyn in MATLAB, scipy or Julia.
#include <memory>

#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/matrices_export.hpp"
#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn::app {
namespace {

struct MatricesCommandOptions {
  SceneCommandOptions scene;
  int harmonics = 0;
};

int RunMatrices(const MatricesCommandOptions& opts, std::ostream& out) {
  if (opts.scene.out_dir.empty()) {
    throw InvalidInput("--out: `geardyn matrices` writes files; give the directory");
  }
  const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
  const SystemMatrices m = ExportSystemMatrices(scene, opts.harmonics);
  WriteSystemMatrices(m, opts.scene.out_dir);
  if (opts.scene.json) {
    out << m.report.dump(2) << "\n";
  } else {
    out << "matrices: " << scene.source << ", " << m.report["num_dofs"].get<int>()
        << " DOFs: M, C, K (" << m.mean.stiffness.nonZeros() << " non-zeros), f";
    if (opts.harmonics > 0) out << ", K_m, C_m, f_m for m = 1 … " << opts.harmonics;
    out << "\n";
    for (const auto& w : m.report["warnings"]) out << "warning: " << w.get<std::string>() << "\n";
    out << "written to " << opts.scene.out_dir << "\n";
  }
  return kExitOk;
}

}  // namespace

Command AddMatricesCommand(CLI::App& app) {
  auto opts = std::make_shared<MatricesCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "matrices",
      "write M, C, K of the mean system (what `modes` solves), f and the harmonics K_m, C_m, f_m "
      "as MatrixMarket files with a JSON DOF map (dofs.json)");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option("--harmonics", opts->harmonics,
                  "Fourier harmonics m = 1 … H of K(θ), C(θ), f(θ) (default 0: the mean system "
                  "only; harmonic m is at m/P times the mesh frequency, P = period_meshes)")
      ->check(CLI::Range(0, kMaxExportHarmonics));
  return {cmd, [opts](std::ostream& out) { return RunMatrices(*opts, out); }};
}

}  // namespace geardyn::app
