#include <memory>

#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/info_report.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {

Command AddInfoCommand(CLI::App& app) {
  auto opts = std::make_shared<SceneCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info", "print the derived geometry, ISO 6336-1 stiffness and model facts of a scene");
  AddSceneOptions(cmd, opts.get());
  return {cmd, [opts](std::ostream& out) {
            const Scene scene = LoadScene(opts->scene, opts->overrides);
            const nlohmann::json report = MakeInfoReport(scene);
            const std::string json_text = report.dump(2) + "\n";
            const std::string text = FormatInfoText(report);
            out << (opts->json ? json_text : text);
            if (!opts->out_dir.empty()) {
              WriteOutputFile(opts->out_dir, "info.json", json_text);
              WriteOutputFile(opts->out_dir, "info.txt", text);
            }
            return int{kExitOk};
          }};
}

}  // namespace geardyn::app
