// What a worker does with one job: run the shared pipeline (core/pipeline) with the job's
// adapters (its upload decoded in a subprocess, its share of the memory budget, a Draco
// encoding of the mesh, its event stream), and end the job with its statistics and mesh or
// its status.
#ifndef MEMBRANE_SERVER_JOB_RUNNER_H_
#define MEMBRANE_SERVER_JOB_RUNNER_H_

#include <memory>

#include "server/idle_watchdog.h"
#include "server/job.h"
#include "server/memory_budget.h"
#include "server/server_metrics.h"
#include "server/server_options.h"

namespace membrane::server {

// The threads of a job that starts while `running_jobs` jobs run (itself included): the
// fixed options.job_threads, or with 0, options.cores divided among the running jobs (at least
// 1). The mesh does not depend on it, so an idle server can give a lone job every core.
int JobThreads(const ServerOptions& options, int running_jobs);

class JobRunner {
 public:
  // `options`, `memory`, `metrics` and `deadlines` (not owned) must outlive the runner.
  // `deadlines` watches each running job for options.max_job_seconds.
  JobRunner(const ServerOptions& options, MemoryBudget& memory, ServerMetrics& metrics,
            IdleWatchdog& deadlines)
      : options_(options), memory_(memory), metrics_(metrics), deadlines_(deadlines) {}

  // Runs `job` to its end (QUEUED -> RUNNING -> SUCCEEDED / FAILED / CANCELLED) on the
  // calling thread; returns at once when the job was cancelled while queued. Statuses a job
  // can end with: InvalidArgument (bad parameters, an upload the decoder rejects or dies on,
  // a degenerate cloud), ResourceExhausted (points, voxels or memory over the server's
  // limits, or a floor of seconds over options.max_job_seconds), Cancelled (with the reason
  // given to Job::RequestCancel), DeadlineExceeded (running past options.max_job_seconds),
  // Internal.
  // `threads` is the job's ReconstructionOptions::threads (JobThreads).
  void Run(const std::shared_ptr<Job>& job, int threads) const;

 private:
  const ServerOptions& options_;
  MemoryBudget& memory_;
  ServerMetrics& metrics_;
  IdleWatchdog& deadlines_;
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_RUNNER_H_
