// What membraned exposes to Prometheus (--metrics-listen, path /metrics): the jobs and calls
// the log's lifecycle events tell of, counted, and the seconds of jobs and stages, so that a
// dashboard, an alert or an autoscaler can read them without parsing logs. Owned by
// MembraneServer and passed by reference (no global registry). Thread-safe.
#ifndef MEMBRANE_SERVER_SERVER_METRICS_H_
#define MEMBRANE_SERVER_SERVER_METRICS_H_

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "absl/status/status.h"
#include "core/pipeline/pipeline_stage.h"
#include "membrane/v1/reconstruction.pb.h"
#include "prometheus/collectable.h"
#include "prometheus/counter.h"
#include "prometheus/family.h"
#include "prometheus/histogram.h"
#include "prometheus/registry.h"

namespace membrane::server {

class ServerMetrics {
 public:
  ServerMetrics();

  // A Reconstruct call that made no job (refused upload, full queue, no token, shutting
  // down), by its status code: membrane_reconstruct_refused_total{code}.
  void ReconstructRefused(absl::StatusCode code);
  // A Reconstruct call refused because its job could not be written to the store (a
  // read-only or full disk): membrane_store_refused_total. Also counted by ReconstructRefused.
  void StoreRefused();
  // membrane_jobs_accepted_total, membrane_upload_bytes_total.
  void JobAccepted(uint64_t upload_bytes);
  // Once per job, whatever ended it: membrane_jobs_finished_total{state, code},
  // membrane_job_seconds{state} (acceptance to end: queue time included),
  // membrane_mesh_bytes_total.
  void JobFinished(v1::JobState state, absl::StatusCode code, double seconds,
                   uint64_t mesh_bytes);
  // A call cancelled for making no progress for --stall-seconds (IdleWatchdog):
  // membrane_calls_stalled_total.
  void CallStalled();
  // membrane_stage_seconds{stage}: one observation per stage a job finished.
  void StageFinished(PipelineStage stage, double seconds);

  // Everything above, for an exposer.
  std::shared_ptr<prometheus::Registry> registry() const { return registry_; }

 private:
  std::shared_ptr<prometheus::Registry> registry_;
  prometheus::Family<prometheus::Counter>& refused_;
  prometheus::Counter& store_refused_;
  prometheus::Counter& accepted_;
  prometheus::Counter& upload_bytes_;
  prometheus::Family<prometheus::Counter>& finished_;
  prometheus::Family<prometheus::Histogram>& job_seconds_;
  prometheus::Counter& mesh_bytes_;
  prometheus::Counter& stalled_;
  std::array<prometheus::Histogram*, 8> stage_seconds_{};  // by PipelineStage
};

// The server's state read at each scrape: gauges of the queue, the workers and the memory
// pools (their limits beside what is held, 0 for no limit).
struct ServerState {
  int queued = 0;
  int queue_limit = 0;
  int running = 0;
  int workers = 0;
  int64_t memory_reserved_bytes = 0;
  int64_t memory_budget_bytes = 0;
  int memory_waiting_jobs = 0;
  int64_t upload_held_bytes = 0;
  int64_t upload_memory_bytes = 0;
  bool store_writable = true;  // false while a durable store's disk cannot be written
};

// A Prometheus collectable giving `read()`'s ServerState as membrane_* gauges. `read` is
// called on the exposer's threads, at every scrape.
class ServerStateCollector : public prometheus::Collectable {
 public:
  explicit ServerStateCollector(std::function<ServerState()> read) : read_(std::move(read)) {}
  std::vector<prometheus::MetricFamily> Collect() const override;

 private:
  std::function<ServerState()> read_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_SERVER_METRICS_H_
