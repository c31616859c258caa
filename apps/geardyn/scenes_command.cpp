#include "geardyn/cli.hpp"
#include "geardyn/command.hpp"
#include "geardyn/models/scene/builtin_scenes.hpp"

namespace geardyn::app {

Command AddScenesCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("scenes", "list the built-in scenes");
  return {cmd, [](std::ostream& out) {
            for (const std::string& name : BuiltinSceneNames()) out << "builtin:" << name << "\n";
            return int{kExitOk};
          }};
}

}  // namespace geardyn::app
