// The gRPC service membrane.v1.Reconstruction (proto/membrane/v1/reconstruction.proto): the
// handlers, thin over a JobStore and a JobScheduler.
#ifndef MEMBRANE_SERVER_RECONSTRUCTION_SERVICE_H_
#define MEMBRANE_SERVER_RECONSTRUCTION_SERVICE_H_

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "absl/base/thread_annotations.h"
#include "absl/random/random.h"
#include "absl/synchronization/mutex.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "server/caller.h"
#include "server/job_scheduler.h"
#include "server/clock.h"
#include "server/job_store.h"
#include "server/idle_watchdog.h"
#include "server/server_metrics.h"
#include "server/server_options.h"
#include "server/upload_memory.h"

namespace membrane::server {

// The upload bytes that count as progress against --stall-seconds (ReadUpload): a client
// sending less than this in that long (under 55 bytes a second with the default 300 s) is cut.
inline constexpr uint64_t kStallProgressBytes = 16 << 10;

class ReconstructionService final : public v1::Reconstruction::Service {
 public:
  // `options`, `store`, `scheduler`, `upload_memory`, `metrics` and `clock` (not owned) must
  // outlive the service. `clock` times the results' TTL and the stalls.
  ReconstructionService(const ServerOptions& options, JobStore& store, JobScheduler& scheduler,
                        UploadMemory& upload_memory, ServerMetrics& metrics, const Clock& clock)
      : options_(options),
        store_(store),
        scheduler_(scheduler),
        upload_memory_(upload_memory),
        metrics_(metrics),
        clock_(clock),
        stall_watchdog_(absl::Seconds(options.stall_seconds), clock,
                        [&metrics] { metrics.CallStalled(); }) {}

  // From now on Reconstruct answers UNAVAILABLE (graceful shutdown); other calls still work,
  // so that clients can fetch their results.
  void StopAccepting() { accepting_ = false; }

  grpc::Status Reconstruct(
      grpc::ServerContext* context,
      grpc::ServerReaderWriter<v1::JobEvent, v1::ReconstructRequest>* stream) override;
  grpc::Status GetJob(grpc::ServerContext* context, const v1::GetJobRequest* request,
                      v1::Job* response) override;
  grpc::Status WatchJob(grpc::ServerContext* context, const v1::WatchJobRequest* request,
                        grpc::ServerWriter<v1::JobEvent>* writer) override;
  grpc::Status CancelJob(grpc::ServerContext* context, const v1::CancelJobRequest* request,
                         v1::Job* response) override;
  grpc::Status ListJobs(grpc::ServerContext* context, const v1::ListJobsRequest* request,
                        v1::ListJobsResponse* response) override;

 private:
  // Reads the header and the chunks of an upload; checks parameters, size, the parts' sizes (into
  // `part_bytes`, CheckDracoPartBytes) and checksum. The buffer's bytes are held in the memory for
  // uploads (`hold`) as it grows: RESOURCE_EXHAUSTED at the header when the upload can never fit,
  // with a retry delay when it does not fit now. The call is cancelled when its upload makes no
  // progress for options_.stall_seconds (DEADLINE_EXCEEDED, for the log). Progress is bytes:
  // kStallProgressBytes, or the rest of the upload, since the last progress; empty chunks, or a
  // byte now and then, are none.
  grpc::Status ReadUpload(grpc::ServerContext* context,
                          grpc::ServerReaderWriter<v1::JobEvent, v1::ReconstructRequest>* stream,
                          v1::Parameters& parameters, std::string& upload,
                          std::vector<uint64_t>& part_bytes, UploadMemory::Hold& hold);
  // OK, with the caller, for a call carrying the token of one of options_.clients (or any call
  // when there are none); UNAUTHENTICATED, logged with the peer, otherwise.
  grpc::Status Authenticate(const grpc::ServerContext& context, Caller& caller);
  // Drops the jobs finished more than options_.result_ttl_seconds ago.
  void ExpireResults();
  // The job with `id` after dropping expired ones, or null, also when it is another client's
  // and `caller` is no operator.
  std::shared_ptr<Job> FindJob(const std::string& id, const Caller& caller);
  std::string NewJobId() ABSL_LOCKS_EXCLUDED(id_mutex_);
  // Runs `write` (one write to the call of `context`, true when it went out), cancelling the
  // call when the write is held longer than options_.stall_seconds (it then returns false, as
  // for a gone caller).
  template <typename Write>
  bool WriteUnlessStalled(grpc::ServerContext* context, Write write) {
    IdleWatchdog::Watch watch = stall_watchdog_.Start(context);
    return write();
  }

  const ServerOptions& options_;
  JobStore& store_;
  JobScheduler& scheduler_;
  UploadMemory& upload_memory_;
  ServerMetrics& metrics_;
  const Clock& clock_;
  // Ends calls stalled for options_.stall_seconds: an upload receiving nothing, or a write of
  // an event that the client does not read (flow control holds the write).
  IdleWatchdog stall_watchdog_;
  std::atomic<bool> accepting_{true};
  absl::Mutex id_mutex_;
  absl::BitGen id_random_ ABSL_GUARDED_BY(id_mutex_);
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_RECONSTRUCTION_SERVICE_H_
