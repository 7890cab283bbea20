// How the client waits between attempts at a call the server did not take: a busy server is
// asked again after the delay it gives (RetryInfo) or a backoff, with jitter, and an
// unreachable one as soon as a connection to it is made again.
#ifndef MEMBRANE_CLIENT_RETRY_WAIT_H_
#define MEMBRANE_CLIENT_RETRY_WAIT_H_

#include <grpcpp/channel.h>
#include <grpcpp/support/status.h>

#include "absl/time/time.h"
#include "client/backoff.h"

namespace membrane::client {

// True for a call that failed without reaching a server: UNAVAILABLE without a RetryInfo (a
// server shutting down sends one). Such a call is retried once the channel connects again.
bool Unreachable(const grpc::Status& status);

class RetryWait {
 public:
  // Waits on `channel` (not owned; it must outlive this), whose calls are being retried.
  explicit RetryWait(grpc::Channel& channel) : channel_(channel) {}

  // Blocks before the next attempt at a call that failed with `status` (IsRetryable), and
  // returns true then; false, at once or when `until` comes, when the next attempt would not
  // start before `until`.
  // - Busy (a RetryInfo, or no call thread free): the larger of the server's delay and a
  //   backoff from 250 ms doubling to 8 s, plus up to 20% jitter, so that the clients a full
  //   queue refused together do not all come back together.
  // - Unreachable: until the channel is connected (an event, not a poll: gRPC reconnects at
  //   most a second apart, see Connect), and at least a backoff from 100 ms doubling to 1 s,
  //   so that a balancer answering UNAVAILABLE for a backend that is down is not hammered.
  bool Wait(const grpc::Status& status, absl::Time until);

  // When the last Wait saw the channel connected; InfinitePast before.
  absl::Time connected_at() const { return connected_at_; }

 private:
  grpc::Channel& channel_;
  Backoff busy_{absl::Milliseconds(250), absl::Seconds(8)};
  Backoff reconnect_{absl::Milliseconds(100), absl::Seconds(1)};
  absl::Time connected_at_ = absl::InfinitePast();
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_RETRY_WAIT_H_
