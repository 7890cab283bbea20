#include "client/retry_wait.h"

#include <chrono>
#include <optional>

#include "absl/time/clock.h"
#include "client/rpc_errors.h"

namespace membrane::client {

bool Unreachable(const grpc::Status& status) {
  return status.error_code() == grpc::StatusCode::UNAVAILABLE && !RetryDelayOf(status);
}

bool RetryWait::Wait(const grpc::Status& status, absl::Time until) {
  if (!Unreachable(status)) {
    const absl::Duration delay = busy_.Next(RetryDelayOf(status));
    if (absl::Now() + delay >= until) return false;
    absl::SleepFor(delay);
    return true;
  }
  const absl::Time not_before = absl::Now() + reconnect_.Next(std::nullopt);
  if (not_before >= until) return false;
  const auto chrono_until = until == absl::InfiniteFuture()
                                ? std::chrono::system_clock::time_point::max()
                                : absl::ToChronoTime(until);
  if (!channel_.WaitForConnected(chrono_until)) return false;
  connected_at_ = absl::Now();
  if (connected_at_ < not_before) absl::SleepFor(not_before - connected_at_);
  return true;
}

}  // namespace membrane::client
