// One reconstruction job as the server holds it: its state, the events it produced so far
// (for every watcher, however late), its result, and its cancel token. Thread-safe: the
// worker writes, any number of handlers read and wait.
#ifndef MEMBRANE_SERVER_JOB_H_
#define MEMBRANE_SERVER_JOB_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "core/base/cancel_token.h"
#include "membrane/v1/reconstruction.pb.h"
#include "server/event_log.h"
#include "server/shared_bytes.h"
#include "server/upload_memory.h"

namespace membrane::server {

class Job {
 public:
  // Called once, when the job ends, whatever ends it (the worker, or a cancel while it is
  // queued): its final state and status, the time since it was created, the bytes of its
  // mesh, and whether it ran (false: it ended QUEUED, no worker ever started it). Called under
  // the job's lock: it must not call the job.
  using FinishHook = std::function<void(v1::JobState state, const absl::Status& status,
                                        absl::Duration age, uint64_t mesh_bytes, bool ran)>;

  // A QUEUED job. `upload` is the Draco cloud (kept until the job runs); `upload_hold` its
  // bytes in the server's memory for uploads, given back by ReleaseUploadHold() or when the
  // job ends. `on_finish` may be empty.
  Job(std::string id, std::string peer, v1::Parameters parameters, std::string upload,
      UploadMemory::Hold upload_hold = {}, FinishHook on_finish = nullptr);

  // A finished job as a durable store wrote it down (JobStore): `snapshot` (id, peer,
  // parameters, times, state and error), its stage, progress and generation `events`, and for a
  // SUCCEEDED job its statistics, mesh check and mesh. It is done at once; no hook runs.
  static std::shared_ptr<Job> Restore(const v1::Job& snapshot, std::vector<v1::JobEvent> events,
                                      std::string statistics_json, v1::MeshSummary summary,
                                      std::string mesh);

  // A job the previous process accepted and did not end, to run again from its kept
  // `upload`: QUEUED, with the id, peer, parameters and creation time of `snapshot`, and no
  // events (the run starts over). Its upload holds no UploadMemory.
  static std::shared_ptr<Job> Resume(const v1::Job& snapshot, std::string upload,
                                     FinishHook on_finish);

  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  const std::string& id() const { return id_; }
  const std::string& peer() const { return peer_; }
  // The name of the client (--token-file) that submitted the job; empty without tokens.
  const std::string& client() const { return client_; }
  // Sets client(); once, before the job is shared.
  void set_client(std::string client) { client_ = std::move(client); }
  const v1::Parameters& parameters() const { return parameters_; }
  CancelToken& cancel_token() { return cancel_; }

  // The upload, handed over once to the worker (later calls return an empty string).
  std::string TakeUpload() ABSL_LOCKS_EXCLUDED(mutex_);
  // Gives the upload's bytes back to the server's memory for uploads: the worker calls it once
  // the upload is decoded (and gone). Ending the job does it too.
  void ReleaseUploadHold() ABSL_LOCKS_EXCLUDED(mutex_);
  uint64_t upload_bytes() const { return upload_bytes_; }
  // The sizes of the upload's Draco parts (UploadHeader.upload_part_bytes, checked by
  // CheckDracoPartBytes); empty for an upload of one part.
  const std::vector<uint64_t>& upload_part_bytes() const { return upload_part_bytes_; }
  // Sets upload_part_bytes(); once, before the job is shared.
  void set_upload_part_bytes(std::vector<uint64_t> sizes) {
    upload_part_bytes_ = std::move(sizes);
  }
  // Calls `read` with the upload (empty once taken), under the job's lock: `read` must not
  // call the job. For a store that keeps the upload beside the job.
  void ReadUpload(const std::function<void(absl::string_view)>& read) const
      ABSL_LOCKS_EXCLUDED(mutex_);

  // The resource as GetJob returns it. A job that has ended but is not closed yet (its end not
  // yet written down, see closed()) is RUNNING here, without its error, mesh size or finish
  // time: a client told SUCCEEDED can fetch the result at once, and no crash takes it back.
  v1::Job Snapshot() const ABSL_LOCKS_EXCLUDED(mutex_);
  // The job as a durable store writes it down: Snapshot() with the end as soon as there is one.
  v1::Job RecordSnapshot() const ABSL_LOCKS_EXCLUDED(mutex_);
  // Snapshot()'s state.
  v1::JobState state() const ABSL_LOCKS_EXCLUDED(mutex_);
  // Ended (SUCCEEDED, FAILED or CANCELLED), whether or not closed.
  bool done() const ABSL_LOCKS_EXCLUDED(mutex_);

