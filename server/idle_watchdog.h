// Ends calls that stop making progress (--stall-seconds): a Reconstruct call whose upload has
// made no progress that long (what counts as progress is the caller's: bytes, for uploads), or
// a call whose client has read nothing of an event written to it that long, is cancelled. So
// a stalled client (alive enough to answer keepalive pings) cannot hold a call thread, or its
// upload's memory, for ever. One thread watches every call. The same mechanism bounds a job's
// running time (--max-job-seconds): a watch that is never touched fires once its limit passes.
#ifndef MEMBRANE_SERVER_IDLE_WATCHDOG_H_
#define MEMBRANE_SERVER_IDLE_WATCHDOG_H_

#include <cstdint>
#include <functional>
#include <thread>

#include <grpcpp/server_context.h>

#include "absl/base/thread_annotations.h"
#include "absl/container/flat_hash_map.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "server/clock.h"

namespace membrane::server {

class IdleWatchdog {
 public:
  // `idle_limit` <= 0: watches nothing (Watch objects are inert). Idle time is read on
  // `clock` (not owned; it must outlive the watchdog), which is looked at every quarter of the
  // limit (at most every second); `on_cut` (may be empty) runs, on the watchdog's thread, for
  // each call it cancels.
  IdleWatchdog(absl::Duration idle_limit, const Clock& clock,
               std::function<void()> on_cut = nullptr);
  // Stops the watching thread; every Watch must be gone by then.
  ~IdleWatchdog();
  IdleWatchdog(const IdleWatchdog&) = delete;
  IdleWatchdog& operator=(const IdleWatchdog&) = delete;

  // One call (or job) under watch from its creation to its destruction, which must come
  // before what its cancel function reaches is destroyed (the handler's scope).
  class Watch {
   public:
    ~Watch();
    Watch(const Watch&) = delete;
    Watch& operator=(const Watch&) = delete;
    // The call made progress now.
    void Touch();
    // True once the watchdog cancelled the call for idling.
    bool fired() const;

   private:
    friend class IdleWatchdog;
    Watch(IdleWatchdog* owner, int64_t id) : owner_(owner), id_(id) {}
    IdleWatchdog* owner_;
    int64_t id_;
  };

  // Starts watching the call of `context`, as of now: TryCancel ends it.
  Watch Start(grpc::ServerContext* context) ABSL_LOCKS_EXCLUDED(mutex_);
  // Starts watching something that `cancel` ends, as of now. `cancel` runs once, on the
  // watchdog's thread under its lock: it must not touch the watchdog or its watches.
  Watch Start(std::function<void()> cancel) ABSL_LOCKS_EXCLUDED(mutex_);

  absl::Duration idle_limit() const { return limit_; }

 private:
  struct Entry {
    std::function<void()> cancel;
    absl::Time last;
    bool fired = false;
  };
  void Loop();

  const absl::Duration limit_;
  const Clock& clock_;
  const std::function<void()> on_cut_;
  mutable absl::Mutex mutex_;
  int64_t next_id_ ABSL_GUARDED_BY(mutex_) = 0;
  absl::flat_hash_map<int64_t, Entry> calls_ ABSL_GUARDED_BY(mutex_);
  bool stopping_ ABSL_GUARDED_BY(mutex_) = false;
  std::thread thread_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_IDLE_WATCHDOG_H_
