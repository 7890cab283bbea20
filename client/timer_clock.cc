#include "client/timer_clock.h"

namespace membrane::client {

TimerClock::TimePoint SteadyTimerClock::Now() { return std::chrono::steady_clock::now(); }

void SteadyTimerClock::WaitUntil(std::condition_variable& cv, std::unique_lock<std::mutex>& lock,
                                 TimePoint deadline) {
  cv.wait_until(lock, deadline);
}

}  // namespace membrane::client
