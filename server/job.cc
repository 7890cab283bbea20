#include "server/job.h"

#include <algorithm>
#include <utility>

#include "proto/crc32c.h"
#include "server/rpc_status.h"

namespace membrane::server {

Job::Job(std::string id, std::string peer, v1::Parameters parameters, std::string upload,
         UploadMemory::Hold upload_hold, FinishHook on_finish)
    : id_(std::move(id)),
      peer_(std::move(peer)),
      parameters_(std::move(parameters)),
      upload_bytes_(upload.size()),
      created_at_(absl::Now()),
      on_finish_(std::move(on_finish)),
      upload_(std::move(upload)),
      upload_hold_(std::move(upload_hold)) {}

std::shared_ptr<Job> Job::Restore(const v1::Job& snapshot, std::vector<v1::JobEvent> events,
                                  std::string statistics_json, v1::MeshSummary summary,
                                  std::string mesh) {
  auto job = std::make_shared<Job>(snapshot.id(), snapshot.peer(), snapshot.parameters(),
                                   std::string());
  const auto at = [](double unix_seconds) {
    return absl::UnixEpoch() + absl::Seconds(unix_seconds);
  };
  job->client_ = snapshot.client();
  job->created_at_ = at(snapshot.created_unix_seconds());
  job->upload_bytes_ = snapshot.upload_bytes();
  absl::MutexLock lock(&job->mutex_);
  for (const v1::JobEvent& event : events) job->events_.Append(event);
  job->statistics_json_ = SharedBytes::Copy(statistics_json);
  job->mesh_summary_ = std::move(summary);
  job->mesh_ = SharedBytes::Copy(mesh);
  job->mesh_crc32c_ = Crc32c(job->mesh_.view());
  job->state_ = snapshot.state();
  job->status_ = FromRpcStatus(snapshot.error());
  job->finished_at_ = at(snapshot.finished_unix_seconds());
  return job;
}

std::shared_ptr<Job> Job::Resume(const v1::Job& snapshot, std::string upload,
                                 FinishHook on_finish) {
  auto job = std::make_shared<Job>(snapshot.id(), snapshot.peer(), snapshot.parameters(),
                                   std::move(upload), UploadMemory::Hold{}, std::move(on_finish));
  job->client_ = snapshot.client();
  job->created_at_ = absl::UnixEpoch() + absl::Seconds(snapshot.created_unix_seconds());
  return job;
}

void Job::ReadUpload(const std::function<void(absl::string_view)>& read) const {
  absl::MutexLock lock(&mutex_);
  read(upload_);
}

std::vector<v1::JobEvent> Job::Events() const {
  std::vector<v1::JobEvent> events;
  absl::MutexLock lock(&mutex_);
  events_.CopyFrom(0, events);
  return events;
}

std::string Job::TakeUpload() {
  absl::MutexLock lock(&mutex_);
  return std::exchange(upload_, std::string());
}

void Job::ReleaseUploadHold() {
  absl::MutexLock lock(&mutex_);
  upload_hold_.Release();
}

v1::Job Job::Snapshot() const {
  absl::MutexLock lock(&mutex_);
  return SnapshotLocked(/*as_closed=*/true);
}

v1::Job Job::RecordSnapshot() const {
  absl::MutexLock lock(&mutex_);
  return SnapshotLocked(/*as_closed=*/false);
}

v1::Job Job::SnapshotLocked(bool as_closed) const {
  // Until the end is written down, a client sees the job running: its end, result and error
  // come together with the record that makes them durable.
  const bool ended = as_closed ? ClosedLocked() : DoneLocked();
  v1::Job job;
  job.set_id(id_);
  job.set_state(ended || !DoneLocked() ? state_ : v1::RUNNING);
  job.set_queue_position(state_ == v1::QUEUED ? queue_position_ : 0);
  job.set_stage(stage_);
  if (ended && !status_.ok()) *job.mutable_error() = ToRpcStatus(status_);
  job.set_peer(peer_);
  job.set_client(client_);
  job.set_upload_bytes(upload_bytes_);
  if (ended) job.set_mesh_bytes(mesh_.size());
  job.set_created_unix_seconds(absl::ToDoubleSeconds(created_at_ - absl::UnixEpoch()));
  if (ended) {
    job.set_finished_unix_seconds(absl::ToDoubleSeconds(finished_at_ - absl::UnixEpoch()));
  }
  *job.mutable_parameters() = parameters_;
  return job;
}

v1::JobState Job::state() const {
  absl::MutexLock lock(&mutex_);
  return DoneLocked() && !ClosedLocked() ? v1::RUNNING : state_;
}

bool Job::done() const {
  absl::MutexLock lock(&mutex_);
  return DoneLocked();
}

bool Job::closed() const {
  absl::MutexLock lock(&mutex_);
  return ClosedLocked();
}

bool Job::ClosedLocked() const {
  return DoneLocked() && (end_recorded_ || !end_record_required_);
}

void Job::RequireEndRecord() {
  absl::MutexLock lock(&mutex_);
  end_record_required_ = true;
}

void Job::MarkEndRecorded() {
  absl::MutexLock lock(&mutex_);
  end_recorded_ = true;
}

bool Job::DoneLocked() const {
  return state_ == v1::SUCCEEDED || state_ == v1::FAILED || state_ == v1::CANCELLED;
}

void Job::SetQueuePosition(int position) {
  absl::MutexLock lock(&mutex_);
  queue_position_ = position;
}

bool Job::Start() {
  absl::MutexLock lock(&mutex_);
  if (state_ != v1::QUEUED) return false;
  state_ = v1::RUNNING;
  return true;
}

void Job::AddEvent(const v1::JobEvent& event) {
  absl::MutexLock lock(&mutex_);
  if (event.has_stage() && event.stage().phase() == v1::StageEvent::STARTED) {
    stage_ = event.stage().stage();
  }
  events_.Append(event);
}

void Job::Succeed(std::string statistics_json, v1::MeshSummary summary, std::string mesh) {
  absl::MutexLock lock(&mutex_);
  if (DoneLocked()) return;
  statistics_json_ = SharedBytes::Copy(statistics_json);
  mesh_summary_ = std::move(summary);
  mesh_ = SharedBytes::Copy(mesh);
  mesh_crc32c_ = Crc32c(mesh_.view());
  FinishLocked(v1::SUCCEEDED, absl::OkStatus());
}

void Job::Fail(const absl::Status& status) {
  absl::MutexLock lock(&mutex_);
  if (DoneLocked() || interrupted_) return;
  FinishLocked(status.code() == absl::StatusCode::kCancelled ? v1::CANCELLED : v1::FAILED,
               status);
}

void Job::RequestCancel(const std::string& reason) {
  absl::MutexLock lock(&mutex_);
  if (DoneLocked()) return;
  if (cancel_status_.ok()) cancel_status_ = absl::CancelledError(reason);
  cancel_.Cancel();
  if (state_ == v1::QUEUED) FinishLocked(v1::CANCELLED, absl::CancelledError(reason));
}

void Job::Interrupt() {
  absl::MutexLock lock(&mutex_);
  if (DoneLocked()) return;
  interrupted_ = true;
  cancel_.Cancel();
}

bool Job::interrupted() const {
  absl::MutexLock lock(&mutex_);
  return interrupted_;
}

void Job::ExceedDeadline(const std::string& reason) {
  absl::MutexLock lock(&mutex_);
  if (DoneLocked() || !cancel_status_.ok()) return;
  cancel_status_ = absl::DeadlineExceededError(reason);
  cancel_.Cancel();
}

absl::Status Job::cancel_status() const {
  absl::MutexLock lock(&mutex_);
  return cancel_status_;
}

void Job::FinishLocked(v1::JobState state, const absl::Status& status) {
  const bool ran = state_ != v1::QUEUED;
  state_ = state;
  status_ = status;
  stage_.clear();
  upload_.clear();
  upload_.shrink_to_fit();
  upload_hold_.Release();
  finished_at_ = absl::Now();
  if (on_finish_) on_finish_(state, status, finished_at_ - created_at_, mesh_.size(), ran);
}

size_t Job::WaitForEvents(size_t next, absl::Duration timeout,
                          std::vector<v1::JobEvent>& out) const {
  absl::MutexLock lock(&mutex_);
  auto ready = [this, next]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mutex_) {
    return events_.size() > next || ClosedLocked();
  };
  mutex_.AwaitWithTimeout(absl::Condition(&ready), timeout);
  events_.CopyFrom(next, out);
  return std::max(next, events_.size());
}

