#include "geardyn/cli.hpp"

#include <CLI/CLI.hpp>
#include <exception>

#include "geardyn/command.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/interrupt.hpp"

namespace geardyn::app {
namespace {

constexpr const char* kVersion = "0.1.0";

}  // namespace

int RunCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CLI::App app{
      "geardyn — gear mesh dynamics (Blankenship–Singh mesh interface, eigen, Floquet, "
      "harmonic balance)",
      "geardyn"};
  app.require_subcommand(1);
  app.set_version_flag("--version", kVersion);

  std::vector<Command> commands;
  for (const CommandFactory factory : CommandFactories()) commands.push_back(factory(app));

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
    for (const Command& command : commands) {
      if (command.cli->parsed()) {
        // SIGINT/SIGTERM stop the long analyses, which return what they computed; the files are
        // written marked as partial (output_files.hpp) and the exit code says so.
        const InterruptScope interrupt_scope;
        const int code = command.run_with_err ? command.run_with_err(out, err) : command.run(out);
        if (Interrupted() && code != kExitInterrupted) {
          err << "geardyn: interrupted (SIGINT/SIGTERM); the results computed before it were "
                 "written, marked as partial\n";
          return kExitInterrupted;
        }
        return code;
      }
    }
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
