// The time the server's timers read: the result TTL and the stall watchdog. Passed in, so that
// tests move time forward instead of sleeping through it.
#ifndef MEMBRANE_SERVER_CLOCK_H_
#define MEMBRANE_SERVER_CLOCK_H_

#include "absl/time/clock.h"
#include "absl/time/time.h"

namespace membrane::server {

class Clock {
 public:
  virtual ~Clock() = default;
  // The current time; thread-safe, never earlier than a value it returned before.
  virtual absl::Time Now() const = 0;
};

// absl::Now().
class RealClock final : public Clock {
 public:
  absl::Time Now() const override { return absl::Now(); }
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_CLOCK_H_
