// A JobStore that also writes its jobs to a directory (membraned --store-dir), so that finished
// jobs and their results survive a crash or a restart of the server: a client can still fetch
// its mesh with WatchJob, and GetJob and ListJobs still show the job, until it expires.
//
// A job is written when it is added and again when it ends, to DIR/<id>.job (a new file
// renamed over the old, after fsync): the stream WatchJob sends for it, each message
// length-delimited: the v1.Job snapshot, the stage and generation events, and once it has
// ended its ResultHeader, mesh chunks and JobDone. Writes happen on the store's own thread;
// only Add waits for its write (one small file), so that no worker waits for the disk.
//
// Uploads are not kept: a job the previous process left queued or running is restored as
// FAILED (UNAVAILABLE, "submit it again"), which tells its client what happened, where an
// in-memory store would answer NOT_FOUND.
#ifndef MEMBRANE_SERVER_DISK_JOB_STORE_H_
#define MEMBRANE_SERVER_DISK_JOB_STORE_H_

#include <deque>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "server/in_memory_job_store.h"
#include "server/job_store.h"

namespace membrane::server {

class DiskJobStore : public JobStore {
 public:
  // Touches nothing on disk before Load().
  explicit DiskJobStore(std::string dir);
  // Writes what is pending, then stops the writer.
  ~DiskJobStore() override;

  DiskJobStore(const DiskJobStore&) = delete;
  DiskJobStore& operator=(const DiskJobStore&) = delete;

  // Creates the directory when missing and reads every DIR/*.job into memory: finished jobs as
  // they were, unfinished ones ended FAILED as above (and written so). A record that cannot be
  // read (truncated, corrupted, a mesh that fails its CRC) is skipped, logged as
  // store_unreadable, and left in place. Returns how many jobs were loaded; Unavailable
  // naming the directory when it cannot be created or listed. Call once, before Add.
  absl::StatusOr<int> Load();

  // Returns once the job is written (or its write failed and was logged): a client told that
  // its job was accepted finds it after a crash.
  void Add(std::shared_ptr<Job> job) override;
  std::shared_ptr<Job> Find(const std::string& id) const override;
  std::vector<std::shared_ptr<Job>> List() const override;
  // Also deletes their files.
  int RemoveFinishedBefore(absl::Time cutoff) override;
  void Finished(const std::string& id) override;

  // Returns once every write asked for so far is on disk (or failed, and was logged as
  // store_write_failed; the job stays in memory).
  void Flush();

 private:
  // Asks the writer for the job's current state; returns the write's ticket (asked_).
  int64_t Enqueue(const std::string& id);
  // Returns once the write with `ticket` (and every one before it) is done.
  void WaitFor(int64_t ticket);
  void WriterLoop();
  absl::Status Write(const Job& job) const;
  std::string PathOf(const std::string& id) const;

  const std::string dir_;
  InMemoryJobStore memory_;
  absl::Mutex mutex_;
  std::deque<std::string> pending_ ABSL_GUARDED_BY(mutex_);
  int64_t asked_ ABSL_GUARDED_BY(mutex_) = 0;  // writes enqueued so far
  int64_t done_ ABSL_GUARDED_BY(mutex_) = 0;   // of those, the ones finished
  bool stopping_ ABSL_GUARDED_BY(mutex_) = false;
  std::thread writer_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_DISK_JOB_STORE_H_
