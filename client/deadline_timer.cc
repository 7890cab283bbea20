#include "client/deadline_timer.h"

#include <chrono>

namespace membrane::client {

DeadlineTimer::DeadlineTimer(double seconds, CancelToken* token) {
  if (seconds > 0)
    thread_ = std::thread([this, seconds, token] { WaitThenCancel(seconds, token); });
}

DeadlineTimer::~DeadlineTimer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_requested_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void DeadlineTimer::WaitThenCancel(double seconds, CancelToken* token) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(seconds));
  std::unique_lock<std::mutex> lock(mutex_);
  // wait_until returns true when stopping_ became true before the deadline.
  if (stop_requested_.wait_until(lock, deadline, [this] { return stopping_; })) return;
  expired_.store(true);
  token->Cancel();
}

}  // namespace membrane::client
