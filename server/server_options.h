// The limits and policies of one membraned instance, as set by its flags (server/main.cc).
#ifndef MEMBRANE_SERVER_SERVER_OPTIONS_H_
#define MEMBRANE_SERVER_SERVER_OPTIONS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "server/client_tokens.h"

namespace membrane::server {

enum class DisconnectPolicy {
  kContinue,  // a job whose Reconstruct call drops keeps running, for WatchJob to re-attach
  kCancel,    // a dropped call cancels its job
};

struct ServerOptions {
  int workers = 1;                          // jobs running at once
  // Threads of one job's surface fit and mesh check; 0: the cores shared among the jobs
  // running when it starts (JobThreads).
  int job_threads = 1;
  int cores = 1;                            // this machine's, for job_threads 0
  int queue = 16;                           // jobs waiting beyond those; more: RESOURCE_EXHAUSTED
  // This replica's name (a DNS label; proto/job_routing.h), the prefix of its job ids so that
  // a balancer can route calls about a job to it; empty = none.
  std::string replica;
  // HOST:PORT serving Prometheus metrics over HTTP (/metrics); empty = none.
  std::string metrics_listen;
  // HOST:PORT serving the web console and its JSON API over HTTP (server/http_api.h); empty =
  // none. The page's files come from web_dir, three.js from three_js_dir (Debian's libjs-three).
  std::string http_listen;
  std::string web_dir;
  std::string three_js_dir = "/usr/share/javascript/three";
  // A directory where jobs and results are also written (DiskJobStore), so that they survive
  // a restart; empty = in memory only.
  std::string store_dir;
  int max_calls = 1000;                     // calls served at once, of any kind; 0 = no limit
  int64_t max_upload_bytes = 512 << 20;     // Draco bytes of one upload
  int64_t max_points = 50'000'000;          // points of one decoded cloud
  // Bytes of one job's mesh as returned (Draco or PLY); a larger one fails the job with
  // RESOURCE_EXHAUSTED. The store's records are bounded by it (RecordBytesFor).
  int64_t max_result_bytes = int64_t{2} << 30;
  // Voxels of one job's grid, padding included; 0: no cap (the memory budget decides).
  int64_t voxel_budget = 0;
  int64_t memory_budget_bytes = 0;          // estimated bytes across running jobs; 0 = no limit
  std::string memory_budget_source;         // for the log: the flag, or what the default took
  std::string malloc_settings;              // for the log: "one-arena" (the policy) or "environment"
  int64_t upload_memory_bytes = 0;          // uploads held at once (UploadMemory); 0 = no limit
  double stall_seconds = 300;               // a call stalled this long is cancelled; 0 = never
  // A stage running longer than this sends StageProgress every second; 0 = every stage.
  double progress_after_seconds = 1;
  // A job running this long ends FAILED DEADLINE_EXCEEDED, and one whose estimated floor of
  // seconds is over it is refused before it runs (TimeLimitGate); 0 = no limit.
  double max_job_seconds = 1800;
  double result_ttl_seconds = 3600;         // how long finished jobs and results are kept
  double grace_seconds = 30;                // SIGTERM: how long running jobs may finish
  DisconnectPolicy on_disconnect = DisconnectPolicy::kContinue;
  double decoder_timeout_seconds = 30;      // wall clock for one decode subprocess
  int64_t decoder_memory_bytes = 4LL << 30; // RLIMIT_AS of the decode subprocess
  std::string decoder_path;                 // the membrane-decode binary
  double retry_delay_seconds = 2;           // RetryInfo sent with a full queue
  // The clients whose bearer tokens membrane.v1 calls must carry (--token-file); empty = open.
  std::vector<ClientToken> clients;
  std::string tls_cert_pem;                 // the server's certificate chain; empty = plaintext
  std::string tls_key_pem;                  // its private key (set with tls_cert_pem)
};

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_SERVER_OPTIONS_H_
