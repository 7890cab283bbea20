#include "client/exit_codes.h"

namespace membrane::client {

ExitCode ExitCodeFor(const absl::Status& status) {
  switch (status.code()) {
    case absl::StatusCode::kOk: return kExitSuccess;
    // Local runs have no server, so ResourceExhausted can only be the input's own fault
    // (a grid over the memory limit, the machine's memory or a voxel budget), not a busy
    // server.
    case absl::StatusCode::kInvalidArgument:
    case absl::StatusCode::kNotFound:
    case absl::StatusCode::kOutOfRange:
    case absl::StatusCode::kResourceExhausted:
    case absl::StatusCode::kPermissionDenied:
    case absl::StatusCode::kUnauthenticated:
    case absl::StatusCode::kUnimplemented:
    case absl::StatusCode::kDataLoss: return kExitInvalidInput;
    case absl::StatusCode::kDeadlineExceeded:
    case absl::StatusCode::kUnavailable: return kExitUnavailable;
    default: return kExitJobFailed;
  }
}

}  // namespace membrane::client
