#include "client/job_event_sink.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "proto/crc32c.h"

namespace membrane::client {

void JobEventSink::Consume(const v1::JobEvent& event) {
  ++events_in_call_;
  switch (event.event_case()) {
    case v1::JobEvent::kAccepted:
      job_id_ = event.accepted().job_id();
      upload_parts_ = event.accepted().upload_parts();
      if (on_accepted_) on_accepted_(job_id_);
      events_in_call_ = 0;
      progress_.Finish(absl::StrFormat("job %s accepted, queue position %d", job_id_,
                                       event.accepted().queue_position()));
      break;
    case v1::JobEvent::kSnapshot:
      // WatchJob starts over from the job's first event.
      job_id_ = event.snapshot().id();
      if (event.snapshot().parameters().origin_size() == 3) {
        for (int k = 0; k < 3; ++k) origin_[k] = event.snapshot().parameters().origin(k);
      }
      mesh_format_ = event.snapshot().parameters().mesh_format();
      replay_index_ = 0;
      events_in_call_ = 0;
      break;
    case v1::JobEvent::kStage:
    case v1::JobEvent::kGeneration:
    case v1::JobEvent::kProgress: ConsumeProgress(event); break;
    case v1::JobEvent::kResult:
      statistics_json_ = event.result().statistics_json();
      mesh_summary_ = event.result().mesh();
      mesh_bytes_ = event.result().mesh_bytes();
      mesh_crc32c_ = event.result().mesh_crc32c();
      mesh_.clear();
      mesh_.reserve(mesh_bytes_);
      break;
    case v1::JobEvent::kMeshChunk: mesh_ += event.mesh_chunk(); break;
    case v1::JobEvent::kDone:
      done_ = true;
      final_ = event.done();
      break;
    case v1::JobEvent::EVENT_NOT_SET: break;
  }
}

void JobEventSink::ConsumeProgress(const v1::JobEvent& event) {
  if (replay_index_++ < progress_seen_) return;  // shown before the call dropped
  ++progress_seen_;
  if (event.has_generation()) {
    const v1::GenerationEvent& e = event.generation();
    GenerationStats g;
    g.generation = e.generation();
    g.plate_size = e.plate_size();
    g.soft_voxels = e.soft_voxels();
    g.started_contractions = e.started_contractions();
    g.backtrackings = e.backtrackings();
    g.seconds = e.seconds();
    g.handle_retry = e.handle_retry();
    // A kept retry's row replaces the row of its generation, and those after it.
    if (g.handle_retry && g.generation >= 1 &&
        static_cast<size_t>(g.generation) <= generations_.size() + 1) {
      generations_.resize(g.generation - 1);
    }
    generations_.push_back(g);
    progress_.GenerationFinished(g, e.planned_generations());
    return;
  }
  if (event.has_progress()) {
    const v1::StageProgress& p = event.progress();
    progress_.Progress(p.stage(), p.has_fraction() ? std::optional<double>(p.fraction())
                                                    : std::nullopt,
                       p.seconds());
    return;
  }
  const v1::StageEvent& s = event.stage();
  if (s.phase() == v1::StageEvent::STARTED) {
    progress_.Begin(s.line());
  } else {
    progress_.Finish(s.line());
    warnings_.insert(warnings_.end(), s.warnings().begin(), s.warnings().end());
  }
}

absl::Status JobEventSink::Outcome() const {
  if (!done_) return absl::UnavailableError("the job's stream ended before the job did");
  if (final_.state() != v1::SUCCEEDED) {
    const auto code = static_cast<absl::StatusCode>(final_.status().code());
    return absl::Status(code == absl::StatusCode::kOk ? absl::StatusCode::kInternal : code,
                        absl::StrCat("server: job ", job_id_, ": ", final_.status().message()));
  }
  if (mesh_.size() != mesh_bytes_ || Crc32c(mesh_) != mesh_crc32c_) {
    return absl::DataLossError(absl::StrFormat(
        "the mesh of job %s arrived damaged: %d of %d bytes, CRC-32C %08x instead of %08x",
        job_id_, mesh_.size(), mesh_bytes_, Crc32c(mesh_), mesh_crc32c_));
  }
  return absl::OkStatus();
}

}  // namespace membrane::client
