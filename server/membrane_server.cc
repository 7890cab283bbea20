#include "server/membrane_server.h"

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <exception>
#include <vector>
#include <utility>

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpc/grpc.h>
#include <grpcpp/health_check_service_interface.h>
#include <grpcpp/resource_quota.h>
#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server_builder.h>

#include "absl/status/status.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "proto/endpoint_address.h"
#include "server/job_end_hook.h"
#include "server/memory_release.h"
#include "server/server_log.h"
#include "server/web_assets.h"

namespace membrane::server {
namespace {

constexpr int kMaxMessageBytes = 4 << 20;  // gRPC's default, stated: chunks keep under it
// Threads of the sync server that poll for calls rather than serve one (its MAX_POLLERS
// default), on top of --max-calls.
constexpr int kPollerThreads = 2;

// The metrics endpoint's threads (each serves one connection at a time), and how long one may
// wait for a request to arrive whole. A scrape's request is one packet on a LAN.
constexpr int kMetricsThreads = 4;
constexpr int kMetricsRequestTimeoutMs = 2000;
// The web console's threads: each browser tab holds one in a waiting events request and takes
// another now and then for the job list. A response (a mesh) must be taken within the timeout.
constexpr int kHttpThreads = 16;
constexpr int kHttpRequestTimeoutMs = 10000;

// The store of options.store_dir: in memory only when it is empty.
std::unique_ptr<JobStore> MakeStore(const ServerOptions& options,
                                    std::unique_ptr<StoreFiles> files) {
  if (options.store_dir.empty()) return std::make_unique<InMemoryJobStore>();
  DiskJobStoreOptions store;
  store.max_upload_bytes = options.max_upload_bytes;
  store.max_record_bytes = RecordBytesFor(options.max_result_bytes);
  // A disk that fails is tried again as often as refused clients are told to come back.
  store.probe_interval = absl::Seconds(std::max(options.retry_delay_seconds, 0.1));
  return std::make_unique<DiskJobStore>(options.store_dir, store,
                                        files != nullptr ? std::move(files) : PosixStoreFiles());
}

}  // namespace

MembraneServer::MembraneServer(ServerOptions options, const Clock* clock,
                               std::unique_ptr<StoreFiles> store_files)
    : options_(std::move(options)),
      clock_(clock != nullptr ? *clock : real_clock_),
      upload_memory_(options_.upload_memory_bytes),
      store_(MakeStore(options_, std::move(store_files))),
      memory_(options_.memory_budget_bytes),
      job_deadlines_(absl::Seconds(options_.max_job_seconds), clock_),
      runner_(options_, memory_, metrics_, job_deadlines_),
      scheduler_(options_.workers, options_.queue,
                 [this](const std::shared_ptr<Job>& job) {
                   runner_.Run(job, JobThreads(options_, scheduler_.running()));
                   // The job's grid, membrane and surface are freed: give their pages back.
                   ReleaseFreedMemory();
                 }),
      service_(options_, *store_, scheduler_, upload_memory_, metrics_, clock_),
      http_api_(options_, *store_, clock_, memory_) {
  disk_store_ = dynamic_cast<DiskJobStore*>(store_.get());
}

MembraneServer::~MembraneServer() { Shutdown(absl::ZeroDuration()); }

absl::StatusOr<int> MembraneServer::Start(const std::string& address) {
  // A decoder child that dies while its stdin is being fed must cost an EPIPE, not the
  // server: SIGPIPE is ignored process-wide (gRPC needs the same for its sockets).
  signal(SIGPIPE, SIG_IGN);
  if (absl::Status s = CheckEndpointAddress("--listen", address, PortZero::kAllowed); !s.ok()) {
    return s;
  }
  for (auto [flag, listen] : {std::pair{"--metrics-listen", &options_.metrics_listen},
                               std::pair{"--http-listen", &options_.http_listen}}) {
    if (listen->empty()) continue;
    if (absl::Status s = CheckEndpointAddress(flag, *listen, PortZero::kAllowed); !s.ok()) {
      return s;
    }
  }
  std::vector<std::shared_ptr<Job>> resumed;
  if (disk_store_ != nullptr) {
    disk_store_->SetWritableListener([this](bool) { UpdateHealth(); });
    absl::StatusOr<DiskJobStore::Loaded> loaded = disk_store_->Load(
        [this](const std::string& id) { return JobEndHook(metrics_, *store_, id); });
    if (!loaded.ok()) return loaded.status();
    resumed = std::move(loaded->resumed);
  }
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  int port = 0;
  std::shared_ptr<grpc::ServerCredentials> credentials = grpc::InsecureServerCredentials();
  if (!options_.tls_cert_pem.empty()) {
    grpc::SslServerCredentialsOptions ssl;
    ssl.pem_key_cert_pairs.push_back({options_.tls_key_pem, options_.tls_cert_pem});
    credentials = grpc::SslServerCredentials(ssl);
  }
  builder.AddListeningPort(address, credentials, &port);
  // gRPC sets SO_REUSEPORT by default: a second membraned on a port in use would start and
  // take half of the connections, each seeing the other's jobs as NOT_FOUND. Refuse instead.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.SetMaxReceiveMessageSize(kMaxMessageBytes);
  // The sync server gives each open call a thread: without a bound, a flood of calls (or of
  // uploads that never end) would create threads until the process dies. Past it, gRPC answers
  // RESOURCE_EXHAUSTED "Server Threadpool Exhausted". The pollers take threads too.
  if (options_.max_calls > 0) {
    grpc::ResourceQuota quota("membraned");
    quota.SetMaxThreads(options_.max_calls + kPollerThreads);
    builder.SetResourceQuota(quota);
  }
  // A client whose network vanished (no FIN) would hold its call, and its thread, for the
  // kernel's two hours: a ping after a minute without traffic, unanswered for 20 s, ends it.
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIME_MS, 60'000);
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 20'000);
  builder.RegisterService(&service_);
  server_ = builder.BuildAndStart();
  if (server_ == nullptr || port == 0) {
    return absl::UnavailableError(
        absl::StrCat("cannot listen on ", address, " (in use by another process?)"));
  }
  for (auto [listen, start] : {std::pair{&options_.metrics_listen, &MembraneServer::StartMetrics},
                                std::pair{&options_.http_listen, &MembraneServer::StartHttp}}) {
    if (listen->empty()) continue;
    if (absl::Status s = (this->*start)(); !s.ok()) {
      exposer_.reset();
      server_->Shutdown();
      server_.reset();
      return s;
    }
  }
  // Queued once the server is sure to start: a failed start leaves them on disk untouched.
  for (std::shared_ptr<Job>& job : resumed) {
    LogEvent("job_resumed", {{"job", job->id()}, {"peer", job->peer()}});
    scheduler_.Resume(std::move(job));
  }
  {
    absl::MutexLock lock(&health_mutex_);
    started_ = true;
    serving_ = true;
  }
  UpdateHealth();
  LogEvent("server_started", {{"address", address},
                              {"port", absl::StrCat(port)},
                              {"metrics_port", absl::StrCat(metrics_port_)},
                              {"http_port", absl::StrCat(http_port())},
                              {"replica", options_.replica.empty() ? "-" : options_.replica},
                              {"workers", absl::StrCat(options_.workers)},
                              {"job_threads", options_.job_threads > 0
                                                  ? absl::StrCat(options_.job_threads)
                                                  : absl::StrCat("auto (", options_.cores,
                                                                 " cores)")},
                              {"queue", absl::StrCat(options_.queue)},
                              {"max_calls", absl::StrCat(options_.max_calls)},
                              {"max_job_seconds", absl::StrCat(options_.max_job_seconds)},
                              {"memory_budget_bytes", absl::StrCat(options_.memory_budget_bytes)},
                              {"memory_budget_from", options_.memory_budget_source.empty()
                                                         ? "options"
                                                         : options_.memory_budget_source},
                              {"upload_memory_bytes", absl::StrCat(options_.upload_memory_bytes)},
                              {"malloc", options_.malloc_settings.empty()
                                             ? "-"
                                             : options_.malloc_settings},
                              {"store_dir", options_.store_dir.empty() ? "-" : options_.store_dir},
                              {"tls", options_.tls_cert_pem.empty() ? "off" : "on"},
                              {"token", options_.clients.empty()
                                            ? std::string("off")
                                            : absl::StrCat(options_.clients.size(), " clients")}});
  return port;
}

void MembraneServer::Shutdown(absl::Duration grace) {
  if (shut_down_) return;
  shut_down_ = true;
  bool started = false;
  {
    absl::MutexLock lock(&health_mutex_);
    started = started_;
    serving_ = false;
  }
  // A server that never started (its Start failed and said why) stops without a word.
  if (started) {
    LogEvent("server_stopping", {{"grace_seconds", absl::StrCat(absl::ToDoubleSeconds(grace))}});
  }
  // Refusing first: once health says NOT_SERVING, no new job is taken.
  service_.StopAccepting();
  UpdateHealth();
  if (disk_store_ != nullptr) {
    // A crash and a stop leave the same store: what did not end runs at the next start.
    scheduler_.Shutdown(grace, JobScheduler::Unfinished::kKeep);
    // The ends of the jobs that finished are on disk before the process may exit, and
    // nothing the open calls do to the others (a cancel on disconnect) is written.
    disk_store_->Close();
  } else {
    scheduler_.Shutdown(grace, JobScheduler::Unfinished::kCancel);
  }
  if (server_ != nullptr) {
    // The open calls see their jobs ended and write the outcome; a second is plenty.
    server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(1));
  }
  // Waiting events requests answer within 250 ms. The listener stays until the server is
  // destroyed (civetweb's stop takes up to 2 s, which a process about to exit need not wait).
  http_api_.Stop();
  if (started) LogEvent("server_stopped", {});
}