std::optional<Job::Outcome> Job::Closing() const {
  absl::MutexLock lock(&mutex_);
  if (!ClosedLocked()) return std::nullopt;
  return OutcomeLocked();
}

Job::Outcome Job::OutcomeLocked() const {
  Outcome outcome;
  if (state_ == v1::SUCCEEDED) {
    v1::ResultHeader* result = outcome.result.emplace().mutable_result();
    result->set_statistics_json(std::string(statistics_json_.view()));
    result->set_mesh_bytes(mesh_.size());
    result->set_mesh_crc32c(mesh_crc32c_);
    *result->mutable_mesh() = mesh_summary_;
    outcome.mesh = mesh_;
  }
  v1::JobDone* done = outcome.done.mutable_done();
  done->set_state(state_);
  *done->mutable_status() = ToRpcStatus(status_);
  return outcome;
}

std::vector<v1::JobEvent> Job::ClosingEvents(size_t chunk_bytes) const {
  std::vector<v1::JobEvent> events;
  std::optional<Outcome> outcome;
  {
    absl::MutexLock lock(&mutex_);
    if (!DoneLocked()) return events;
    outcome = OutcomeLocked();
  }
  if (outcome->result.has_value()) {
    events.push_back(std::move(*outcome->result));
    for (size_t at = 0; at < outcome->mesh.size(); at += chunk_bytes) {
      events.push_back(MeshChunkEvent(outcome->mesh.view(), at, chunk_bytes));
    }
  }
  events.push_back(std::move(outcome->done));
  return events;
}

v1::JobEvent MeshChunkEvent(absl::string_view mesh, size_t at, size_t chunk_bytes) {
  v1::JobEvent event;
  event.set_mesh_chunk(mesh.data() + at, std::min(chunk_bytes, mesh.size() - at));
  return event;
}

absl::Time Job::finished_at() const {
  absl::MutexLock lock(&mutex_);
  return finished_at_;
}

void Job::SetPreview(absl::string_view png) {
  SharedBytes shared = SharedBytes::Copy(png);
  absl::MutexLock lock(&mutex_);
  preview_png_ = std::move(shared);
}

void Job::SetPointSample(absl::string_view xyz) {
  SharedBytes shared = SharedBytes::Copy(xyz);
  absl::MutexLock lock(&mutex_);
  point_sample_ = std::move(shared);
}

SharedBytes Job::preview_png() const {
  absl::MutexLock lock(&mutex_);
  return preview_png_;
}

SharedBytes Job::point_sample() const {
  absl::MutexLock lock(&mutex_);
  return point_sample_;
}

}  // namespace membrane::server
