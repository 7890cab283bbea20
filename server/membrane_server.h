// One membraned instance: the job store, the memory budget, the workers, the gRPC service with
// health checking and reflection, owned together so that main (or a test) holds one object.
#ifndef MEMBRANE_SERVER_MEMBRANE_SERVER_H_
#define MEMBRANE_SERVER_MEMBRANE_SERVER_H_

#include <memory>
#include <string>

#include <grpcpp/server.h>

#include "prometheus/exposer.h"

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "server/clock.h"
#include "server/disk_job_store.h"
#include "server/http_api.h"
#include "server/http_server.h"
#include "server/in_memory_job_store.h"
#include "server/job_runner.h"
#include "server/job_scheduler.h"
#include "server/memory_budget.h"
#include "server/upload_memory.h"
#include "server/reconstruction_service.h"
#include "server/server_metrics.h"
#include "server/server_options.h"
#include "server/store_files.h"

namespace membrane::server {

class MembraneServer {
 public:
  // `clock` (not owned; null: the real clock) times the results' TTL and the stall watchdog,
  // and must outlive the server. `store_files` replaces the file operations of the disk store
  // (options.store_dir): a test's that fail; null for this machine's.
  explicit MembraneServer(ServerOptions options, const Clock* clock = nullptr,
                          std::unique_ptr<StoreFiles> store_files = nullptr);
  // Shutdown(0) unless it was called.
  ~MembraneServer();

  MembraneServer(const MembraneServer&) = delete;
  MembraneServer& operator=(const MembraneServer&) = delete;

  // Loads the jobs of options.store_dir when set (DiskJobStore::Load) and queues again those
  // the previous process did not end, then listens on `address` ("127.0.0.1:0" picks a free
  // port), health SERVING (NOT_SERVING while the store's disk cannot be written), and serves
  // Prometheus metrics on options.metrics_listen (HTTP, path /metrics) when set; ignores
  // SIGPIPE in this process (see decode_subprocess.h). Returns the bound port of `address`;
  // Unavailable when the store cannot be created, read or written, or either address cannot
  // be bound.
  absl::StatusOr<int> Start(const std::string& address);

  // Graceful shutdown: health NOT_SERVING, new Reconstruct calls UNAVAILABLE, running jobs
  // given `grace` to finish, their ends written to the store's directory. The others: with a
  // store directory, queued jobs and those still running after `grace` (interrupted) stay
  // unfinished in it, for the next start to run; in memory only, they end CANCELLED. Then the
  // calls still open get a second to deliver what they can and the server stops. The web
  // console's waiting events requests are answered within 250 ms; its listener serves until
  // the server is destroyed.
  void Shutdown(absl::Duration grace);

  // Blocks until Shutdown has stopped the gRPC server.
  void Wait();

  // The bound port of options.metrics_listen once Start succeeded; 0 when there is none.
  int metrics_port() const { return metrics_port_; }
  // The bound port of options.http_listen once Start succeeded; 0 when there is none.
  int http_port() const { return http_server_ != nullptr ? http_server_->port() : 0; }

 private:
  // Starts exposer_ on options_.metrics_listen.
  absl::Status StartMetrics();
  // Starts http_server_ on options_.http_listen: the web console's files and http_api_.
  absl::Status StartHttp();
  // Sets the health service's status: SERVING once started, unless stopping or the store
  // cannot be written.
  void UpdateHealth() ABSL_LOCKS_EXCLUDED(health_mutex_);

  const ServerOptions options_;
  const RealClock real_clock_;
  const Clock& clock_;
  // Before everything that counts in it: the store's jobs report their end to it.
  ServerMetrics metrics_;
  // Before the store: jobs hold parts of it until they are destroyed.
  UploadMemory upload_memory_;
  // Before the workers and handlers, whose jobs tell it when they end. In memory, or also on
  // disk (disk_store_) with options.store_dir.
  std::unique_ptr<JobStore> store_;
  DiskJobStore* disk_store_ = nullptr;
  MemoryBudget memory_;
  // Before the runner, which watches each running job with it (--max-job-seconds).
  IdleWatchdog job_deadlines_;
  JobRunner runner_;
  JobScheduler scheduler_;
  ReconstructionService service_;
  HttpApi http_api_;
  std::unique_ptr<grpc::Server> server_;
  // Before the store's end: its handlers read the store.
  std::unique_ptr<HttpServer> http_server_;
  // Last: destroyed first, so that no scrape reads what is gone.
  std::shared_ptr<ServerStateCollector> state_collector_;
  std::unique_ptr<prometheus::Exposer> exposer_;
  int metrics_port_ = 0;
  bool shut_down_ = false;
  absl::Mutex health_mutex_;
  // server_ is built and stays (set once Start succeeds; other threads read server_ after).
  bool started_ ABSL_GUARDED_BY(health_mutex_) = false;
  bool serving_ ABSL_GUARDED_BY(health_mutex_) = false;  // started and not stopping
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_MEMBRANE_SERVER_H_
