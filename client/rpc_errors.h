// How the client reads a gRPC status: as an absl::Status for the exit codes of
// design/contracts.md, and for the retry delay a busy server asks for.
#ifndef MEMBRANE_CLIENT_RPC_ERRORS_H_
#define MEMBRANE_CLIENT_RPC_ERRORS_H_

#include <optional>
#include <string>

#include <grpcpp/support/status.h>

#include "absl/status/status.h"
#include "absl/time/time.h"

namespace membrane::client {

// `status` with the same code and message ("server: " prefixed for codes the server sets, so
// the one error line says where it came from). UNAVAILABLE names `address`, and so does a
// server out of call threads (ServerThreadsExhausted), made Unavailable: it is busy, not a
// limit the input broke.
absl::Status FromGrpcStatus(const grpc::Status& status, const std::string& address);

// The google.rpc.RetryInfo delay in the status details, when the server sent one.
std::optional<absl::Duration> RetryDelayOf(const grpc::Status& status);

// Whether a call that failed with `status` before its job was accepted is worth repeating:
// UNAVAILABLE (no server yet, or one shutting down), RESOURCE_EXHAUSTED when it carries a
// RetryInfo (a full queue, no room for uploads) or the server is out of call threads; the
// other limits carry none and would fail again.
bool IsRetryable(const grpc::Status& status);

// True for the RESOURCE_EXHAUSTED a sync gRPC server answers itself, before any handler runs,
// when every call thread its ResourceQuota allows is busy (membraned --max-calls).
bool ServerThreadsExhausted(const grpc::Status& status);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_RPC_ERRORS_H_
