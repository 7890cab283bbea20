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
// the one error line says where it came from). UNAVAILABLE names `address`.
absl::Status FromGrpcStatus(const grpc::Status& status, const std::string& address);

// The google.rpc.RetryInfo delay in the status details, when the server sent one.
std::optional<absl::Duration> RetryDelayOf(const grpc::Status& status);

// Whether a call that failed with `status` before its job was accepted is worth repeating:
// UNAVAILABLE (no server yet, or one shutting down), and RESOURCE_EXHAUSTED when it carries a
// RetryInfo (a full queue; the other limits carry none and would fail again).
bool IsRetryable(const grpc::Status& status);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_RPC_ERRORS_H_
