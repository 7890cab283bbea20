#include "server/server_metrics.h"

#include <string>
#include <utility>

#include "prometheus/client_metric.h"
#include "prometheus/metric_type.h"

namespace membrane::server {
namespace {

// Jobs last from a fraction of a second (a small scan) to an hour (a big one behind a queue).
prometheus::Histogram::BucketBoundaries JobBuckets() {
  return {0.25, 0.5, 1, 2.5, 5, 10, 25, 60, 150, 300, 600, 1800, 3600};
}

// Stages, from milliseconds (relax on a small membrane) to minutes (a shrink of 400M voxels).
prometheus::Histogram::BucketBoundaries StageBuckets() {
  return {0.001, 0.005, 0.01, 0.05, 0.1, 0.5, 1, 5, 10, 60, 300};
}

constexpr PipelineStage kStages[] = {PipelineStage::kDecode,  PipelineStage::kVoxelize,
                                     PipelineStage::kShrink,  PipelineStage::kRelax,
                                     PipelineStage::kSurface, PipelineStage::kDecimate,
                                     PipelineStage::kCheck,   PipelineStage::kEncode};

prometheus::MetricFamily Gauge(std::string name, std::string help, double value) {
  prometheus::ClientMetric metric;
  metric.gauge.value = value;
  return {std::move(name), std::move(help), prometheus::MetricType::Gauge, {metric}};
}

}  // namespace

ServerMetrics::ServerMetrics()
    : registry_(std::make_shared<prometheus::Registry>()),
      refused_(prometheus::BuildCounter()
                   .Name("membrane_reconstruct_refused_total")
                   .Help("Reconstruct calls that made no job, by status code")
                   .Register(*registry_)),
      store_refused_(prometheus::BuildCounter()
                         .Name("membrane_store_refused_total")
                         .Help("Reconstruct calls refused because the job store could not "
                               "write their job")
                         .Register(*registry_)
                         .Add({})),
      accepted_(prometheus::BuildCounter()
                    .Name("membrane_jobs_accepted_total")
                    .Help("Jobs accepted (queued)")
                    .Register(*registry_)
                    .Add({})),
      upload_bytes_(prometheus::BuildCounter()
                        .Name("membrane_upload_bytes_total")
                        .Help("Draco bytes of the accepted uploads")
                        .Register(*registry_)
                        .Add({})),
      finished_(prometheus::BuildCounter()
                    .Name("membrane_jobs_finished_total")
                    .Help("Jobs ended, by final state and status code")
                    .Register(*registry_)),
      job_seconds_(prometheus::BuildHistogram()
                       .Name("membrane_job_seconds")
                       .Help("Seconds from a job's acceptance to its end, queue included")
                       .Register(*registry_)),
      mesh_bytes_(prometheus::BuildCounter()
                      .Name("membrane_mesh_bytes_total")
                      .Help("Draco bytes of the meshes made")
                      .Register(*registry_)
                      .Add({})),
      stalled_(prometheus::BuildCounter()
                   .Name("membrane_calls_stalled_total")
                   .Help("Calls cancelled for making no progress for --stall-seconds")
                   .Register(*registry_)
                   .Add({})) {
  auto& stages = prometheus::BuildHistogram()
                     .Name("membrane_stage_seconds")
                     .Help("Seconds of one stage of one job")
                     .Register(*registry_);
  for (PipelineStage stage : kStages) {
    stage_seconds_[static_cast<size_t>(stage)] =
        &stages.Add({{"stage", PipelineStageName(stage)}}, StageBuckets());
  }
  // Present from the start, so that rates and alerts see a zero rather than no series. Naming
  // the states through JobState_Name also builds protobuf's descriptors of the API now: built
  // at the first job's end, their blocks would stay for good among that job's freed arrays,
  // and split the space the next job's arrays would take whole (server/mapped_bytes.h).
  for (v1::JobState state : {v1::SUCCEEDED, v1::FAILED, v1::CANCELLED}) {
    job_seconds_.Add({{"state", v1::JobState_Name(state)}}, JobBuckets());
  }
  finished_.Add({{"state", v1::JobState_Name(v1::SUCCEEDED)},
                 {"code", absl::StatusCodeToString(absl::StatusCode::kOk)}});
  finished_.Add({{"state", v1::JobState_Name(v1::CANCELLED)},
                 {"code", absl::StatusCodeToString(absl::StatusCode::kCancelled)}});
}

void ServerMetrics::ReconstructRefused(absl::StatusCode code) {
  refused_.Add({{"code", absl::StatusCodeToString(code)}}).Increment();
}

void ServerMetrics::StoreRefused() { store_refused_.Increment(); }

void ServerMetrics::JobAccepted(uint64_t upload_bytes) {
  accepted_.Increment();
  upload_bytes_.Increment(static_cast<double>(upload_bytes));
}

void ServerMetrics::JobFinished(v1::JobState state, absl::StatusCode code, double seconds,
                                uint64_t mesh_bytes) {
  const std::string name = v1::JobState_Name(state);
  finished_.Add({{"state", name}, {"code", absl::StatusCodeToString(code)}}).Increment();
  job_seconds_.Add({{"state", name}}, JobBuckets()).Observe(seconds);
  mesh_bytes_.Increment(static_cast<double>(mesh_bytes));
}

void ServerMetrics::CallStalled() { stalled_.Increment(); }

void ServerMetrics::StageFinished(PipelineStage stage, double seconds) {
  stage_seconds_[static_cast<size_t>(stage)]->Observe(seconds);
}

std::vector<prometheus::MetricFamily> ServerStateCollector::Collect() const {
  const ServerState s = read_();
  return {
      Gauge("membrane_jobs_queued", "Jobs waiting for a worker", s.queued),
      Gauge("membrane_queue_limit", "Jobs that may wait (--queue)", s.queue_limit),
      Gauge("membrane_jobs_running", "Jobs on a worker", s.running),
      Gauge("membrane_workers", "Jobs that may run at once (--workers)", s.workers),
      Gauge("membrane_memory_reserved_bytes", "Estimated bytes reserved by running jobs",
            static_cast<double>(s.memory_reserved_bytes)),
      Gauge("membrane_memory_budget_bytes", "The running jobs' budget; 0: no limit",
            static_cast<double>(s.memory_budget_bytes)),
      Gauge("membrane_memory_waiting_jobs", "Running jobs waiting for memory others hold",
            s.memory_waiting_jobs),
      Gauge("membrane_upload_held_bytes", "Bytes held by uploads arriving, queued or decoding",
            static_cast<double>(s.upload_held_bytes)),
      Gauge("membrane_upload_memory_bytes", "The uploads' pool; 0: no limit",
            static_cast<double>(s.upload_memory_bytes)),
      Gauge("membrane_store_writable",
            "1 when the job store can be written (or there is no disk store); 0 while its "
            "disk fails, when jobs are refused",
            s.store_writable ? 1 : 0),
  };
}

}  // namespace membrane::server
