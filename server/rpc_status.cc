#include "server/rpc_status.h"

#include <string>

#include "google/rpc/error_details.pb.h"

namespace membrane::server {

grpc::Status ToGrpcStatus(const absl::Status& status) {
  if (status.ok()) return grpc::Status::OK;
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()), std::string(status.message()));
}

grpc::Status ToGrpcStatusWithRetry(const absl::Status& status, absl::Duration retry_delay) {
  google::rpc::RetryInfo retry;
  const int64_t nanos = absl::ToInt64Nanoseconds(retry_delay);
  retry.mutable_retry_delay()->set_seconds(nanos / 1'000'000'000);
  retry.mutable_retry_delay()->set_nanos(static_cast<int32_t>(nanos % 1'000'000'000));
  google::rpc::Status details = ToRpcStatus(status);
  details.add_details()->PackFrom(retry);
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()), std::string(status.message()),
                      details.SerializeAsString());
}

google::rpc::Status ToRpcStatus(const absl::Status& status) {
  google::rpc::Status out;
  out.set_code(static_cast<int>(status.code()));
  out.set_message(std::string(status.message()));
  return out;
}

absl::Status FromRpcStatus(const google::rpc::Status& status) {
  const int code = status.code();
  const absl::StatusCode absl_code = code >= 0 && code <= 16 ? static_cast<absl::StatusCode>(code)
                                                             : absl::StatusCode::kUnknown;
  return absl::Status(absl_code, status.message());
}

}  // namespace membrane::server
