// Exponential backoff between retries of a call, honouring the delay a server asks for.
#ifndef MEMBRANE_CLIENT_BACKOFF_H_
#define MEMBRANE_CLIENT_BACKOFF_H_

#include <optional>

#include "absl/time/time.h"

namespace membrane::client {

class Backoff {
 public:
  // Delays start at `initial` and double up to `max`, each with up to 20% random jitter
  // (clients refused together must not return together).
  Backoff(absl::Duration initial, absl::Duration max) : next_(initial), max_(max) {}

  // The delay before the next attempt: the larger of the backoff and `server_hint` (a
  // RetryInfo), plus up to 20% jitter; never beyond 1.2 `max` unless the server asked for
  // more.
  absl::Duration Next(std::optional<absl::Duration> server_hint);

 private:
  absl::Duration next_;
  const absl::Duration max_;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_BACKOFF_H_
