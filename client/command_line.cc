#include "client/command_line.h"

#include <cstdio>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "absl/strings/string_view.h"
#include "absl/strings/strip.h"
#include "client/check_command.h"
#include "client/render_command.h"
#include "client/command.h"
#include "client/convert_command.h"
#include "client/exit_codes.h"
#include "client/health_command.h"
#include "client/jobs_command.h"
#include "client/reconstruct_command.h"
#include "client/synth_command.h"

namespace membrane::client {
namespace {

constexpr char kExitStatusHelp[] =
    "Exit status: 0 success; 2 usage error (unknown command or flag, missing argument); "
    "3 invalid input (unreadable or malformed file, unknown extension, a parameter value out "
    "of range or not a number, input the core rejects such as a grid over the memory limit, a missing or wrong "
    "--token-file); "
    "4 server unavailable or busy, or --timeout expired; 5 job failed or cancelled, or "
    "`check` found the mesh not closed, not manifold or not oriented. Every error prints one "
    "line \"membrane: <message>\" on stderr.";

// Prints the one error line. Messages from CLI11 may hold newlines; scripts read one line.
void PrintError(absl::string_view message) {
  std::string line =
      absl::StrReplaceAll(absl::StripTrailingAsciiWhitespace(message), {{"\r", ""}, {"\n", "; "}});
  std::fprintf(stderr, "membrane: %s\n", line.c_str());
}

std::vector<std::string> CommandNames(const std::vector<Command>& commands) {
  std::vector<std::string> names;
  for (const Command& c : commands) names.push_back(c.app->get_name());
  return names;
}

// The exit status for a failed parse, after printing help (--help) or the one error line.
int ExitForParseError(CLI::App& app, const std::vector<Command>& commands,
                      const CLI::ParseError& e) {
  // --help ends the parse with a ParseError whose exit code is 0; CLI11 prints the help.
  if (e.get_exit_code() == 0) return app.exit(e);
  // A value that is not a number is a bad parameter (3), like one out of range; the rest
  // (unknown commands and flags, missing arguments) is a usage error (2).
  const bool bad_value = dynamic_cast<const CLI::ConversionError*>(&e) != nullptr ||
                         dynamic_cast<const CLI::ValidationError*>(&e) != nullptr;
  // CLI11 reports a misspelled command as "a subcommand is required" with the word left over.
  const std::vector<std::string> leftover = app.remaining();
  const bool unknown_command =
      app.get_subcommands().empty() && !leftover.empty() && leftover[0][0] != '-';
  if (unknown_command) {
    PrintError("unknown command '" + leftover[0] +
               "'; expected one of: " + absl::StrJoin(CommandNames(commands), ", "));
  } else {
    PrintError(e.what());
  }
  return bad_value ? kExitInvalidInput : kExitUsage;
}

}  // namespace

int RunCommandLine(int argc, char** argv) {
  CLI::App app("membrane: closed triangle meshes from point clouds by discrete membrane shrinking",
               "membrane");
  app.footer(kExitStatusHelp);
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("membrane ") + MEMBRANE_VERSION + " (" +
                                        MEMBRANE_BUILD_TYPE + " build)");
  const std::vector<Command> commands = {AddReconstructCommand(app), AddSynthCommand(app),
                                         AddCheckCommand(app), AddConvertCommand(app),
                                         AddJobsCommand(app), AddHealthCommand(app),
                                         AddRenderCommand(app)};
  // No command at all: the usage, as other command-line tools print it, and a usage error.
  if (argc <= 1) {
    std::fprintf(stderr, "%s", app.help().c_str());
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return ExitForParseError(app, commands, e);
  }
  for (const Command& command : commands) {
    if (!command.app->parsed()) continue;
    const absl::Status status = command.run();
    if (status.ok()) return kExitSuccess;
    PrintError(status.message());
    return ExitCodeFor(status);
  }
  // require_subcommand(1) makes this unreachable; keep the promise of one line anyway.
  PrintError("no command given");
  return kExitUsage;
}

}  // namespace membrane::client

