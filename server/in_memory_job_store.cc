#include "server/in_memory_job_store.h"

#include <algorithm>
#include <iterator>
#include <utility>

namespace membrane::server {

absl::Status InMemoryJobStore::Add(std::shared_ptr<Job> job) {
  absl::MutexLock lock(&mutex_);
  jobs_.push_back(std::move(job));
  return absl::OkStatus();
}

void InMemoryJobStore::Remove(const std::string& id) {
  absl::MutexLock lock(&mutex_);
  std::erase_if(jobs_, [&id](const std::shared_ptr<Job>& job) { return job->id() == id; });
}

std::shared_ptr<Job> InMemoryJobStore::Find(const std::string& id) const {
  absl::MutexLock lock(&mutex_);
  // Linear: the store holds at most queue + workers + the jobs of one TTL.
  for (const std::shared_ptr<Job>& job : jobs_) {
    if (job->id() == id) return job;
  }
  return nullptr;
}

std::vector<std::shared_ptr<Job>> InMemoryJobStore::List() const {
  absl::MutexLock lock(&mutex_);
  return std::vector<std::shared_ptr<Job>>(jobs_.rbegin(), jobs_.rend());
}

int InMemoryJobStore::RemoveFinishedBefore(absl::Time cutoff) {
  return static_cast<int>(TakeFinishedBefore(cutoff).size());
}

std::vector<std::shared_ptr<Job>> InMemoryJobStore::TakeFinishedBefore(absl::Time cutoff) {
  absl::MutexLock lock(&mutex_);
  const auto expired = [cutoff](const std::shared_ptr<Job>& job) {
    return job->done() && job->finished_at() < cutoff;
  };
  // Kept in order at the front; the expired ones end at the back, moved out.
  const auto first = std::stable_partition(
      jobs_.begin(), jobs_.end(), [&](const std::shared_ptr<Job>& job) { return !expired(job); });
  std::vector<std::shared_ptr<Job>> removed(std::make_move_iterator(first),
                                            std::make_move_iterator(jobs_.end()));
  jobs_.erase(first, jobs_.end());
  return removed;
}

}  // namespace membrane::server
