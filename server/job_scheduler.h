// A bounded pool of workers fed by a bounded queue. A full queue is refused at once
// (RESOURCE_EXHAUSTED), never waited on: a client is told to come back instead of hanging.
#ifndef MEMBRANE_SERVER_JOB_SCHEDULER_H_
#define MEMBRANE_SERVER_JOB_SCHEDULER_H_

#include <deque>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "server/job.h"

namespace membrane::server {

class JobScheduler {
 public:
  // Runs each job with `run`, which must end the job (Succeed or Fail), on a thread started
  // for it by one of `workers` workers. At most `queue_capacity` jobs wait beyond those
  // running (with 0, a job is accepted only when a worker is idle).
  using RunFn = std::function<void(const std::shared_ptr<Job>&)>;
  JobScheduler(int workers, int queue_capacity, RunFn run);
  // Shutdown(absl::ZeroDuration()) unless it was called.
  ~JobScheduler();

  JobScheduler(const JobScheduler&) = delete;
  JobScheduler& operator=(const JobScheduler&) = delete;

  // Queues `job` and sets its queue position. ResourceExhausted "queue full (N jobs
  // waiting)" when the queue is full (jobs cancelled while queued do not count: they leave
  // the queue here); Unavailable "shutting down" once Shutdown has begun.
  absl::Status Submit(std::shared_ptr<Job> job) ABSL_LOCKS_EXCLUDED(mutex_);
  // What Submit would answer now (OK: it would queue the job): a check before the costly part
  // of accepting a job (writing its upload), which Submit's own answer still decides.
  absl::Status CheckRoom() const ABSL_LOCKS_EXCLUDED(mutex_);
  // Queues `job`, accepted by an earlier process (DiskJobStore::Load), whatever the queue
  // holds: it was accepted within that process's limits. Ignored once Shutdown has begun.
  void Resume(std::shared_ptr<Job> job) ABSL_LOCKS_EXCLUDED(mutex_);

  // What Shutdown does with the jobs it does not let finish.
  enum class Unfinished {
    kCancel,  // they end CANCELLED ("the server shut down ..."): nothing would run them again
    kKeep,    // queued ones are left as they are and running ones interrupted (Job::Interrupt),
              // so that a durable store keeps them unfinished for the next start
  };
  // Stops accepting jobs and takes the queued ones out of the queue; lets the running ones
  // finish for up to `grace`, then stops them; `unfinished` says how. Joins the workers.
  void Shutdown(absl::Duration grace, Unfinished unfinished = Unfinished::kCancel)
      ABSL_LOCKS_EXCLUDED(mutex_);

  // Jobs waiting for a worker (not those cancelled while waiting), and jobs on a worker.
  int queued() const ABSL_LOCKS_EXCLUDED(mutex_);
  int running() const ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  void WorkerLoop() ABSL_LOCKS_EXCLUDED(mutex_);
  void RenumberQueueLocked() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  absl::Status CheckRoomLocked() const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);

  const int queue_capacity_;
  const RunFn run_;
  mutable absl::Mutex mutex_;
  std::deque<std::shared_ptr<Job>> queue_ ABSL_GUARDED_BY(mutex_);
  std::vector<std::shared_ptr<Job>> running_ ABSL_GUARDED_BY(mutex_);
  bool stopping_ ABSL_GUARDED_BY(mutex_) = false;
  bool joined_ = false;  // touched only by Shutdown's caller
  std::vector<std::thread> workers_;  // last: started after the members they use exist
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_SCHEDULER_H_
