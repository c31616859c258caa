#include "geardyn/cli.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <optional>

#include "geardyn/common/errors.hpp"
#include "geardyn/info_report.hpp"
#include "geardyn/mesh_report.hpp"
#include "geardyn/models/scene/builtin_scenes.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {
namespace {

constexpr const char* kVersion = "0.1.0";

/// Options every scene subcommand accepts.
struct SceneCommandOptions {
  std::string scene;
  std::vector<std::string> overrides;
  std::string out_dir;
  bool json = false;
};

void AddSceneOptions(CLI::App* cmd, SceneCommandOptions* opts) {
  cmd->add_option("scene", opts->scene,
                  "scene file (TOML) or a built-in scene, e.g. builtin:kahraman-blankenship-rig")
      ->required();
  cmd->add_option("--set", opts->overrides,
                  "override a scene value, e.g. --set gear.pinion.teeth=23 (repeatable)")
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_option("--out", opts->out_dir, "directory for result files (created if missing)");
  cmd->add_flag("--json", opts->json, "print the results as JSON instead of text");
}

int RunInfo(const SceneCommandOptions& opts, std::ostream& out) {
  const Scene scene = LoadScene(opts.scene, opts.overrides);
  const nlohmann::json report = MakeInfoReport(scene);
  const std::string json_text = report.dump(2) + "\n";
  const std::string text = FormatInfoText(report);
  out << (opts.json ? json_text : text);
  if (!opts.out_dir.empty()) {
    WriteOutputFile(opts.out_dir, "info.json", json_text);
    WriteOutputFile(opts.out_dir, "info.txt", text);
  }
  return kExitOk;
}

int RunMesh(const SceneCommandOptions& opts, const MeshSamplingOptions& sampling,
            std::ostream& out) {
  const Scene scene = LoadScene(opts.scene, opts.overrides);
  std::vector<MeshSamples> samples;
  const nlohmann::json report = MakeMeshReport(scene, sampling, &samples);
  if (opts.json) {
    out << report.dump(2) << "\n";
  } else {
    for (const nlohmann::json& m : report["meshes"]) {
      out << "mesh " << m["name"].get<std::string>() << ": level " << m["level"].get<std::string>()
          << ", " << m["time_dependence"].get<std::string>() << ", period "
          << m["period_meshes"].get<long>() << " mesh cycle(s), K "
          << m["stiffness"]["min"].get<double>() << " … " << m["stiffness"]["max"].get<double>()
          << " N/m (mean " << m["stiffness"]["mean"].get<double>() << ")\n";
    }
  }
  if (!opts.out_dir.empty()) {
    WriteOutputFile(opts.out_dir, "mesh.json", report.dump(2) + "\n");
    for (const MeshSamples& s : samples) {
      WriteOutputFile(opts.out_dir, "mesh_" + s.mesh_name + ".csv", FormatMeshCsv(s));
      WriteOutputFile(opts.out_dir, "mesh_" + s.mesh_name + ".svg",
                      RenderMeshSvg(s, scene.source + " — mesh " + s.mesh_name));
    }
    if (!opts.json) out << "written to " << opts.out_dir << "\n";
  }
  return kExitOk;
}

int RunScenes(std::ostream& out) {
  for (const std::string& name : BuiltinSceneNames()) out << "builtin:" << name << "\n";
  return kExitOk;
}

}  // namespace

int RunCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "geardyn — gear mesh dynamics (Blankenship–Singh mesh interface, eigen, Floquet, "
      "harmonic balance)",
      "geardyn"};
  app.require_subcommand(1);
  app.set_version_flag("--version", kVersion);

  SceneCommandOptions info_opts;
  CLI::App* info = app.add_subcommand(
      "info", "print the derived geometry, ISO 6336-1 stiffness and model facts of a scene");
  AddSceneOptions(info, &info_opts);

  SceneCommandOptions mesh_opts;
  MeshSamplingOptions sampling;
  CLI::App* mesh = app.add_subcommand(
      "mesh", "write K(θ), h(θ), μ(θ), ε(θ) of every mesh over one period (CSV, JSON, SVG)");
  AddSceneOptions(mesh, &mesh_opts);
  mesh->add_option("--samples", sampling.samples_per_mesh,
                   "samples per mesh cycle (default: 360, fewer over long hunting periods)");

  CLI::App* scenes = app.add_subcommand("scenes", "list the built-in scenes");

  // CLI11 reports an unknown first word only as "a subcommand is required": name it instead.
  const auto is_subcommand = [&app](const std::string& word) {
    for (const CLI::App* sub : app.get_subcommands({})) {
      if (sub->get_name() == word) return true;
    }
    return false;
  };
  if (!args.empty() && !args.front().empty() && args.front()[0] != '-' &&
      !is_subcommand(args.front())) {
    err << "geardyn: error: unknown subcommand '" << args.front() << "' (known:";
    for (const CLI::App* sub : app.get_subcommands({})) err << " " << sub->get_name();
    err << "); see geardyn --help\n";
    return kExitBadInput;
  }
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 parses back to front
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e, out, err);
    return code == 0 ? kExitOk : kExitBadInput;
  }

  try {
    if (info->parsed()) return RunInfo(info_opts, out);
    if (mesh->parsed()) return RunMesh(mesh_opts, sampling, out);
    if (scenes->parsed()) return RunScenes(out);
  } catch (const InvalidInput& e) {
    err << "geardyn: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const InternalError& e) {
    err << "geardyn: internal error (please report): " << e.what() << "\n";
    return kExitInternalError;
  } catch (const std::exception& e) {
    err << "geardyn: internal error (please report): " << e.what() << "\n";
    return kExitInternalError;
  }
  return kExitBadInput;
}

}  // namespace geardyn::app
