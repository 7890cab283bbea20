// Runs the built `membrane` binary as a subprocess, the way scripts on scanning stations do.
#ifndef MEMBRANE_TESTS_SUPPORT_CLI_RUNNER_H_
#define MEMBRANE_TESTS_SUPPORT_CLI_RUNNER_H_

#include <string>
#include <vector>

namespace membrane::testing {

struct CliResult {
  int exit_code = -1;  // the exit status; 128 + signal number when killed by a signal
  std::string out;     // everything written to stdout
  std::string err;     // everything written to stderr
};

// Runs MEMBRANE_BINARY with `args` (no shell: arguments are passed as they are), stdin from
// the file `stdin_path`, stdout and stderr captured through files in `scratch_dir`. Waits for
// it to end.
CliResult RunMembrane(const std::vector<std::string>& args, const std::string& scratch_dir,
                      const std::string& stdin_path = "/dev/null");

// The bytes of the file at `path`; empty when it cannot be read.
std::string ReadWholeFile(const std::string& path);

// The lines of `text` that start with "membrane: " (the error lines of the contract).
std::vector<std::string> ErrorLines(const std::string& text);

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_CLI_RUNNER_H_
