// JobStore in this process's memory: jobs are lost when the server stops.
#ifndef MEMBRANE_SERVER_IN_MEMORY_JOB_STORE_H_
#define MEMBRANE_SERVER_IN_MEMORY_JOB_STORE_H_

#include <memory>
#include <string>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/synchronization/mutex.h"
#include "server/job_store.h"

namespace membrane::server {

class InMemoryJobStore : public JobStore {
 public:
  absl::Status Add(std::shared_ptr<Job> job) override ABSL_LOCKS_EXCLUDED(mutex_);
  void Remove(const std::string& id) override ABSL_LOCKS_EXCLUDED(mutex_);
  std::shared_ptr<Job> Find(const std::string& id) const override ABSL_LOCKS_EXCLUDED(mutex_);
  std::vector<std::shared_ptr<Job>> List() const override ABSL_LOCKS_EXCLUDED(mutex_);
  int RemoveFinishedBefore(absl::Time cutoff) override ABSL_LOCKS_EXCLUDED(mutex_);
  // RemoveFinishedBefore, returning the jobs removed (for a store that also drops their files).
  std::vector<std::shared_ptr<Job>> TakeFinishedBefore(absl::Time cutoff)
      ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  mutable absl::Mutex mutex_;
  std::vector<std::shared_ptr<Job>> jobs_ ABSL_GUARDED_BY(mutex_);  // oldest first
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_IN_MEMORY_JOB_STORE_H_
