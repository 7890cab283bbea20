// The hook every job of the server ends with (Job::FinishHook), for the jobs a call accepts
// and those a restart resumes alike.
#ifndef MEMBRANE_SERVER_JOB_END_HOOK_H_
#define MEMBRANE_SERVER_JOB_END_HOOK_H_

#include <string>

#include "server/job.h"
#include "server/job_store.h"
#include "server/server_metrics.h"

namespace membrane::server {

// Counts the end of job `id` in `metrics`, logs it as job_finished when no worker ran the job
// (the worker logs the others), then tells `store` (JobStore::Finished), which a durable store
// writes down. `metrics` and `store` must outlive the job.
Job::FinishHook JobEndHook(ServerMetrics& metrics, JobStore& store, std::string id);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_END_HOOK_H_
