// What every subcommand file hands to main: its CLI11 definition and the action to run.
#ifndef MEMBRANE_CLIENT_COMMAND_H_
#define MEMBRANE_CLIENT_COMMAND_H_

#include <functional>

#include "absl/status/status.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

struct Command {
  // The subcommand, owned by the parent CLI::App.
  CLI::App* app = nullptr;
  // Runs the subcommand with the values parsed into it. Called at most once, after a
  // successful parse and only when `app` was given. A non-OK status is the one error line
  // (without the "membrane: " prefix) and, through ExitCodeFor, the exit status.
  std::function<absl::Status()> run;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_COMMAND_H_
