// Exit statuses of the `membrane` command (design/contracts.md): scripts on scanning stations
// branch on them, so the numbers never change.
#ifndef MEMBRANE_CLIENT_EXIT_CODES_H_
#define MEMBRANE_CLIENT_EXIT_CODES_H_

#include "absl/status/status.h"

namespace membrane::client {

enum ExitCode : int {
  kExitSuccess = 0,
  kExitUsage = 2,         // command line not understood (unknown command or flag)
  kExitInvalidInput = 3,  // unreadable file, bad parameter value, input the core rejects
  kExitUnavailable = 4,   // server unavailable or busy, or --timeout expired
  kExitJobFailed = 5,     // the reconstruction (or a mesh check) failed or was cancelled
};

// The exit status for a failed (non-OK) `status` from a command:
//   InvalidArgument, NotFound, OutOfRange, ResourceExhausted (a grid over a limit),
//   PermissionDenied, Unauthenticated (a missing or wrong --token-file), Unimplemented (an
//   unsupported file variant), DataLoss -> 3;
//   DeadlineExceeded, Unavailable -> 4; everything else (Cancelled, Internal, ...) -> 5.
// OK maps to 0.
ExitCode ExitCodeFor(const absl::Status& status);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_EXIT_CODES_H_
