#include "server/reconstruction_service.h"

#include <algorithm>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/io/draco_parts.h"
#include "proto/crc32c.h"
#include "proto/job_routing.h"
#include "server/bearer_token.h"
#include "server/client_text.h"
#include "server/job_end_hook.h"
#include "server/job_follower.h"
#include "server/parameter_checks.h"
#include "server/rpc_status.h"
#include "server/memory_release.h"
#include "server/server_log.h"
#include "server/time_limit_gate.h"

namespace membrane::server {
namespace {

grpc::Status InvalidArgument(const std::string& message) {
  return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, message);
}

// NOT_FOUND for a call that reached this replica with what another one holds: `asked` says
// what that was, and the message names both replicas, for whoever configures the balancer.
grpc::Status WrongReplica(absl::string_view asked, const std::string& this_replica) {
  return grpc::Status(
      grpc::StatusCode::NOT_FOUND,
      absl::StrCat(asked, ", and this is ",
                   this_replica.empty() ? "an unnamed replica" : "'" + this_replica + "'",
                   " (the balancer must route on the ", kReplicaHeader, " header)"));
}

// Names the replica the id belongs to when it is another one: a balancer that does not route
// on the replica header sends re-attach calls to any replica.
grpc::Status JobNotFound(const std::string& id, const std::string& this_replica) {
  const absl::string_view owner = ReplicaOfJobId(id);
  if (!owner.empty() && owner != this_replica) {
    return WrongReplica(absl::StrCat("no job '", ClientText(id), "' here: it belongs to replica '",
                                     ClientText(owner), "'"),
                        this_replica);
  }
  return grpc::Status(
      grpc::StatusCode::NOT_FOUND,
      absl::StrCat("no job '", ClientText(id), "' (unknown, or its result expired)"));
}

}  // namespace

std::string ReconstructionService::NewJobId() {
  absl::MutexLock lock(&id_mutex_);
  return MakeJobId(options_.replica, absl::Uniform<uint64_t>(id_random_));
}

void ReconstructionService::ExpireResults() {
  // Expiry is lazy: every lookup first drops the results past their time, and their meshes'
  // pages go back to the system.
  if (store_.RemoveFinishedBefore(clock_.Now() - absl::Seconds(options_.result_ttl_seconds)) > 0) {
    ReleaseFreedMemory();
  }
}

std::shared_ptr<Job> ReconstructionService::FindJob(const std::string& id,
                                                    const Caller& caller) {
  ExpireResults();
  std::shared_ptr<Job> job = store_.Find(id);
  // Another client's job is answered as an unknown one: its existence is not theirs to learn.
  if (job != nullptr && !caller.Sees(*job)) return nullptr;
  return job;
}

grpc::Status ReconstructionService::Authenticate(const grpc::ServerContext& context,
                                                 Caller& caller) {
  absl::StatusOr<const ClientToken*> client = CheckBearerToken(context, options_.clients);
  if (!client.ok()) {
    LogEvent("call_unauthenticated",
             {{"peer", context.peer()}, {"message", std::string(client.status().message())}});
    return ToGrpcStatus(client.status());
  }
  caller = CallerOf(*client);
  return grpc::Status::OK;
}

