// `membrane jobs list|get|watch|cancel [JOB_ID] --server HOST:PORT`: the server's jobs as
// resources.
#ifndef MEMBRANE_CLIENT_JOBS_COMMAND_H_
#define MEMBRANE_CLIENT_JOBS_COMMAND_H_

#include "client/command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

// Adds `jobs` to `parent`:
//   list            one line per job: id, state, stage or outcome, upload bytes, peer
//   get ID          the job's fields, one "key: value" per line
//   watch ID [-o OUT] [--stats-json F]  the job's progress (as `reconstruct`) until it ends;
//                   writes its mesh and statistics when asked; the job's status as the result
//   cancel ID       asks the job to stop; prints its state
// Statuses: NotFound (exit 3) for an unknown or expired id; the call's status otherwise
// (Unavailable, DeadlineExceeded: exit 4); for watch, the job's (Cancelled: exit 5, ...).
Command AddJobsCommand(CLI::App& parent);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_JOBS_COMMAND_H_
