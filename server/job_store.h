// Where the server keeps its jobs. Handlers see only this interface, so a durable store
// (DiskJobStore; a database, a shared cache for several replicas) can replace the in-memory
// one without touching them.
#ifndef MEMBRANE_SERVER_JOB_STORE_H_
#define MEMBRANE_SERVER_JOB_STORE_H_

#include <memory>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/time/time.h"
#include "server/job.h"

namespace membrane::server {

class JobStore {
 public:
  virtual ~JobStore() = default;
  // Adds `job`, whose id must be new, once the store holds what it needs to finish it after
  // a crash (a durable store: the job and its upload, on disk). OK then; Unavailable naming
  // the cause when it cannot (a read-only or full disk), and the job is not added.
  virtual absl::Status Add(std::shared_ptr<Job> job) = 0;
  // Forgets the job `id`, added but then not queued after all (the queue filled meanwhile).
  virtual void Remove(const std::string& id) = 0;
  // False while the store knows that Add would fail (its disk cannot be written): the
  // server then refuses jobs before their upload, and health says NOT_SERVING.
  virtual bool writable() const { return true; }
  // The job with `id`, or null when unknown or expired.
  virtual std::shared_ptr<Job> Find(const std::string& id) const = 0;
  // Every job held, newest first.
  virtual std::vector<std::shared_ptr<Job>> List() const = 0;
  // Drops the jobs that finished before `cutoff`; returns how many.
  virtual int RemoveFinishedBefore(absl::Time cutoff) = 0;
  // Tells the store that the job `id` has ended. Called from the job's finish hook, under the
  // job's lock: the store must not call the job from here. A durable store writes it down.
  virtual void Finished(const std::string& id) { (void)id; }
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_STORE_H_
