#include "client/backoff.h"

#include <algorithm>

#include "absl/random/random.h"

namespace membrane::client {

absl::Duration Backoff::Next(std::optional<absl::Duration> server_hint) {
  absl::BitGen random;
  const absl::Duration jittered = next_ * absl::Uniform(random, 1.0, 1.2);
  next_ = std::min(next_ * 2, max_);
  return server_hint.has_value() ? std::max(jittered, *server_hint) : jittered;
}

}  // namespace membrane::client
