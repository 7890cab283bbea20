// Conversions between absl::Status (the server's currency) and what travels on the wire.
#ifndef MEMBRANE_SERVER_RPC_STATUS_H_
#define MEMBRANE_SERVER_RPC_STATUS_H_

#include <grpcpp/support/status.h>

#include "absl/status/status.h"
#include "absl/time/time.h"
#include "google/rpc/status.pb.h"

namespace membrane::server {

// `status` as a gRPC status with the same code and message.
grpc::Status ToGrpcStatus(const absl::Status& status);

// `status` as a gRPC status carrying a google.rpc.Status with a google.rpc.RetryInfo of
// `retry_delay` in its details (the "grpc-status-details-bin" trailer), so that clients know
// when to try again.
grpc::Status ToGrpcStatusWithRetry(const absl::Status& status, absl::Duration retry_delay);

// `status` as a google.rpc.Status message (for JobDone and Job.error).
google::rpc::Status ToRpcStatus(const absl::Status& status);

// The absl::Status of a google.rpc.Status (code and message; codes outside absl's become
// Unknown).
absl::Status FromRpcStatus(const google::rpc::Status& status);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_RPC_STATUS_H_
