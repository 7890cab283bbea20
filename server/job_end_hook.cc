#include "server/job_end_hook.h"

#include <utility>

#include "absl/strings/str_format.h"
#include "server/server_log.h"

namespace membrane::server {

Job::FinishHook JobEndHook(ServerMetrics& metrics, JobStore& store, std::string id) {
  return [&metrics, &store, id = std::move(id)](v1::JobState state, const absl::Status& status,
                                                absl::Duration age, uint64_t mesh_bytes,
                                                bool ran) {
    metrics.JobFinished(state, status.code(), absl::ToDoubleSeconds(age), mesh_bytes);
    // The worker logs the end of a job it ran, with what only the run knows (points, faces).
    // A job cancelled while queued never runs (a worker reaching it skips it, a Submit or a
    // stop drops it), and may be cancelled before an idle worker wakes for it: its end is
    // logged here, as it happens, else no job_finished line would ever say it.
    if (!ran) {
      LogEvent("job_finished",
               {{"job", id},
                {"outcome", absl::StatusCodeToString(status.code())},
                {"queued_seconds", absl::StrFormat("%.3f", absl::ToDoubleSeconds(age))},
                {"message", std::string(status.message())}});
    }
    store.Finished(id);
  };
}

}  // namespace membrane::server
