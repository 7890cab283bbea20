#include "server/job_scheduler.h"

#include <algorithm>
#include <system_error>
#include <thread>
#include <utility>

#include "absl/strings/str_format.h"

namespace membrane::server {

JobScheduler::JobScheduler(int workers, int queue_capacity, RunFn run)
    : queue_capacity_(queue_capacity), run_(std::move(run)) {
  for (int i = 0; i < workers; ++i) workers_.emplace_back([this] { WorkerLoop(); });
}

JobScheduler::~JobScheduler() { Shutdown(absl::ZeroDuration()); }

absl::Status JobScheduler::Submit(std::shared_ptr<Job> job) {
  absl::MutexLock lock(&mutex_);
  // Jobs cancelled while queued leave their place now rather than when a worker reaches them:
  // else they would fill the queue for nothing.
  if (std::erase_if(queue_, [](const std::shared_ptr<Job>& j) { return j->done(); }) > 0) {
    RenumberQueueLocked();
  }
  if (absl::Status s = CheckRoomLocked(); !s.ok()) return s;
  queue_.push_back(std::move(job));
  RenumberQueueLocked();
  return absl::OkStatus();
}

absl::Status JobScheduler::CheckRoom() const {
  absl::MutexLock lock(&mutex_);
  return CheckRoomLocked();
}

absl::Status JobScheduler::CheckRoomLocked() const {
  if (stopping_) return absl::UnavailableError("the server is shutting down; try another replica");
  // Jobs waiting beyond the idle workers count against the queue; those cancelled while
  // waiting do not.
  const size_t waiting = static_cast<size_t>(
      std::count_if(queue_.begin(), queue_.end(), [](const auto& j) { return !j->done(); }));
  if (waiting + running_.size() >= workers_.size() + queue_capacity_) {
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the server is busy: queue full (%d jobs waiting, %d running)", waiting,
        running_.size()));
  }
  return absl::OkStatus();
}

void JobScheduler::Resume(std::shared_ptr<Job> job) {
  absl::MutexLock lock(&mutex_);
  if (stopping_) return;
  queue_.push_back(std::move(job));
  RenumberQueueLocked();
}

void JobScheduler::RenumberQueueLocked() {
  int position = 1;
  for (const std::shared_ptr<Job>& job : queue_) job->SetQueuePosition(position++);
}

void JobScheduler::WorkerLoop() {
  while (true) {
    std::shared_ptr<Job> job;
    {
      absl::MutexLock lock(&mutex_);
      mutex_.Await(absl::Condition(
          +[](JobScheduler* s) ABSL_EXCLUSIVE_LOCKS_REQUIRED(s->mutex_) {
            return s->stopping_ || !s->queue_.empty();
          },
          this));
      if (queue_.empty()) return;  // stopping, nothing left
      job = std::move(queue_.front());
      queue_.pop_front();
      RenumberQueueLocked();
      running_.push_back(job);
    }
    // A thread of the job's own, which ends with it: glibc keeps the small blocks a thread
    // frees in that thread's cache (tcache), where the heap counts them as used. Freed in the
    // run's late stages, they lie among the run's freed arrays; on a worker that lives on they
    // would stay there and split the space the next job's arrays would take whole
    // (docs/memory-decisions.md, "What a job keeps lives outside the heap").
    // A process out of threads (RLIMIT_NPROC, memory) runs the job on the worker itself, as
    // the core's threads fall back: the same job, the worker's cache kept.
    try {
      std::thread([this, &job] { run_(job); }).join();
    } catch (const std::system_error&) {
      run_(job);
    }
    absl::MutexLock lock(&mutex_);
    running_.erase(std::find(running_.begin(), running_.end(), job));
  }
}

void JobScheduler::Shutdown(absl::Duration grace, Unfinished unfinished) {
  if (joined_) return;
  {
    absl::MutexLock lock(&mutex_);
    stopping_ = true;
    if (unfinished == Unfinished::kCancel) {
      for (const std::shared_ptr<Job>& job : queue_) {
        job->RequestCancel("the server shut down before the job started");
      }
    }
    queue_.clear();
    auto idle = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) { return running_.empty(); };
    if (!mutex_.AwaitWithTimeout(absl::Condition(&idle), grace)) {
      for (const std::shared_ptr<Job>& job : running_) {
        if (unfinished == Unfinished::kKeep) {
          job->Interrupt();
        } else {
          job->RequestCancel(absl::StrFormat(
              "the server shut down; the job did not finish within the %g s grace period",
              absl::ToDoubleSeconds(grace)));
        }
      }
    }
  }
  for (std::thread& worker : workers_) worker.join();
  joined_ = true;
}

int JobScheduler::queued() const {
  absl::MutexLock lock(&mutex_);
  // A job cancelled while queued stays in queue_ until a worker or the next Submit drops it.
  const auto waiting = [](const std::shared_ptr<Job>& job) { return !job->done(); };
  return static_cast<int>(std::count_if(queue_.begin(), queue_.end(), waiting));
}

int JobScheduler::running() const {
  absl::MutexLock lock(&mutex_);
  return static_cast<int>(running_.size());
}

}  // namespace membrane::server
