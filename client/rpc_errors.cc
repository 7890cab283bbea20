#include "client/rpc_errors.h"

#include "absl/strings/str_cat.h"
#include "google/rpc/error_details.pb.h"
#include "google/rpc/status.pb.h"

namespace membrane::client {

absl::Status FromGrpcStatus(const grpc::Status& status, const std::string& address) {
  if (status.ok()) return absl::OkStatus();
  const auto code = static_cast<absl::StatusCode>(status.error_code());
  if (code == absl::StatusCode::kUnavailable || ServerThreadsExhausted(status)) {
    return absl::UnavailableError(
        absl::StrCat("server ", address, " unavailable: ", status.error_message()));
  }
  return absl::Status(code, absl::StrCat("server: ", status.error_message()));
}

std::optional<absl::Duration> RetryDelayOf(const grpc::Status& status) {
  if (status.error_details().empty()) return std::nullopt;
  google::rpc::Status details;
  if (!details.ParseFromString(status.error_details())) return std::nullopt;
  for (const google::protobuf::Any& any : details.details()) {
    google::rpc::RetryInfo retry;
    if (any.UnpackTo(&retry)) {
      return absl::Seconds(retry.retry_delay().seconds()) +
             absl::Nanoseconds(retry.retry_delay().nanos());
    }
  }
  return std::nullopt;
}

bool IsRetryable(const grpc::Status& status) {
  if (status.error_code() == grpc::StatusCode::UNAVAILABLE) return true;
  return status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED &&
         (RetryDelayOf(status).has_value() || ServerThreadsExhausted(status));
}

bool ServerThreadsExhausted(const grpc::Status& status) {
  // gRPC's own message (src/cpp/server/server_cc.cc, the sync server's ErrorMethodHandler): no
  // code or detail tells it apart from our limits.
  return status.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED &&
         status.error_message() == "Server Threadpool Exhausted";
}

}  // namespace membrane::client
