// A TimerClock that stands still until the test moves it, and that returns from Advance only
// once every timer waiting on it has seen the new time: a test of a deadline neither sleeps
// nor races the timer's thread.
#ifndef MEMBRANE_TESTS_CLIENT_MANUAL_TIMER_CLOCK_H_
#define MEMBRANE_TESTS_CLIENT_MANUAL_TIMER_CLOCK_H_

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <vector>

#include "client/timer_clock.h"

namespace membrane::testing {

class ManualTimerClock final : public client::TimerClock {
 public:
  TimePoint Now() override;
  void WaitUntil(std::condition_variable& cv, std::unique_lock<std::mutex>& lock,
                 TimePoint deadline) override;

  // Blocks until `count` threads wait on this clock (a timer's thread has started waiting).
  void AwaitWaiters(int count);
  // The number of threads waiting on this clock now.
  int waiters();

  // Moves the clock forward by `step`, wakes every thread waiting on it, and returns once
  // each has acted on the new time: it waits again, or it has left the wait (a timer that
  // expired has cancelled its token). The timers waiting must outlive the call.
  void Advance(std::chrono::steady_clock::duration step);

 private:
  struct Waiter {
    int64_t id;
    std::condition_variable* cv;
    std::mutex* mutex;  // the waiter's own, which it holds but while waiting
  };

  std::mutex mutex_;  // taken after a waiter's mutex, never before
  std::condition_variable changed_;  // a waiter came or left
  TimePoint now_{};
  int64_t next_id_ = 0;
  std::vector<Waiter> waiting_;
};

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_CLIENT_MANUAL_TIMER_CLOCK_H_
