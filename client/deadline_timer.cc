#include "client/deadline_timer.h"

#include <chrono>

namespace membrane::client {

DeadlineTimer::DeadlineTimer(double seconds, CancelToken* token)
    : DeadlineTimer(seconds, token, nullptr) {}

DeadlineTimer::DeadlineTimer(double seconds, CancelToken* token, TimerClock* clock)
    : clock_(clock != nullptr ? clock : &steady_clock_) {
  if (seconds <= 0) return;
  const TimerClock::TimePoint deadline =
      clock_->Now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                          std::chrono::duration<double>(seconds));
  thread_ = std::thread([this, deadline, token] { WaitThenCancel(deadline, token); });
}

DeadlineTimer::~DeadlineTimer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_requested_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void DeadlineTimer::WaitThenCancel(TimerClock::TimePoint deadline, CancelToken* token) {
  std::unique_lock<std::mutex> lock(mutex_);
  // A stop that comes before the deadline wins, and one that comes with it too: the work
  // finished in time.
  while (!stopping_) {
    if (clock_->Now() >= deadline) {
      expired_.store(true);
      token->Cancel();
      return;
    }
    clock_->WaitUntil(stop_requested_, lock, deadline);
  }
}

}  // namespace membrane::client
