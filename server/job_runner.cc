#include "server/job_runner.h"

#include <algorithm>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/io/decode_subprocess.h"
#include "core/pipeline/draco_mesh_sink.h"
#include "core/pipeline/ply_mesh_sink.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/pipeline/stats_json.h"
#include "core/pipeline/stopwatch.h"
#include "core/pipeline/thread_limits.h"
#include "server/job_event_observer.h"
#include "server/memory_budget_gate.h"
#include "server/parameter_checks.h"
#include "server/point_sample.h"
#include "server/preview_sink.h"
#include "server/server_log.h"
#include "server/time_limit_gate.h"
#include "server/upload_source.h"

namespace membrane::server {
namespace {

v1::MeshSummary MeshSummaryOf(const MeshReport& m) {
  v1::MeshSummary summary;
  summary.set_vertices(m.vertices);
  summary.set_faces(m.faces);
  summary.set_closed(m.closed);
  summary.set_manifold(m.manifold);
  summary.set_oriented(m.oriented);
  summary.set_shells(m.shells);
  for (const int g : m.genus) summary.add_genus(g);
  return summary;
}

}  // namespace

int JobThreads(const ServerOptions& options, int running_jobs) {
  if (options.job_threads > 0) return options.job_threads;
  return std::clamp(options.cores / std::max(running_jobs, 1), 1, kMaxReconstructionThreads);
}

void JobRunner::Run(const std::shared_ptr<Job>& job, int threads) const {
  if (!job->Start()) return;  // cancelled while queued
  LogEvent("job_started", {{"job", job->id()}, {"peer", job->peer()}});
  // Its token fires past --max-job-seconds of running; the job then ends DEADLINE_EXCEEDED.
  const IdleWatchdog::Watch deadline = deadlines_.Start([job, limit = options_.max_job_seconds] {
    job->ExceedDeadline(absl::StrFormat(
        "the job ran past the server's --max-job-seconds of %g s; use a larger voxel_size or "
        "fewer quantization bits",
        limit));
  });
  const Stopwatch total;
  const auto fail = [&](const absl::Status& status) {
    if (job->interrupted()) {
      // The server stops and keeps the job for its next start: it has not ended.
      LogEvent("job_interrupted", {{"job", job->id()},
                                   {"seconds", absl::StrFormat("%.3f", total.Seconds())}});
      return;
    }
    absl::Status final_status = status;
    if (status.code() == absl::StatusCode::kCancelled && !job->cancel_status().ok()) {
      final_status = job->cancel_status();
    }
    job->Fail(final_status);
    LogEvent("job_finished",
             {{"job", job->id()},
              {"outcome", absl::StatusCodeToString(final_status.code())},
              {"seconds", absl::StrFormat("%.3f", total.Seconds())},
              {"message", std::string(final_status.message())}});
  };

  absl::StatusOr<JobSettings> settings =
      CheckParameters(job->parameters(), options_.voxel_budget);
  if (!settings.ok()) return fail(settings.status());
  settings->reconstruction.threads = threads;

  DecodeLimits limits;
  limits.helper = {options_.decoder_path};
  limits.timeout_seconds = options_.decoder_timeout_seconds;
  limits.memory_bytes = options_.decoder_memory_bytes;
  limits.max_points = options_.max_points;
  limits.threads = threads;
  limits.subject = "the upload";
  UploadSource upload(*job, std::move(limits), settings->origin);
  // The web console draws a sample of the points over the mesh.
  SamplingSource source(upload, *job);
  // Held until the job ends.
  MemoryBudgetGate memory_gate(memory_, settings->reconstruction.output_quantization_bits);
  TimeLimitGate gate(memory_gate, options_.max_job_seconds,
                     settings->reconstruction.output_quantization_bits,
                     settings->reconstruction.threads);
  DracoMeshSink draco_sink(settings->mesh_encoding.compression_level);
  PlyMeshSink ply_sink;
  // The web console's job list shows a preview of each mesh.
  PreviewSink sink(settings->ply_mesh ? static_cast<MeshSink&>(ply_sink) : draco_sink,
                   &job->cancel_token());
  JobEventObserver events(*job, &metrics_, options_.progress_after_seconds);
  // The preview is drawn once the check beside the encode has ended.
  PreviewCheckObserver observer(events, sink);
  // A grid over the budget: the message says which job fields change it.
  ErrorContext errors;
  errors.resource_exhausted_advice =
      "; use a larger voxel_size (a positive voxel budget of the server caps voxel_budget)";
  absl::StatusOr<ReconstructionReport> report =
      RunReconstruction(settings->reconstruction, {source, gate, sink, observer}, errors,
                        job->cancel_token());
  if (!report.ok()) return fail(report.status());
  std::string mesh = settings->ply_mesh ? ply_sink.TakeBytes() : draco_sink.TakeBytes();
  const size_t mesh_bytes = mesh.size();
  if (static_cast<int64_t>(mesh_bytes) > options_.max_result_bytes) {
    // Held past the job and written to the store whole: a bound keeps both finite.
    return fail(absl::ResourceExhaustedError(absl::StrFormat(
        "the mesh of %d faces takes %d bytes, over the server's --max-result-bytes of %d; ask "
        "for fewer faces (target_faces)%s",
        report->mesh.faces, mesh_bytes, options_.max_result_bytes,
        settings->ply_mesh ? " or a Draco mesh (mesh_format)" : "")));
  }
  job->SetPreview(sink.TakePng());
  job->Succeed(StatsJson(*report), MeshSummaryOf(report->mesh), std::move(mesh));
  LogEvent("job_finished", {{"job", job->id()},
                            {"outcome", "OK"},
                            {"points", absl::StrCat(report->points)},
                            {"upload_bytes", absl::StrCat(job->upload_bytes())},
                            {"mesh_bytes", absl::StrCat(mesh_bytes)},
                            {"faces", absl::StrCat(report->mesh.faces)},
                            {"seconds", absl::StrFormat("%.3f", report->seconds.total)}});
}

}  // namespace membrane::server
