#include "server/job_end_hook.h"

#include <utility>

namespace membrane::server {

Job::FinishHook JobEndHook(ServerMetrics& metrics, JobStore& store, std::string id) {
  return [&metrics, &store, id = std::move(id)](v1::JobState state, const absl::Status& status,
                                                absl::Duration age, uint64_t mesh_bytes) {
    metrics.JobFinished(state, status.code(), absl::ToDoubleSeconds(age), mesh_bytes);
    store.Finished(id);
  };
}

}  // namespace membrane::server