absl::Status MembraneServer::StartHttp() {
  absl::StatusOr<WebAssets> assets = WebAssets::Load(options_.web_dir, options_.three_js_dir);
  if (!assets.ok()) return assets.status();
  absl::StatusOr<std::unique_ptr<HttpServer>> http = HttpServer::Start(
      options_.http_listen, kHttpThreads, kHttpRequestTimeoutMs,
      [this, assets = *std::move(assets)](const HttpRequest& request) {
        if (absl::StartsWith(request.path, "/api/")) return http_api_.Handle(request);
        return assets.Serve(request);
      });
  if (!http.ok()) return http.status();
  http_server_ = *std::move(http);
  return absl::OkStatus();
}

absl::Status MembraneServer::StartMetrics() {
  state_collector_ = std::make_shared<ServerStateCollector>([this] {
    ServerState s;
    s.queued = scheduler_.queued();
    s.queue_limit = options_.queue;
    s.running = scheduler_.running();
    s.workers = options_.workers;
    s.memory_reserved_bytes = memory_.reserved();
    s.memory_budget_bytes = std::max<int64_t>(options_.memory_budget_bytes, 0);
    s.memory_waiting_jobs = memory_.waiting();
    s.upload_held_bytes = upload_memory_.held();
    s.upload_memory_bytes = std::max<int64_t>(options_.upload_memory_bytes, 0);
    s.store_writable = store_->writable();
    return s;
  });
  // prometheus-cpp reports a port it cannot bind by throwing: the one exception caught here.
  try {
    // Several scrapes at once (Prometheus, a person with curl, a second Prometheus), and a
    // request that is not sent whole within kMetricsRequestTimeoutMs gives its thread back:
    // civetweb's default of one thread waiting 30 s let one half-sent request block them all.
    exposer_ = std::make_unique<prometheus::Exposer>(std::vector<std::string>{
        "listening_ports", options_.metrics_listen,
        "num_threads", absl::StrCat(kMetricsThreads),
        "request_timeout_ms", absl::StrCat(kMetricsRequestTimeoutMs)});
  } catch (const std::exception& e) {
    return absl::UnavailableError(absl::StrCat("cannot serve metrics on ", options_.metrics_listen,
                                               " (--metrics-listen): ", e.what()));
  }
  exposer_->RegisterCollectable(metrics_.registry());
  exposer_->RegisterCollectable(state_collector_);
  const std::vector<int> ports = exposer_->GetListeningPorts();
  metrics_port_ = ports.empty() ? 0 : ports.front();
  return absl::OkStatus();
}

void MembraneServer::UpdateHealth() {
  // Under the lock, so that two updates cannot land in the opposite order.
  absl::MutexLock lock(&health_mutex_);
  if (!started_) return;
  const bool serving = serving_ && store_->writable();
  // Probes ask for the server ("") or for the service by name; both answer the same.
  server_->GetHealthCheckService()->SetServingStatus(v1::Reconstruction::service_full_name(),
                                                     serving);
  server_->GetHealthCheckService()->SetServingStatus(serving);
}

void MembraneServer::Wait() {
  if (server_ != nullptr) server_->Wait();
}

}  // namespace membrane::server