  // Followers deliver a job's end (ResultHeader, mesh, JobDone) only once it is closed: done,
  // and, when a durable store asked for it (RequireEndRecord), its end written down
  // (MarkEndRecorded), so that no client is told of an end that a crash would undo.
  bool closed() const ABSL_LOCKS_EXCLUDED(mutex_);
  // From now on the job closes only once MarkEndRecorded is called. Call before the job can
  // end (before it is queued).
  void RequireEndRecord() ABSL_LOCKS_EXCLUDED(mutex_);
  // The store has written the job's end (or has given up writing it and keeps what lets it
  // run the job again): followers may deliver it.
  void MarkEndRecorded() ABSL_LOCKS_EXCLUDED(mutex_);

  // Updates the queue position (1 = next) of a QUEUED job.
  void SetQueuePosition(int position) ABSL_LOCKS_EXCLUDED(mutex_);
  // QUEUED -> RUNNING. False when the job is already done (cancelled while queued).
  bool Start() ABSL_LOCKS_EXCLUDED(mutex_);
  // Appends a stage, progress or generation event for every watcher; a StageEvent STARTED also
  // sets the job's current stage.
  void AddEvent(const v1::JobEvent& event) ABSL_LOCKS_EXCLUDED(mutex_);
  // Ends the job: SUCCEEDED with `statistics_json`, the mesh check and the Draco `mesh`, or
  // FAILED/CANCELLED
  // with `status`. A second call is ignored (the first outcome stands).
  void Succeed(std::string statistics_json, v1::MeshSummary summary, std::string mesh)
      ABSL_LOCKS_EXCLUDED(mutex_);
  void Fail(const absl::Status& status) ABSL_LOCKS_EXCLUDED(mutex_);
  // Asks the job to stop for `reason` ("cancelled by the client", "deadline expired", ...):
  // a QUEUED job ends CANCELLED at once; a RUNNING one has its token fired and ends when the
  // worker sees it (within 100 ms). Ignored once the job is done.
  void RequestCancel(const std::string& reason) ABSL_LOCKS_EXCLUDED(mutex_);
  // Asks a RUNNING job to stop because it ran too long: its token fires as for a cancel, and
  // it ends FAILED with DeadlineExceeded `reason` (cancel_status). Ignored once the job is
  // done or a cancel was asked for.
  void ExceedDeadline(const std::string& reason) ABSL_LOCKS_EXCLUDED(mutex_);
  // The status a job whose token fired ends with: Cancelled with the reason given to the
  // first RequestCancel, or ExceedDeadline's DeadlineExceeded; OK when neither was asked.
  absl::Status cancel_status() const ABSL_LOCKS_EXCLUDED(mutex_);

  // Stops the job's run for a server that stops and keeps the job to run it again when it
  // starts (a durable store): the cancel token fires, and a Fail that follows (the run's
  // Cancelled, or any other) is ignored, so the job does not end here; a Succeed still ends
  // it. Ignored once the job is done.
  void Interrupt() ABSL_LOCKS_EXCLUDED(mutex_);
  bool interrupted() const ABSL_LOCKS_EXCLUDED(mutex_);

  // Waits up to `timeout` for events past the first `next` or for the job to close, then
  // appends the events past `next` to `out` and returns how many there are now in all.
  size_t WaitForEvents(size_t next, absl::Duration timeout, std::vector<v1::JobEvent>& out) const
      ABSL_LOCKS_EXCLUDED(mutex_);

  // How a finished job ended, for its followers: the ResultHeader event (SUCCEEDED only), the
  // mesh (SUCCEEDED only; one immutable buffer shared by every follower, not a copy each),
  // and the JobDone event.
  struct Outcome {
    std::optional<v1::JobEvent> result;
    SharedBytes mesh;
    v1::JobEvent done;
  };
  // The outcome of a closed job; nullopt until the job is closed.
  std::optional<Outcome> Closing() const ABSL_LOCKS_EXCLUDED(mutex_);

