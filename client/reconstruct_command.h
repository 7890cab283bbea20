// `membrane reconstruct INPUT -o OUTPUT [--local | --server HOST:PORT] [...]`: point cloud
// in, closed mesh out, in process or through a membraned.
#ifndef MEMBRANE_CLIENT_RECONSTRUCT_COMMAND_H_
#define MEMBRANE_CLIENT_RECONSTRUCT_COMMAND_H_

#include "client/command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

// Adds the `reconstruct` subcommand to `parent`. Its action validates every value (one
// InvalidArgument naming the flag and its range), then runs the reconstruction in process with
// progress on stderr, prints the generation table and a summary line on stdout, and writes the
// statistics JSON when --stats-json is given. Without --local it does the same through the
// server (RunRemoteReconstruction). Statuses: DeadlineExceeded "timed out after N s" when
// --timeout expires; Internal when the surface fails its check (the output is written all the
// same); otherwise those of RunLocalReconstruction or RunRemoteReconstruction.
Command AddReconstructCommand(CLI::App& parent);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_RECONSTRUCT_COMMAND_H_
