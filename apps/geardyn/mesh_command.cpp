#include <memory>

#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/mesh_report.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

struct MeshCommandOptions {
  SceneCommandOptions scene;
  MeshSamplingOptions sampling;
};

int RunMesh(const MeshCommandOptions& opts, std::ostream& out) {
  std::string why;
  GEARDYN_THROW_UNLESS(opts.sampling.IsValid(&why), why);
  const Scene scene = LoadScene(opts.scene.scene, opts.scene.overrides);
  GEARDYN_THROW_UNLESS(!scene.oscillator,
                       scene.source << ": an oscillator scene has no gear mesh to sample (its "
                                       "stiffness is k (1 + alpha cos theta) by definition; see "
                                       "geardyn info)");
  std::vector<MeshSamples> samples;
  const nlohmann::json report = MakeMeshReport(scene, opts.sampling, &samples);
  if (opts.scene.json) {
    out << report.dump(2) << "\n";
  } else {
    for (const nlohmann::json& m : report["meshes"]) {
      out << "mesh " << m["name"].get<std::string>() << ": level " << m["level"].get<std::string>()
          << ", " << m["time_dependence"].get<std::string>() << ", period "
          << m["period_meshes"].get<long>() << " mesh cycle(s), K "
          << m["stiffness"]["min"].get<double>() << " … " << m["stiffness"]["max"].get<double>()
          << " N/m (mean " << m["stiffness"]["mean"].get<double>() << ")\n";
      for (const nlohmann::json& w : m["warnings"]) {
        out << "warning: " << w.get<std::string>() << "\n";
      }
    }
  }
  const std::string& dir = opts.scene.out_dir;
  if (!dir.empty()) {
    WriteOutputFile(dir, "mesh.json", report.dump(2) + "\n");
    for (const MeshSamples& s : samples) {
      WriteOutputFile(dir, "mesh_" + s.mesh_name + ".csv", FormatMeshCsv(s));
      WriteOutputFile(dir, "mesh_" + s.mesh_name + ".svg",
                      RenderMeshSvg(s, scene.source + " — mesh " + s.mesh_name));
    }
    if (!opts.scene.json) out << "written to " << dir << "\n";
  }
  return kExitOk;
}

}  // namespace

Command AddMeshCommand(CLI::App& app) {
  auto opts = std::make_shared<MeshCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh",
      "write K(θ), h(θ), μ(θ), ε(θ) of every mesh over one period or --cycles (CSV, JSON, SVG)");
  AddSceneOptions(cmd, &opts->scene);
  cmd->add_option_function<double>(
      "--samples", [opts](const double& n) { opts->sampling.samples_per_mesh = n; },
      "samples per mesh cycle, 1 … 100000 (default: 360, fewer over long hunting periods)");
  cmd->add_option_function<double>(
      "--cycles", [opts](const double& n) { opts->sampling.cycles = n; },
      "mesh cycles sampled from θ = 0 (default: the mesh's period, at most the first 12500 "
      "cycles of a hunting period)");
  return {cmd, [opts](std::ostream& out) { return RunMesh(*opts, out); }};
}

}  // namespace geardyn::app
