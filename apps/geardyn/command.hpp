/// @file
/// @brief One geardyn subcommand: how it registers its options and how it runs. Each subcommand
/// lives in its own `<name>_command.cpp` and is listed once in `commands.cpp`.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace geardyn::app {

/// Options every scene subcommand accepts (`SCENE`, `--set`, `--out`, `--json`).
struct SceneCommandOptions {
  std::string scene;
  std::vector<std::string> overrides;
  std::string out_dir;
  bool json = false;
};

/// @brief CLI11 check of a finite number in [lo, hi] (an open end with lo_open / hi_open).
///
/// Used instead of CLI::PositiveNumber / CLI::NonNegativeNumber, which let NaN through and print
/// their range up to DBL_MAX ("Value 0 not in range 0.000000 to 1797…"). CLI11 prefixes the
/// message with the option's name: "--tolerance: must be a finite number in (0, 1), got nan".
CLI::Validator FiniteNumberIn(double lo, double hi, bool lo_open = false, bool hi_open = false);

/// Adds the SceneCommandOptions to `cmd`.
void AddSceneOptions(CLI::App* cmd, SceneCommandOptions* opts);

/// @brief A registered subcommand: its CLI11 node and the action run when it was parsed.
///
/// The action returns an ExitCode and may throw InvalidInput (exit 2) or InternalError (exit 3);
/// RunCli turns exceptions into messages. Options are owned by the action's closure.
struct Command {
  CLI::App* cli = nullptr;
  std::function<int(std::ostream& out)> run;
  /// Used instead of `run` when set: for commands that also write progress to the error stream.
  std::function<int(std::ostream& out, std::ostream& err)> run_with_err = nullptr;
};

/// A function that adds one subcommand to `app`.
using CommandFactory = Command (*)(CLI::App& app);

/// Every subcommand, in the order `geardyn --help` lists them (commands.cpp).
const std::vector<CommandFactory>& CommandFactories();

// One factory per subcommand (each in its own <name>_command.cpp).
Command AddHbCommand(CLI::App& app);
Command AddInfoCommand(CLI::App& app);
Command AddMeshCommand(CLI::App& app);
Command AddModesCommand(CLI::App& app);
Command AddScenesCommand(CLI::App& app);
Command AddFloquetCommand(CLI::App& app);
Command AddStabilityChartCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddCompareCommand(CLI::App& app);
Command AddMatricesCommand(CLI::App& app);
Command AddCampbellCommand(CLI::App& app);

}  // namespace geardyn::app
