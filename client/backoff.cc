#include "client/backoff.h"

#include <algorithm>

#include "absl/random/random.h"

namespace membrane::client {

absl::Duration Backoff::Next(std::optional<absl::Duration> server_hint) {
  absl::BitGen random;
  const absl::Duration base = server_hint.has_value() ? std::max(next_, *server_hint) : next_;
  next_ = std::min(next_ * 2, max_);
  // On the server's delay too: every client a full queue refused gets the same one.
  return base * absl::Uniform(random, 1.0, 1.2);
}

}  // namespace membrane::client
