// `membrane`: the command-line client. Parses the command line, runs one subcommand, and turns
// its status into one error line and the exit status of design/contracts.md.
#include <malloc.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "absl/strings/string_view.h"
#include "absl/strings/strip.h"
#include "client/check_command.h"
#include "client/command.h"
#include "client/convert_command.h"
#include "client/exit_codes.h"
#include "client/health_command.h"
#include "client/input_files.h"
#include "client/jobs_command.h"
#include "client/reconstruct_command.h"
#include "client/synth_command.h"
#include "core/io/decode_helper.h"

namespace membrane::client {
namespace {

constexpr char kExitStatusHelp[] =
    "Exit status: 0 success; 2 usage error (unknown command or flag, missing argument); "
    "3 invalid input (unreadable or malformed file, unknown extension, a parameter value out "
    "of range or not a number, input the core rejects such as a grid over the voxel budget, a missing or wrong "
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

int Main(int argc, char** argv) {
  CLI::App app("membrane: closed triangle meshes from point clouds by discrete membrane shrinking",
               "membrane");
  app.footer(kExitStatusHelp);
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("membrane ") + MEMBRANE_VERSION + " (" +
                                        MEMBRANE_BUILD_TYPE + " build)");
  const std::vector<Command> commands = {AddReconstructCommand(app), AddSynthCommand(app),
                                         AddCheckCommand(app), AddConvertCommand(app),
                                         AddJobsCommand(app), AddHealthCommand(app)};
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

}  // namespace
}  // namespace membrane::client

int main(int argc, char** argv) {
  // One malloc arena for the process. `reconstruct --local` checks the mesh on a second thread
  // while it encodes; with an arena of its own that thread would fault in fresh pages instead
  // of reusing what the earlier stages freed (on rocker-arm-scan the check takes 0.23 s with
  // one arena and 0.36 s with glibc's default, the whole run 1.05 s and 1.27 s). Two threads
  // hardly contend for one arena.
  // The server keeps glibc's default: its workers allocate in parallel.
  mallopt(M_ARENA_MAX, 1);
  // Run by ReadInputCloud on itself to decode a Draco file under resource limits.
  if (argc >= 2 && std::string(argv[1]) == membrane::client::kDecodeHelperFlag) {
    return membrane::RunDecodeHelper(std::vector<std::string>(argv + 2, argv + argc));
  }
  // Nothing may escape as an exception: a crash is not one readable line.
  try {
    return membrane::client::Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "membrane: internal error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "membrane: internal error\n");
  }
  return membrane::client::kExitJobFailed;
}