  // The closing events of a finished job, closed or not (for the store that closes it):
  // ResultHeader, mesh chunks of at most `chunk_bytes` (SUCCEEDED only), then JobDone. Empty
  // while the job runs. The chunks copy the mesh: for one writer at a time (the store), not
  // for every follower (Closing, MeshChunkEvent).
  std::vector<v1::JobEvent> ClosingEvents(size_t chunk_bytes) const ABSL_LOCKS_EXCLUDED(mutex_);

  // The stage, progress and generation events so far.
  std::vector<v1::JobEvent> Events() const ABSL_LOCKS_EXCLUDED(mutex_);

  // When the job finished; InfinitePast while it runs.
  absl::Time finished_at() const ABSL_LOCKS_EXCLUDED(mutex_);

  // What the web console shows beside a SUCCEEDED job's mesh: a PNG preview of the mesh
  // (core/render) and a sample of the input points (float32 x y z, little-endian, in the
  // mesh's coordinates). The worker sets them before the job ends; a store may set the preview
  // of a restored job. Empty when none was set.
  void SetPreview(absl::string_view png) ABSL_LOCKS_EXCLUDED(mutex_);
  void SetPointSample(absl::string_view xyz) ABSL_LOCKS_EXCLUDED(mutex_);
  SharedBytes preview_png() const ABSL_LOCKS_EXCLUDED(mutex_);
  SharedBytes point_sample() const ABSL_LOCKS_EXCLUDED(mutex_);

 private:
  bool DoneLocked() const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  bool ClosedLocked() const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  void FinishLocked(v1::JobState state, const absl::Status& status)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // The job's snapshot, its end shown once closed (`as_closed`) or once done.
  v1::Job SnapshotLocked(bool as_closed) const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);
  // The outcome of a done job.
  Outcome OutcomeLocked() const ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_);

  const std::string id_;
  const std::string peer_;
  std::string client_;  // set once, before the job is shared
  const v1::Parameters parameters_;
  uint64_t upload_bytes_;  // set once, before the job is shared
  std::vector<uint64_t> upload_part_bytes_;  // set once, before the job is shared
  absl::Time created_at_;  // set once, before the job is shared
  const FinishHook on_finish_;
  CancelToken cancel_;

  mutable absl::Mutex mutex_;
  std::string upload_ ABSL_GUARDED_BY(mutex_);
  UploadMemory::Hold upload_hold_ ABSL_GUARDED_BY(mutex_);
  v1::JobState state_ ABSL_GUARDED_BY(mutex_) = v1::QUEUED;
  int queue_position_ ABSL_GUARDED_BY(mutex_) = 0;
  std::string stage_ ABSL_GUARDED_BY(mutex_);
  // What the job keeps after its run (events, statistics, mesh, preview, point sample) lies in
  // pages of its own (EventLog, SharedBytes): most of it is made while the run's freed arrays
  // are what the heap has free, where it would split them for the next job.
  EventLog events_ ABSL_GUARDED_BY(mutex_);
  absl::Status status_ ABSL_GUARDED_BY(mutex_);
  SharedBytes statistics_json_ ABSL_GUARDED_BY(mutex_);
  v1::MeshSummary mesh_summary_ ABSL_GUARDED_BY(mutex_);
  // Shared with the followers streaming it (Closing).
  SharedBytes mesh_ ABSL_GUARDED_BY(mutex_);
  uint32_t mesh_crc32c_ ABSL_GUARDED_BY(mutex_) = 0;  // of mesh_, once, not per follower
  absl::Time finished_at_ ABSL_GUARDED_BY(mutex_) = absl::InfinitePast();
  // Handed to HTTP handlers without a copy.
  SharedBytes preview_png_ ABSL_GUARDED_BY(mutex_);
  SharedBytes point_sample_ ABSL_GUARDED_BY(mutex_);
  absl::Status cancel_status_ ABSL_GUARDED_BY(mutex_);
  bool end_record_required_ ABSL_GUARDED_BY(mutex_) = false;
  bool end_recorded_ ABSL_GUARDED_BY(mutex_) = false;
  bool interrupted_ ABSL_GUARDED_BY(mutex_) = false;
};

// The MeshChunk event of the bytes [at, at + chunk_bytes) of `mesh` (fewer at its end).
v1::JobEvent MeshChunkEvent(absl::string_view mesh, size_t at, size_t chunk_bytes);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_H_
