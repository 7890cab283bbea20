// The clock a DeadlineTimer measures its time on: the steady clock in the program; a test
// moves a clock of its own by hand, so that it need not sleep to see a deadline pass.
#ifndef MEMBRANE_CLIENT_TIMER_CLOCK_H_
#define MEMBRANE_CLIENT_TIMER_CLOCK_H_

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace membrane::client {

class TimerClock {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;

  virtual ~TimerClock() = default;

  // The time now on this clock; never earlier than a time it returned before.
  virtual TimePoint Now() = 0;

  // Blocks on `cv` with `lock` released, as std::condition_variable::wait does, until this
  // clock reaches `deadline` or `cv` is notified; it may also return early for no reason
  // (callers check their condition again). Returns with `lock` held.
  virtual void WaitUntil(std::condition_variable& cv, std::unique_lock<std::mutex>& lock,
                         TimePoint deadline) = 0;
};

// std::chrono::steady_clock: not moved by changes to the wall clock.
class SteadyTimerClock final : public TimerClock {
 public:
  TimePoint Now() override;
  void WaitUntil(std::condition_variable& cv, std::unique_lock<std::mutex>& lock,
                 TimePoint deadline) override;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_TIMER_CLOCK_H_
