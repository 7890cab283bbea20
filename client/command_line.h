// The `membrane` command line: its subcommands, their flags, and the exit status of
// design/contracts.md for each outcome.
#ifndef MEMBRANE_CLIENT_COMMAND_LINE_H_
#define MEMBRANE_CLIENT_COMMAND_LINE_H_

namespace membrane::client {

// Parses `argv`, runs the one subcommand it names, and returns the exit status: kExitSuccess,
// or the status's exit code after printing one line "membrane: <message>" on stderr (help
// goes to stdout with status 0). Exceptions other than CLI11's parse errors propagate.
int RunCommandLine(int argc, char** argv);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_COMMAND_LINE_H_