grpc::Status ReconstructionService::ReadUpload(
    grpc::ServerContext* context,
    grpc::ServerReaderWriter<v1::JobEvent, v1::ReconstructRequest>* stream,
    v1::Parameters& parameters, std::string& upload, std::vector<uint64_t>& part_bytes,
    UploadMemory::Hold& hold) {
  IdleWatchdog::Watch watch = stall_watchdog_.Start(context);
  auto idle = [&] {
    return grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                        absl::StrFormat("the upload made no progress (%d bytes) for %g s "
                                        "(--stall-seconds): call cancelled",
                                        kStallProgressBytes, options_.stall_seconds));
  };
  v1::ReconstructRequest request;
  if (!stream->Read(&request) || !request.has_header()) {
    if (watch.fired()) return idle();
    return InvalidArgument("the first message of Reconstruct must be an UploadHeader");
  }
  // A copy: the chunks are read into `request` below, which frees the header it held.
  const v1::UploadHeader header = request.header();
  parameters = header.parameters();
  if (absl::StatusOr<JobSettings> s = CheckParameters(parameters, options_.voxel_budget); !s.ok()) {
    return ToGrpcStatus(s.status());
  }
  if (absl::Status s = CheckEncodeTime(parameters, options_.max_job_seconds); !s.ok()) {
    return ToGrpcStatus(s);
  }
  if (header.upload_bytes() == 0) return InvalidArgument("the upload is empty (0 bytes)");
  if (absl::Status s = CheckDracoPartBytes(header.upload_part_bytes(), header.upload_bytes());
      !s.ok()) {
    return ToGrpcStatus(s);
  }
  part_bytes.assign(header.upload_part_bytes().begin(), header.upload_part_bytes().end());
  if (header.upload_bytes() > static_cast<uint64_t>(options_.max_upload_bytes)) {
    return grpc::Status(grpc::StatusCode::RESOURCE_EXHAUSTED,
                        absl::StrFormat("upload of %d bytes is over the server's limit of %d "
                                        "bytes (--max-upload-bytes)",
                                        header.upload_bytes(), options_.max_upload_bytes));
  }
  if (absl::Status s = upload_memory_.CheckFits(static_cast<int64_t>(header.upload_bytes()));
      !s.ok()) {
    return ToGrpcStatus(s);
  }
  // The buffer's bytes are held from here until the job's decoding ends; a busy server asks
  // the client to come back. Held as they grow, so a header alone pins nothing.
  auto grow = [&](uint64_t capacity) {
    const int64_t more = static_cast<int64_t>(capacity) - hold.bytes();
    if (more <= 0) return grpc::Status::OK;
    if (absl::Status s = upload_memory_.Grow(hold, more); !s.ok()) {
      return ToGrpcStatusWithRetry(s, absl::Seconds(options_.retry_delay_seconds));
    }
    return grpc::Status::OK;
  };
  // The buffer's first size: no more than what a few chunks justify, so that a call which
  // announces much and sends a byte holds little.
  const uint64_t first = std::min<uint64_t>(header.upload_bytes(), 4 << 20);
  uint32_t crc = 0;
  uint64_t since_progress = 0;  // bytes since the watchdog was last told of progress
  v1::ReconstructRequest chunk;
  while (stream->Read(&chunk)) {
    if (!chunk.has_chunk()) return InvalidArgument("UploadHeader sent twice");
    // What was still to come when this chunk arrived (upload.size() never passes the header's).
    const uint64_t to_come = header.upload_bytes() - upload.size();
    since_progress += chunk.chunk().size();
    if (since_progress > 0 && since_progress >= std::min(kStallProgressBytes, to_come)) {
      watch.Touch();
      since_progress = 0;
    }
    if (upload.size() + chunk.chunk().size() > header.upload_bytes()) {
      return InvalidArgument(absl::StrFormat("the upload is longer than the %d bytes announced",
                                             header.upload_bytes()));
    }
    crc = Crc32c(chunk.chunk(), crc);
    // Grown geometrically but never past the size announced, each step held first.
    if (upload.size() + chunk.chunk().size() > upload.capacity()) {
      const uint64_t capacity = std::min<uint64_t>(
          header.upload_bytes(),
          std::max<uint64_t>({first, 2 * upload.capacity(), upload.size() + chunk.chunk().size()}));
      if (grpc::Status s = grow(capacity); !s.ok()) return s;
      upload.reserve(capacity);
    }
    upload += chunk.chunk();
  }
  if (watch.fired()) return idle();
  if (context->IsCancelled()) return grpc::Status(grpc::StatusCode::CANCELLED, "call cancelled");
  if (upload.size() != header.upload_bytes()) {
    return InvalidArgument(absl::StrFormat("the upload is truncated: %d of %d bytes arrived",
                                           upload.size(), header.upload_bytes()));
  }
  if (crc != header.upload_crc32c()) {
    return InvalidArgument(absl::StrFormat(
        "the upload's CRC-32C is %08x, not the %08x announced: corrupted in transit", crc,
        header.upload_crc32c()));
  }
  return grpc::Status::OK;
}

