// Streaming one job's events to one caller until the job ends or the caller goes away.
#ifndef MEMBRANE_SERVER_JOB_FOLLOWER_H_
#define MEMBRANE_SERVER_JOB_FOLLOWER_H_

#include <functional>
#include <string>

#include <grpcpp/server_context.h>

#include "server/job.h"

namespace membrane::server {

// What to do with the job when the call ends before it (the caller dropped or its deadline
// expired): the deadline always cancels the job; a drop cancels it when `cancel_on_drop`.
struct FollowPolicy {
  bool cancel_on_drop = false;
};

// Writes each event of `job` from its first one through `write` (false: the caller is gone),
// then its closing events (result, mesh chunks, JobDone) once the job is closed (Job::closed:
// its end written down by a durable store). Polls the call every 50 ms, so a
// dropped caller or an expired deadline is seen (and the job cancelled per `policy`) within
// 100 ms, and logged as `call_dropped` with `peer`, the caller's address taken when the call
// began (a cancelled call's context no longer knows it). Returns the job's final status for
// the call: OK, or the status the job ended with; CANCELLED or DEADLINE_EXCEEDED when the
// call ended first.
grpc::Status FollowJob(Job& job, grpc::ServerContext& context, const std::string& peer,
                       FollowPolicy policy,
                       const std::function<bool(const v1::JobEvent&)>& write);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_JOB_FOLLOWER_H_
