#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "geardyn/command.hpp"
#include "geardyn/output_files.hpp"

namespace geardyn::app {

CLI::Validator FiniteNumberIn(double lo, double hi, bool lo_open, bool hi_open) {
  std::ostringstream range;
  range << std::setprecision(12) << (lo_open ? "(" : "[") << lo << ", " << hi
        << (hi_open ? ")" : "]");
  const std::string bounds = range.str();
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool number = !text.empty() && end == text.c_str() + text.size();
        const bool inside = number && std::isfinite(v) && (lo_open ? v > lo : v >= lo) &&
                            (hi_open ? v < hi : v <= hi);
        return inside ? std::string() : "must be a finite number in " + bounds + ", got " + text;
      },
      "NUMBER in " + bounds);
}

void AddSceneOptions(CLI::App* cmd, SceneCommandOptions* opts) {
  cmd->add_option("scene", opts->scene,
                  "scene file (TOML) or a built-in scene, e.g. builtin:kahraman-blankenship-rig")
      ->required();
  cmd->add_option("--set", opts->overrides,
                  "override a scene value, e.g. --set gear.pinion.teeth=23 (repeatable)")
      ->take_all()
      ->allow_extra_args(false);
  // Checked (and created) while parsing, before any computation: a bad --out fails at once.
  cmd->add_option("--out", opts->out_dir, "directory for result files (created if missing)")
      ->check(CLI::Validator([](std::string& dir) { return PrepareOutputDirectory(dir); }, "DIR",
                             "writable directory"));
  cmd->add_flag("--json", opts->json, "print the results as JSON instead of text");
}

const std::vector<CommandFactory>& CommandFactories() {
  // One line per subcommand; keep the order of `geardyn --help`.
  static const std::vector<CommandFactory> factories = {
      &AddInfoCommand,    &AddScenesCommand,         &AddMeshCommand, &AddModesCommand,
      &AddFloquetCommand, &AddStabilityChartCommand, &AddHbCommand,   &AddSimulateCommand,
      &AddCompareCommand, &AddMatricesCommand, &AddCampbellCommand,
  };
  return factories;
}

}  // namespace geardyn::app
