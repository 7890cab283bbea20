// A JobStore that also writes its jobs to a directory (membraned --store-dir), so that an
// accepted job survives a crash or a restart of the server: a job the previous process did not
// end runs again, under its id, and a finished one still serves its mesh to WatchJob, GetJob
// and ListJobs, until it expires.
//
// Files, each written as a new file fsynced and renamed over the old, then the directory
// fsynced (StoreFiles::Write):
// - DIR/<id>.upload: the Draco upload, as a length-delimited v1.UploadHeader (its size and
//   CRC-32C) and the bytes. Written when the job is added; removed once its end is recorded.
// - DIR/<id>.job: the stream WatchJob sends for the job, each message length-delimited: the
//   v1.Job snapshot, the stage and generation events, and once it has ended its ResultHeader,
//   mesh chunks and JobDone. Written when the job is added and again when it ends.
// Add writes both before it returns, so a client told that its job was accepted finds it after
// a crash; a job's end is written on the store's own thread (no worker waits for the disk), and
// only then do followers deliver it (Job::closed): a client never receives an end that a crash
// would undo.
//
// A disk that cannot be written makes the store unwritable (writable(), and the listener
// hears it): Add fails, and every probe_interval the writer tries a small write; the first
// write that succeeds makes it writable again and writes the ends that failed meanwhile.
#ifndef MEMBRANE_SERVER_DISK_JOB_STORE_H_
#define MEMBRANE_SERVER_DISK_JOB_STORE_H_

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "server/in_memory_job_store.h"
#include "server/job_store.h"
#include "server/store_files.h"

namespace membrane::server {

// The largest record of a job whose mesh (Draco or PLY) has at most `max_mesh_bytes`: the mesh
// and its chunks' framing, and the job's events (a snapshot, the stage and generation events
// and a progress event a second: well under a megabyte for a job of hours), with a margin.
int64_t RecordBytesFor(int64_t max_mesh_bytes);

struct DiskJobStoreOptions {
  // Largest DIR/<id>.job read at start-up: a larger one is skipped (store_unreadable) rather
  // than read whole. A record is the job's events and its mesh; a server sets it to
  // RecordBytesFor its largest result (--max-result-bytes), so that every result it returns is
  // written and read back.
  int64_t max_record_bytes = RecordBytesFor(int64_t{2} << 30);
  // Largest upload kept (--max-upload-bytes); its file may hold a few bytes more (the header).
  int64_t max_upload_bytes = int64_t{512} << 20;
  // While the disk cannot be written, how often the writer tries it again.
  absl::Duration probe_interval = absl::Seconds(1);
};

class DiskJobStore : public JobStore {
 public:
  // Touches nothing on disk before Load(). `files` are the file operations (a test's may fail).
  explicit DiskJobStore(std::string dir, DiskJobStoreOptions options = {},
                        std::unique_ptr<StoreFiles> files = PosixStoreFiles());
  // Writes what is pending, then stops the writer.
  ~DiskJobStore() override;

  DiskJobStore(const DiskJobStore&) = delete;
  DiskJobStore& operator=(const DiskJobStore&) = delete;

  // Makes the hook of a job Load resumes (the server's: metrics, then Finished(id)).
  using HookMaker = std::function<Job::FinishHook(const std::string& id)>;

  struct Loaded {
    int jobs = 0;  // every job loaded, the resumed ones included
    // The jobs the previous process accepted and did not end, with their uploads, QUEUED,
    // oldest first: the caller queues them (JobScheduler::Resume).
    std::vector<std::shared_ptr<Job>> resumed;
  };

  // Creates the directory when missing, checks that it can be written, and reads every
  // DIR/*.job: finished jobs as they were; unfinished ones resumed from their upload, or, when
  // the upload cannot be read, ended FAILED (UNAVAILABLE, "submit it again"; written so). A
  // record that cannot be trusted (truncated, corrupted, a mesh failing its CRC, over
  // max_record_bytes, not a regular file) is skipped, logged as store_unreadable, and left in
  // place. Removes half-written files and uploads whose job has ended or is gone. Unavailable
  // naming the directory when it cannot be created, listed or written (a start-up error).
  // Call once, before Add.
  absl::StatusOr<Loaded> Load(const HookMaker& make_hook);

  // Calls `listener` with writable() whenever it changes (from the thread that saw the change;
  // never under the store's lock). Set before Load.
  void SetWritableListener(std::function<void(bool writable)> listener);

  // Writes the job's upload and record; Unavailable "the job store DIR cannot be written: ..."
  // when either fails (what was written is removed; logged as store_write_failed).
  absl::Status Add(std::shared_ptr<Job> job) override;
  void Remove(const std::string& id) override;
  bool writable() const override;
  std::shared_ptr<Job> Find(const std::string& id) const override;
  std::vector<std::shared_ptr<Job>> List() const override;
  // Also deletes their files.
  int RemoveFinishedBefore(absl::Time cutoff) override;
  // Asks the writer to write the job's end; ignored once Close() was called.
  void Finished(const std::string& id) override;

  // Returns once every write asked for so far is on disk (or failed, and was logged as
  // store_write_failed; the job stays in memory and, its upload kept, runs again after a
  // restart).
  void Flush();
  // Flush, then write no more job ends: for a server that stops and leaves its unfinished
  // jobs on disk for the next start, whatever their calls do to them while it stops.
  void Close();

 private:
  // Asks the writer for the job's current state; returns the write's ticket (asked_).
  int64_t Enqueue(const std::string& id);
  // Returns once the write with `ticket` (and every one before it) is done.
  void WaitFor(int64_t ticket);
  void WriterLoop();
  // Writes the job's record; `ended` says whether it holds the job's end.
  absl::Status Write(const Job& job, bool& ended) const;
  // The writer's job: writes `id`'s record, and once its end is on disk removes its upload and
  // lets followers deliver the end.
  void WriteRecord(const std::string& id);
  // A small write, while the disk is known to fail: becomes writable when it succeeds.
  void Probe();
  void SetWritable(bool writable) ABSL_LOCKS_EXCLUDED(mutex_, listener_mutex_);
  std::string PathOf(const std::string& id) const;
  std::string UploadPathOf(const std::string& id) const;

  const std::string dir_;
  const DiskJobStoreOptions options_;
  const std::unique_ptr<StoreFiles> files_;
  InMemoryJobStore memory_;
  mutable absl::Mutex mutex_;
  std::deque<std::string> pending_ ABSL_GUARDED_BY(mutex_);
  int64_t asked_ ABSL_GUARDED_BY(mutex_) = 0;  // writes enqueued so far
  int64_t done_ ABSL_GUARDED_BY(mutex_) = 0;   // of those, the ones finished
  bool stopping_ ABSL_GUARDED_BY(mutex_) = false;
  bool closed_ ABSL_GUARDED_BY(mutex_) = false;
  bool writable_ ABSL_GUARDED_BY(mutex_) = true;
  // Jobs whose end could not be written: written again once the disk can be.
  std::vector<std::string> unwritten_ ABSL_GUARDED_BY(mutex_);
  // Held while the listener runs, so that it hears the changes in the order they happened.
  absl::Mutex listener_mutex_;
  std::function<void(bool)> listener_ ABSL_GUARDED_BY(listener_mutex_);
  std::thread writer_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_DISK_JOB_STORE_H_
