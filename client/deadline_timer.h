// --timeout: a thread that cancels a reconstruction's CancelToken when its time is up.
#ifndef MEMBRANE_CLIENT_DEADLINE_TIMER_H_
#define MEMBRANE_CLIENT_DEADLINE_TIMER_H_

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "client/timer_clock.h"
#include "core/base/cancel_token.h"

namespace membrane::client {

class DeadlineTimer {
 public:
  // Cancels `token` (not owned; must outlive the timer) `seconds` from now on the steady clock,
  // unless the timer is destroyed first. `seconds` <= 0 means no deadline: no thread is
  // started.
  DeadlineTimer(double seconds, CancelToken* token);
  // The same, `seconds` from now on `clock` (not owned; must outlive the timer; null: the
  // steady clock).
  DeadlineTimer(double seconds, CancelToken* token, TimerClock* clock);
  // Stops the thread without cancelling (the work finished in time) and joins it.
  ~DeadlineTimer();

  DeadlineTimer(const DeadlineTimer&) = delete;
  DeadlineTimer& operator=(const DeadlineTimer&) = delete;

  // True once the deadline has passed and the token was cancelled by this timer, so that a
  // Cancelled status can be reported as a timeout rather than a failure.
  bool expired() const { return expired_.load(); }

 private:
  void WaitThenCancel(TimerClock::TimePoint deadline, CancelToken* token);

  SteadyTimerClock steady_clock_;  // the clock when none is given
  TimerClock* const clock_;
  std::mutex mutex_;
  std::condition_variable stop_requested_;
  bool stopping_ = false;  // guarded by mutex_
  std::atomic<bool> expired_{false};
  std::thread thread_;  // last: started after the members it uses exist
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_DEADLINE_TIMER_H_
