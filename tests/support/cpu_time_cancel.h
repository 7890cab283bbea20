// Cancels a CancelToken once the thread that armed it has spent a given amount of CPU time:
// a cancel that lands in the middle of the work, counted in the work's own time, however the
// machine schedules the test. A POSIX CPU-time timer on the thread's clock signals a watcher
// thread, which cancels: nothing polls and nothing sleeps.
#ifndef MEMBRANE_TESTS_SUPPORT_CPU_TIME_CANCEL_H_
#define MEMBRANE_TESTS_SUPPORT_CPU_TIME_CANCEL_H_

#include <pthread.h>
#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <future>
#include <thread>

#include "core/base/cancel_token.h"

namespace membrane::testing {

// CPU seconds used so far by the thread whose CPU clock is `clock`.
inline double ThreadCpuSeconds(clockid_t clock) {
  timespec ts;
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

class CancelAfterThreadCpu {
 public:
  // `token` is cancelled once the calling thread has used `seconds` more CPU time (to within
  // a scheduler tick). Aborts when the system refuses the clock, the timer or the thread.
  CancelAfterThreadCpu(CancelToken& token, double seconds) : token_(token) {
    if (pthread_getcpuclockid(pthread_self(), &clock_) != 0) std::abort();
    std::promise<pid_t> watcher_tid;
    std::future<pid_t> tid = watcher_tid.get_future();
    watcher_ = std::thread([this, &watcher_tid] { Watch(watcher_tid); });
    sigevent event{};
    event.sigev_notify = SIGEV_THREAD_ID;
    event.sigev_signo = Signal();
    event._sigev_un._tid = tid.get();  // sigev_notify_thread_id, which older glibc do not name
    if (timer_create(clock_, &event, &timer_) != 0) std::abort();
    const double at = ThreadCpuSeconds(clock_) + seconds;
    itimerspec when{};
    when.it_value.tv_sec = static_cast<time_t>(at);
    const double whole = static_cast<double>(when.it_value.tv_sec);
    when.it_value.tv_nsec = static_cast<long>((at - whole) * 1e9);
    if (timer_settime(timer_, TIMER_ABSTIME, &when, nullptr) != 0) std::abort();
  }

  // Disarms the timer if it has not fired, then wakes and joins the watcher.
  ~CancelAfterThreadCpu() {
    timer_delete(timer_);
    pthread_kill(watcher_.native_handle(), Signal());
    watcher_.join();
  }

  CancelAfterThreadCpu(const CancelAfterThreadCpu&) = delete;
  CancelAfterThreadCpu& operator=(const CancelAfterThreadCpu&) = delete;

  // The arming thread's CPU time (ThreadCpuSeconds) when the token was cancelled; < 0 when it
  // has not been.
  double cancelled_at() const { return cancelled_at_.load(); }
  // The arming thread's CPU time now (call it on that thread or any other).
  double now() const { return ThreadCpuSeconds(clock_); }

 private:
  static int Signal() { return SIGRTMIN + 3; }

  // Blocks the signal on this thread only, so that it is waited for here and never delivered
  // elsewhere (the timer directs it to this thread), then waits for it once: from the timer,
  // cancel; from the destructor, just return.
  void Watch(std::promise<pid_t>& tid) {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, Signal());
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    tid.set_value(gettid());
    siginfo_t info;
    while (sigwaitinfo(&set, &info) < 0) {
    }
    if (info.si_code == SI_TIMER) {
      cancelled_at_.store(ThreadCpuSeconds(clock_));
      token_.Cancel();
    }
  }

  CancelToken& token_;
  clockid_t clock_;
  timer_t timer_{};
  std::thread watcher_;
  std::atomic<double> cancelled_at_{-1.0};
};

}  // namespace membrane::testing

#endif  // MEMBRANE_TESTS_SUPPORT_CPU_TIME_CANCEL_H_