grpc::Status ReconstructionService::Reconstruct(
    grpc::ServerContext* context,
    grpc::ServerReaderWriter<v1::JobEvent, v1::ReconstructRequest>* stream) {
  // gRPC's codes are absl's, number for number.
  const auto refused = [this](const grpc::Status& s) {
    metrics_.ReconstructRefused(static_cast<absl::StatusCode>(s.error_code()));
    return s;
  };
  // Taken now: once the call is cancelled (a stall, a drop) its context no longer knows it.
  const std::string peer = context->peer();
  Caller caller;
  if (grpc::Status s = Authenticate(*context, caller); !s.ok()) return refused(s);
  if (!accepting_) {
    return refused(ToGrpcStatusWithRetry(
        absl::UnavailableError("the server is shutting down; try again or another replica"),
        absl::Seconds(options_.retry_delay_seconds)));
  }
  // A job is accepted only once it is durable: while the store's disk fails, say so before
  // the client sends its upload.
  const auto store_refused = [&](const absl::Status& s) {
    metrics_.StoreRefused();
    LogEvent("job_refused",
             {{"peer", peer}, {"client", caller.LogName()}, {"message", std::string(s.message())}});
    return refused(ToGrpcStatusWithRetry(s, absl::Seconds(options_.retry_delay_seconds)));
  };
  if (!store_.writable()) {
    return store_refused(absl::UnavailableError(
        "the job store cannot be written (read-only or full disk); try again later or another "
        "replica"));
  }
  v1::Parameters parameters;
  std::string upload;
  std::vector<uint64_t> part_bytes;
  UploadMemory::Hold hold;
  if (grpc::Status s = ReadUpload(context, stream, parameters, upload, part_bytes, hold);
      !s.ok()) {
    LogEvent("upload_rejected", {{"peer", peer},
                                 {"client", caller.LogName()},
                                 {"code", absl::StrCat(s.error_code())},
                                 {"message", s.error_message()}});
    return refused(s);
  }
  const uint64_t upload_bytes = upload.size();
  const std::string id = NewJobId();
  auto job = std::make_shared<Job>(id, peer, parameters, std::move(upload),
                                   std::move(hold), JobEndHook(metrics_, store_, id));
  job->set_client(caller.name);
  job->set_upload_part_bytes(std::move(part_bytes));
  const auto queue_refused = [&](const absl::Status& s) {
    LogEvent("job_refused", {{"peer", peer},
                             {"client", caller.LogName()},
                             {"message", std::string(s.message())}});
    return refused(ToGrpcStatusWithRetry(s, absl::Seconds(options_.retry_delay_seconds)));
  };
  // The queue's answer before the store's write, so that a busy server writes nothing; the
  // write before the job is queued, so that no worker runs a job the store does not hold.
  if (absl::Status s = scheduler_.CheckRoom(); !s.ok()) return queue_refused(s);
  if (absl::Status s = store_.Add(job); !s.ok()) return store_refused(s);
  if (absl::Status s = scheduler_.Submit(job); !s.ok()) {
    store_.Remove(id);
    return queue_refused(s);
  }
  metrics_.JobAccepted(upload_bytes);
  const v1::Job snapshot = job->Snapshot();
  LogEvent("job_accepted", {{"job", job->id()},
                            {"peer", peer},
                            {"client", caller.LogName()},
                            {"upload_bytes", absl::StrCat(upload_bytes)},
                            {"queue_position", absl::StrCat(snapshot.queue_position())}});
  v1::JobEvent accepted;
  accepted.mutable_accepted()->set_job_id(job->id());
  accepted.mutable_accepted()->set_queue_position(snapshot.queue_position());
  accepted.mutable_accepted()->set_upload_parts(
      static_cast<uint32_t>(std::max<size_t>(job->upload_part_bytes().size(), 1)));
  const FollowPolicy policy{options_.on_disconnect == DisconnectPolicy::kCancel};
  if (!WriteUnlessStalled(context, [&] { return stream->Write(accepted); })) {
    return FollowJob(*job, *context, peer, policy, [](const v1::JobEvent&) { return false; });
  }
  return FollowJob(*job, *context, peer, policy,
                   [this, context, stream](const v1::JobEvent& event) {
                     return WriteUnlessStalled(context, [&] { return stream->Write(event); });
                   });
}

