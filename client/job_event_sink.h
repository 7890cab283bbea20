// The client's end of a job's event stream (Reconstruct or WatchJob): shows the progress
// lines, keeps the generation rows, the statistics and the mesh. Survives re-attaching: a
// WatchJob replays the job's events from its first, and the ones already seen are skipped.
#ifndef MEMBRANE_CLIENT_JOB_EVENT_SINK_H_
#define MEMBRANE_CLIENT_JOB_EVENT_SINK_H_

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "client/progress_printer.h"
#include "core/engine/membrane_shrinker.h"
#include "core/geometry/point_cloud.h"
#include "membrane/v1/reconstruction.pb.h"

namespace membrane::client {

class JobEventSink {
 public:
  // `progress` (not owned) must outlive the sink.
  explicit JobEventSink(ProgressPrinter& progress) : progress_(progress) {}

  // Called with the job id when the server accepts the job (on the consuming thread).
  void set_on_accepted(std::function<void(const std::string&)> on_accepted) {
    on_accepted_ = std::move(on_accepted);
  }

  // Takes the next event of the stream.
  void Consume(const v1::JobEvent& event);

  bool accepted() const { return !job_id_.empty(); }
  // Accepted.upload_parts: the Draco clouds the server reads the upload as (0: a server that
  // predates uploads in parts, or no Accepted yet).
  uint32_t upload_parts() const { return upload_parts_; }
  bool done() const { return done_; }
  const std::string& job_id() const { return job_id_; }
  // Events taken since the last Accepted or snapshot (for tests that drop a call midway).
  int events_in_call() const { return events_in_call_; }

  // Once done: OK when the job SUCCEEDED and the mesh arrived whole (size and CRC-32C as
  // announced), else the job's status ("server: ..." message), DataLoss for a damaged mesh.
  absl::Status Outcome() const;
  const std::vector<GenerationStats>& generations() const { return generations_; }
  const std::string& statistics_json() const { return statistics_json_; }
  // The stages' warnings (StageEvent.warnings), in order, each once.
  const std::vector<std::string>& warnings() const { return warnings_; }
  // The server's check of the mesh.
  const v1::MeshSummary& mesh_summary() const { return mesh_summary_; }
  const std::string& mesh() const { return mesh_; }
  // The job's Parameters.origin, from WatchJob's snapshot (zero before one, or without one).
  const Origin3d& origin() const { return origin_; }
  // The job's Parameters.mesh_format, from WatchJob's snapshot: the encoding of mesh().
  // MESH_FORMAT_UNSPECIFIED (Draco) before a snapshot: Reconstruct calls of this client ask
  // for Draco.
  v1::MeshFormat mesh_format() const { return mesh_format_; }

 private:
  void ConsumeProgress(const v1::JobEvent& event);

  ProgressPrinter& progress_;
  std::function<void(const std::string&)> on_accepted_;
  std::string job_id_;
  uint32_t upload_parts_ = 0;
  int progress_seen_ = 0;   // stage, progress and generation events handled, over all calls
  int replay_index_ = 0;    // stage, progress and generation events of the current call
  int events_in_call_ = 0;
  std::vector<GenerationStats> generations_;
  std::string statistics_json_;
  std::vector<std::string> warnings_;
  v1::MeshSummary mesh_summary_;
  uint64_t mesh_bytes_ = 0;
  uint32_t mesh_crc32c_ = 0;
  std::string mesh_;
  bool done_ = false;
  v1::JobDone final_;
  Origin3d origin_{0, 0, 0};
  v1::MeshFormat mesh_format_ = v1::MESH_FORMAT_UNSPECIFIED;
};

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_JOB_EVENT_SINK_H_
