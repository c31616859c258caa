/// @file
/// @brief The geardyn command run in-process for the apps tests: RunGeardyn (exit code, stdout,
/// stderr) and RunJson (adds --json, expects success, parses stdout).
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/cli.hpp"

namespace geardyn::test {

/// Result of one in-process run of the geardyn command.
struct CliRun {
  int code;
  std::string out;
  std::string err;
};

/// Runs `geardyn args...` in-process.
inline CliRun RunGeardyn(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int code = app::RunCli(args, out, err);
  return {code, out.str(), err.str()};
}

/// Runs `geardyn args... --json`, expects exit code kExitOk and returns the parsed stdout.
inline nlohmann::json RunJson(std::vector<std::string> args) {
  args.push_back("--json");
  const CliRun run = RunGeardyn(args);
  EXPECT_EQ(run.code, app::kExitOk) << run.err;
  return nlohmann::json::parse(run.out);
}

}  // namespace geardyn::test
