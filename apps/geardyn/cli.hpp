/// @file
/// @brief The `geardyn` command: subcommands, options and exit codes, runnable in-process.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace geardyn::app {

/// Exit codes of the geardyn command.
enum ExitCode : int {
  kExitOk = 0,              ///< success
  kExitNumericalIssue = 1,  ///< an analysis reported a status other than success
  kExitBadInput = 2,        ///< bad command line, unreadable or invalid scene
  kExitInternalError = 3,   ///< a bug in geardyn (an internal invariant failed)
  kExitInterrupted = 130,   ///< interrupted by SIGINT or SIGTERM; results so far were written
};

/// @brief Runs the geardyn command.
/// @param[in] args the arguments without the program name, e.g. {"info", "builtin:helical-pair"}.
/// @param[out] out results and help text.
/// @param[out] err error messages (`file:line: key: reason` for scene errors).
/// @return an ExitCode; never throws.
int RunCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace geardyn::app
