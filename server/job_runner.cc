#include "server/job_runner.h"

#include <algorithm>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/io/decode_subprocess.h"
#include "core/io/draco_codec.h"
#include "core/pipeline/memory_estimate.h"
#include "core/pipeline/peak_memory.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/pipeline/stats_json.h"
#include "core/pipeline/stopwatch.h"
#include "server/job_event_observer.h"
#include "server/parameter_checks.h"
#include "server/server_log.h"

namespace membrane::server {
namespace {

// A grid over the budget: the message says which job fields change it.
absl::Status WithParameterHint(const absl::Status& status) {
  if (status.code() != absl::StatusCode::kResourceExhausted) return status;
  return absl::ResourceExhaustedError(
      absl::StrCat(status.message(), "; use a larger voxel_size (the server's voxel budget caps "
                                     "voxel_budget)"));
}

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
  const Stopwatch total;
  JobEventObserver observer(*job, &metrics_);
  const auto fail = [&](const absl::Status& status) {
    absl::Status final_status = status;
    if (status.code() == absl::StatusCode::kCancelled && !job->cancel_reason().empty()) {
      final_status = absl::CancelledError(job->cancel_reason());
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

  ReconstructionReport decode_report;
  const Stopwatch decode_watch;
  observer.StageStarted(PipelineStage::kDecode, decode_report);
  DecodeLimits limits;
  limits.helper = {options_.decoder_path};
  limits.timeout_seconds = options_.decoder_timeout_seconds;
  limits.memory_bytes = options_.decoder_memory_bytes;
  limits.max_points = options_.max_points;
  limits.subject = "the upload";
  absl::StatusOr<PointCloud> cloud =
      DecodeInSubprocess(job->TakeUpload(), limits, job->cancel_token());
  job->ReleaseUploadHold();  // the upload is gone with the decoder's input
  if (!cloud.ok()) return fail(cloud.status());
  cloud->origin = settings->origin;
  decode_report.points = static_cast<int64_t>(cloud->points.size());
  decode_report.seconds.decode = decode_watch.Seconds();
  observer.StageFinished(PipelineStage::kDecode, decode_report.seconds.decode, decode_report);

  absl::StatusOr<PlannedGrid> plan = PlanGrid(*cloud, settings->reconstruction.voxelize);
  if (!plan.ok()) return fail(plan.status());
  settings->reconstruction.voxelize.voxel_size = plan->voxel_size;
  // Held until the job ends; the surface's share is added once the membrane is known.
  MemoryBudget::Share memory(memory_);
  if (absl::Status s = memory.Add(plan->bytes, job->cancel_token()); !s.ok()) return fail(s);
  // Its refusal is the job's status as it is: the voxel-budget hint below is not about it.
  absl::Status admission;
  settings->reconstruction.admit_surface = [&](const MembraneCounts& membrane) {
    admission = memory.Add(SurfaceBytesEstimate(membrane), job->cancel_token());
    if (absl::IsResourceExhausted(admission)) {
      admission = absl::ResourceExhaustedError(absl::StrCat(
          "the surface of a membrane of ", membrane.membrane_voxels(),
          " voxels (a noisy cloud makes a foam of one): ", admission.message()));
    }
    return admission;
  };

  // The Draco encoding of the result runs beside the mesh check.
  std::string mesh;
  const MeshDelivery encode = [&](const TriangleMesh& m, const PositionGrid& grid) {
    absl::StatusOr<DracoEncoding> encoded =
        EncodeDracoMesh(m, DracoOptionsOnGrid(grid, settings->mesh_encoding.compression_level));
    if (!encoded.ok()) return encoded.status();
    mesh = std::move(encoded->bytes);
    return absl::OkStatus();
  };
  settings->reconstruction.threads = threads;
  absl::StatusOr<ReconstructionResult> result = ReconstructCloud(
      *cloud, settings->reconstruction, job->cancel_token(), observer, encode);
  if (!result.ok()) return fail(admission.ok() ? WithParameterHint(result.status()) : admission);
  ReconstructionReport& report = result->report;
  report.seconds.decode = decode_report.seconds.decode;
  report.seconds.total = total.Seconds();
  report.peak_rss_bytes = PeakRssBytes();
  const size_t mesh_bytes = mesh.size();
  job->Succeed(StatsJson(report), MeshSummaryOf(report.mesh), std::move(mesh));
  LogEvent("job_finished", {{"job", job->id()},
                            {"outcome", "OK"},
                            {"points", absl::StrCat(report.points)},
                            {"upload_bytes", absl::StrCat(job->upload_bytes())},
                            {"mesh_bytes", absl::StrCat(mesh_bytes)},
                            {"faces", absl::StrCat(report.mesh.faces)},
                            {"seconds", absl::StrFormat("%.3f", report.seconds.total)}});
}

}  // namespace membrane::server
