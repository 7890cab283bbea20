#include "tests/client/manual_timer_clock.h"

#include <algorithm>

namespace membrane::testing {

ManualTimerClock::TimePoint ManualTimerClock::Now() {
  std::lock_guard<std::mutex> lock(mutex_);
  return now_;
}

void ManualTimerClock::WaitUntil(std::condition_variable& cv,
                                 std::unique_lock<std::mutex>& lock, TimePoint deadline) {
  int64_t id = 0;
  {
    // Registered and checked in one step: an Advance either sees this waiter or came before
    // the check, so no move of the clock goes unnoticed.
    std::lock_guard<std::mutex> clock_lock(mutex_);
    if (now_ >= deadline) return;
    id = next_id_++;
    waiting_.push_back({id, &cv, lock.mutex()});
  }
  changed_.notify_all();
  cv.wait(lock);
  {
    std::lock_guard<std::mutex> clock_lock(mutex_);
    std::erase_if(waiting_, [id](const Waiter& w) { return w.id == id; });
  }
  changed_.notify_all();
}

void ManualTimerClock::AwaitWaiters(int count) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return static_cast<int>(waiting_.size()) >= count; });
}

int ManualTimerClock::waiters() {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(waiting_.size());
}

void ManualTimerClock::Advance(std::chrono::steady_clock::duration step) {
  std::vector<Waiter> woken;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    now_ += step;
    woken = waiting_;
  }
  // Under the waiter's mutex: it is then inside cv.wait, so the notification cannot be lost.
  for (const Waiter& w : woken) {
    std::lock_guard<std::mutex> lock(*w.mutex);
    w.cv->notify_all();
  }
  // Each woken waiter leaves the list holding its mutex, and releases that mutex only when it
  // waits again or is done; taking the mutex once more waits for that.
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] {
      return std::none_of(woken.begin(), woken.end(), [&](const Waiter& w) {
        return std::any_of(waiting_.begin(), waiting_.end(),
                           [&](const Waiter& v) { return v.id == w.id; });
      });
    });
  }
  for (const Waiter& w : woken) {
    std::lock_guard<std::mutex> lock(*w.mutex);
  }
}

}  // namespace membrane::testing
