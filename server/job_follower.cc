#include "server/job_follower.h"

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "absl/time/time.h"
#include "server/server_log.h"

namespace membrane::server {
namespace {

constexpr size_t kMeshChunkBytes = 1 << 20;  // well under gRPC's 4 MB message limit
constexpr std::chrono::seconds kDeadlineSlack{2};

grpc::Status CallEnded(Job& job, grpc::ServerContext& context, const std::string& peer,
                       FollowPolicy policy) {
  // The server's deadline is the client's timeout counted from when the call's headers
  // arrived, so it trails the client's own by the transit time (tens to hundreds of ms on a
  // loaded machine): a call that ends just before it was ended by the client's deadline.
  const bool deadline_expired =
      context.deadline() <= std::chrono::system_clock::now() + kDeadlineSlack;
  if (deadline_expired) {
    job.RequestCancel("the call's deadline expired");
  } else if (policy.cancel_on_drop) {
    job.RequestCancel("the client disconnected (--on-disconnect=cancel)");
  }
  LogEvent("call_dropped", {{"job", job.id()},
                            {"peer", peer},
                            {"deadline_expired", deadline_expired ? "true" : "false"}});
  return deadline_expired ? grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED, "deadline expired")
                          : grpc::Status(grpc::StatusCode::CANCELLED, "call cancelled");
}

}  // namespace

grpc::Status FollowJob(Job& job, grpc::ServerContext& context, const std::string& peer,
                       FollowPolicy policy,
                       const std::function<bool(const v1::JobEvent&)>& write) {
  size_t next = 0;
  while (true) {
    if (context.IsCancelled()) return CallEnded(job, context, peer, policy);
    // Read `done` first: no event is added after the job ends, so the events fetched next
    // are then all of them. Closed, not merely done: the end is delivered once the store has
    // written it (Job::closed).
    const bool done = job.closed();
    std::vector<v1::JobEvent> events;
    next = job.WaitForEvents(next, done ? absl::ZeroDuration() : absl::Milliseconds(50), events);
    for (const v1::JobEvent& event : events) {
      if (!write(event)) return CallEnded(job, context, peer, policy);
    }
    if (!done) continue;
    // The mesh is the job's one buffer: each chunk is copied into its message as it is
    // written, so a follower holds a chunk of it, not the whole.
    const std::optional<Job::Outcome> outcome = job.Closing();
    if (outcome->result.has_value()) {
      if (!write(*outcome->result)) return CallEnded(job, context, peer, policy);
      for (size_t at = 0; at < outcome->mesh.size(); at += kMeshChunkBytes) {
        if (!write(MeshChunkEvent(outcome->mesh.view(), at, kMeshChunkBytes))) {
          return CallEnded(job, context, peer, policy);
        }
      }
    }
    if (!write(outcome->done)) return CallEnded(job, context, peer, policy);
    const google::rpc::Status& status = outcome->done.done().status();
    return grpc::Status(static_cast<grpc::StatusCode>(status.code()), status.message());
  }
}

}  // namespace membrane::server