grpc::Status ReconstructionService::GetJob(grpc::ServerContext* context,
                                           const v1::GetJobRequest* request, v1::Job* response) {
  Caller caller;
  if (grpc::Status s = Authenticate(*context, caller); !s.ok()) return s;
  std::shared_ptr<Job> job = FindJob(request->job_id(), caller);
  if (job == nullptr) return JobNotFound(request->job_id(), options_.replica);
  *response = job->Snapshot();
  return grpc::Status::OK;
}

grpc::Status ReconstructionService::WatchJob(grpc::ServerContext* context,
                                             const v1::WatchJobRequest* request,
                                             grpc::ServerWriter<v1::JobEvent>* writer) {
  Caller caller;
  if (grpc::Status s = Authenticate(*context, caller); !s.ok()) return s;
  std::shared_ptr<Job> job = FindJob(request->job_id(), caller);
  if (job == nullptr) return JobNotFound(request->job_id(), options_.replica);
  const std::string peer = context->peer();
  LogEvent("job_watched", {{"job", job->id()}, {"peer", peer}, {"client", caller.LogName()}});
  v1::JobEvent snapshot;
  *snapshot.mutable_snapshot() = job->Snapshot();
  if (!WriteUnlessStalled(context, [&] { return writer->Write(snapshot); })) {
    return grpc::Status(grpc::StatusCode::CANCELLED, "call cancelled");
  }
  // A watcher going away never cancels the job: only its own Reconstruct call may.
  return FollowJob(*job, *context, peer, FollowPolicy{},
                   [this, context, writer](const v1::JobEvent& event) {
                     return WriteUnlessStalled(context, [&] { return writer->Write(event); });
                   });
}

grpc::Status ReconstructionService::CancelJob(grpc::ServerContext* context,
                                              const v1::CancelJobRequest* request,
                                              v1::Job* response) {
  Caller caller;
  if (grpc::Status s = Authenticate(*context, caller); !s.ok()) return s;
  std::shared_ptr<Job> job = FindJob(request->job_id(), caller);
  if (job == nullptr) return JobNotFound(request->job_id(), options_.replica);
  job->RequestCancel(caller.CancelReason(*job));
  LogEvent("job_cancel_requested",
           {{"job", job->id()}, {"peer", context->peer()}, {"client", caller.LogName()}});
  *response = job->Snapshot();
  return grpc::Status::OK;
}

grpc::Status ReconstructionService::ListJobs(grpc::ServerContext* context,
                                             const v1::ListJobsRequest*,
                                             v1::ListJobsResponse* response) {
  Caller caller;
  if (grpc::Status s = Authenticate(*context, caller); !s.ok()) return s;
  // A list asked of one replica (membrane jobs list --replica) must not silently be another's.
  const auto asked = context->client_metadata().find(kReplicaHeader);
  if (asked != context->client_metadata().end()) {
    const std::string name(asked->second.data(), asked->second.size());
    if (name != options_.replica) {
      return WrongReplica(
          absl::StrCat("the jobs of replica '", ClientText(name), "' were asked for"),
          options_.replica);
    }
  }
  ExpireResults();
  for (const std::shared_ptr<Job>& job : store_.List()) {
    if (caller.Sees(*job)) *response->add_jobs() = job->Snapshot();
  }
  return grpc::Status::OK;
}

}  // namespace membrane::server
