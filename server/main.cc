// membraned: the membrane reconstruction server (proto/membrane/v1/reconstruction.proto).
// Runs until SIGTERM or SIGINT, then shuts down gracefully (see MembraneServer::Shutdown).
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "absl/flags/flag.h"
#include "absl/flags/parse.h"
#include "absl/flags/reflection.h"
#include "absl/flags/usage.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "core/base/malloc_policy.h"
#include "core/io/file_bytes.h"
#include "core/pipeline/machine_memory.h"
#include "core/pipeline/reconstruction_pipeline.h"
#include "core/pipeline/thread_limits.h"
#include "proto/job_routing.h"
#include "server/client_tokens.h"
#include "server/membrane_server.h"
#include "server/memory_release.h"
#include "server/memory_budget.h"
#include "server/upload_memory.h"
#include "server/server_options.h"

ABSL_FLAG(std::string, listen, "127.0.0.1:50051", "address to listen on (HOST:PORT; port 0 = any)");
ABSL_FLAG(int, workers, 0, "jobs running at once; 0 = the number of cores");
ABSL_FLAG(int, job_threads, 0,
          "threads of one job's surface fit and mesh check; 0 = the cores shared among the jobs "
          "running when it starts (at least 1)");
ABSL_FLAG(int, queue, 16, "jobs waiting beyond the running ones; more get RESOURCE_EXHAUSTED");
ABSL_FLAG(int, max_calls, 1000,
          "calls served at once, of any kind (each holds a thread); more get RESOURCE_EXHAUSTED; "
          "0 = no limit");
ABSL_FLAG(std::string, store_dir, "",
          "a directory where jobs and their results are also written, so that they survive a "
          "crash or restart (until --result-ttl-seconds); empty = in memory only");
ABSL_FLAG(std::string, metrics_listen, "",
          "HOST:PORT serving Prometheus metrics over HTTP at /metrics (jobs, stages, queue, "
          "memory); empty = none");
ABSL_FLAG(std::string, http_listen, "",
          "HOST:PORT serving the web console (jobs, live progress, the mesh in 3D) and its JSON "
          "API over HTTP, with --token-file's tokens; empty = none");
ABSL_FLAG(std::string, web_dir, "",
          "the web console's files; empty = 'web' beside membraned, else "
          "../share/membrane/web from it");
ABSL_FLAG(std::string, three_js_dir, "/usr/share/javascript/three",
          "three.js for the web console (Debian's libjs-three)");
ABSL_FLAG(std::string, replica, "",
          "this replica's name (lower-case letters, digits, '-'; e.g. the pod's), put in front "
          "of its job ids so that a balancer routes calls about a job here; empty = none");
ABSL_FLAG(int64_t, max_upload_bytes, 512LL << 20, "largest Draco upload, bytes");
ABSL_FLAG(int64_t, max_points, 50'000'000, "largest decoded cloud, points");
ABSL_FLAG(int64_t, max_result_bytes, 2LL << 30,
          "largest mesh a job returns, bytes (Draco or PLY); a job whose mesh is larger fails "
          "RESOURCE_EXHAUSTED");
ABSL_FLAG(int64_t, voxel_budget, 0,
          "largest grid of one job, voxels (padding included); 0 = no cap in voxels: the "
          "memory budget decides, on the job's estimated bytes");
ABSL_FLAG(int64_t, memory_budget_bytes, -1,
          "estimated bytes across running jobs (about 6 per voxel, and 1000 per membrane voxel "
          "for the surface); -1 = 3/4 of this machine's memory, or of its container's limit "
          "when lower; 0 = no limit");
ABSL_FLAG(int64_t, upload_memory_bytes, -1,
          "bytes of uploads held at once (arriving, queued, being decoded), beside the memory "
          "budget; -1 = 1/8 of this machine's memory or of its container's limit; 0 = no limit");
ABSL_FLAG(double, stall_seconds, 300,
          "a call that makes no progress for this long is cancelled: its upload receives "
          "under 16 KiB, or its client reads none of the events written to it; 0 = never");
ABSL_FLAG(double, progress_after_seconds, 1,
          "a stage running longer than this sends its progress (fraction done, seconds so "
          "far) every second; 0 = every stage, from its start");
ABSL_FLAG(double, max_job_seconds, 1800,
          "a job running this long ends FAILED DEADLINE_EXCEEDED, and one whose estimated "
          "floor of seconds is over it is refused before it runs; 0 = no limit");
ABSL_FLAG(double, result_ttl_seconds, 3600, "how long finished jobs and results are kept");
ABSL_FLAG(double, grace_seconds, 30, "on SIGTERM, how long running jobs may finish");
ABSL_FLAG(std::string, on_disconnect, "continue",
          "a dropped Reconstruct call: continue (re-attach with WatchJob) or cancel");
ABSL_FLAG(double, decoder_timeout_seconds, 30, "wall-clock limit of one upload's decoding");
ABSL_FLAG(int64_t, decoder_memory_bytes, 4LL << 30, "address-space limit of the decoder process");
ABSL_FLAG(std::string, decoder_path, "", "the membrane-decode binary; empty = beside membraned");
ABSL_FLAG(double, retry_delay_seconds, 2, "retry delay sent with a full queue");
ABSL_FLAG(std::string, token_file, "",
          "the clients' bearer tokens, one of which every membrane.v1 call must carry: a file "
          "of lines 'NAME TOKEN' or 'NAME TOKEN operator' (an operator sees every client's "
          "jobs; the others their own), a file holding one bare token, or a directory of such "
          "files; empty = none");
ABSL_FLAG(std::string, tls_cert, "", "PEM certificate chain: serve TLS (with --tls-key)");
ABSL_FLAG(std::string, tls_key, "", "PEM private key of --tls-cert");

namespace membrane::server {
namespace {

// The directory of this executable, for the default --decoder_path.
std::string ExecutableDirectory() {
  char path[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return ".";
  std::string dir(path, static_cast<size_t>(n));
  return dir.substr(0, dir.rfind('/'));
}

// The default --web-dir: "web" beside this executable (the build tree), or else
// ../share/membrane/web from it (an installation: /usr/local/bin and /usr/local/share).
std::string DefaultWebDirectory() {
  const std::string beside = ExecutableDirectory() + "/web";
  struct stat s;
  if (stat(beside.c_str(), &s) == 0 && S_ISDIR(s.st_mode)) return beside;
  return ExecutableDirectory() + "/../share/membrane/web";
}

// Reads the files of --token-file, --tls-cert and --tls-key into `o`; an error line and false
// when one cannot be read or only one of the TLS pair is given.
bool ReadSecrets(ServerOptions& o) {
  if (const std::string path = absl::GetFlag(FLAGS_token_file); !path.empty()) {
    absl::StatusOr<std::vector<ClientToken>> clients = ReadClientTokens(path);
    if (!clients.ok()) {
      std::fprintf(stderr, "membraned: --token-file: %s\n",
                   std::string(clients.status().message()).c_str());
      return false;
    }
    o.clients = *std::move(clients);
  }
  const std::string cert = absl::GetFlag(FLAGS_tls_cert), key = absl::GetFlag(FLAGS_tls_key);
  if (cert.empty() != key.empty()) {
    std::fprintf(stderr, "membraned: --tls-cert and --tls-key go together\n");
    return false;
  }
  if (cert.empty()) return true;
  for (auto [flag, path, pem] : {std::tuple{"--tls-cert", cert, &o.tls_cert_pem},
                                 std::tuple{"--tls-key", key, &o.tls_key_pem}}) {
    absl::StatusOr<std::string> bytes = ReadFileBytes(path);
    if (!bytes.ok()) {
      std::fprintf(stderr, "membraned: %s: %s\n", flag,
                   std::string(bytes.status().message()).c_str());
      return false;
    }
    *pem = *std::move(bytes);
  }
  return true;
}

// The options from the flags; an error line and false when a value is out of range.
bool OptionsFromFlags(ServerOptions& o) {
  o.workers = absl::GetFlag(FLAGS_workers);
  const int cores = MachineThreads();
  if (o.workers <= 0) o.workers = cores;
  o.cores = cores;
  o.job_threads = absl::GetFlag(FLAGS_job_threads);
  if (o.job_threads < 0 || o.job_threads > kMaxReconstructionThreads) {
    std::fprintf(stderr, "membraned: --job-threads %d is not in 0..%d\n", o.job_threads,
                 kMaxReconstructionThreads);
    return false;
  }
  o.queue = absl::GetFlag(FLAGS_queue);
  o.max_calls = absl::GetFlag(FLAGS_max_calls);
  o.metrics_listen = absl::GetFlag(FLAGS_metrics_listen);
  o.store_dir = absl::GetFlag(FLAGS_store_dir);
  o.http_listen = absl::GetFlag(FLAGS_http_listen);
  o.web_dir = absl::GetFlag(FLAGS_web_dir);
  if (o.web_dir.empty()) o.web_dir = DefaultWebDirectory();
  o.three_js_dir = absl::GetFlag(FLAGS_three_js_dir);
  o.replica = absl::GetFlag(FLAGS_replica);
  if (!o.replica.empty() && !IsReplicaName(o.replica)) {
    std::fprintf(stderr,
                 "membraned: --replica '%s' is not a DNS label (1-63 lower-case letters, digits "
                 "and '-', no '-' at either end)\n",
                 o.replica.c_str());
    return false;
  }
  o.max_upload_bytes = absl::GetFlag(FLAGS_max_upload_bytes);
  o.max_points = absl::GetFlag(FLAGS_max_points);
  o.max_result_bytes = absl::GetFlag(FLAGS_max_result_bytes);
  o.voxel_budget = absl::GetFlag(FLAGS_voxel_budget);
  o.memory_budget_bytes = absl::GetFlag(FLAGS_memory_budget_bytes);
  o.upload_memory_bytes = absl::GetFlag(FLAGS_upload_memory_bytes);
  for (auto [flag, value] : {std::pair{"--memory-budget-bytes", o.memory_budget_bytes},
                             std::pair{"--upload-memory-bytes", o.upload_memory_bytes}}) {
    if (value < -1) {
      std::fprintf(stderr, "membraned: %s %lld is not -1 (auto), 0 (none) or a byte count\n",
                   flag, static_cast<long long>(value));
      return false;
    }
  }
  const MachineMemory machine = ReadMachineMemory();
  o.memory_budget_source = "--memory-budget-bytes";
  if (o.memory_budget_bytes == -1) {
    o.memory_budget_bytes = DefaultMemoryBudget(machine.total_bytes);
    o.memory_budget_source = "3/4 of " + machine.total_source;
  }
  if (o.upload_memory_bytes == -1) o.upload_memory_bytes = DefaultUploadMemory(machine.total_bytes);
  o.result_ttl_seconds = absl::GetFlag(FLAGS_result_ttl_seconds);
  o.stall_seconds = absl::GetFlag(FLAGS_stall_seconds);
  o.progress_after_seconds = absl::GetFlag(FLAGS_progress_after_seconds);
  o.max_job_seconds = absl::GetFlag(FLAGS_max_job_seconds);
  o.grace_seconds = absl::GetFlag(FLAGS_grace_seconds);
  o.decoder_timeout_seconds = absl::GetFlag(FLAGS_decoder_timeout_seconds);
  o.decoder_memory_bytes = absl::GetFlag(FLAGS_decoder_memory_bytes);
  o.decoder_path = absl::GetFlag(FLAGS_decoder_path);
  if (o.decoder_path.empty()) o.decoder_path = ExecutableDirectory() + "/membrane-decode";
  o.retry_delay_seconds = absl::GetFlag(FLAGS_retry_delay_seconds);
  const std::string on_disconnect = absl::GetFlag(FLAGS_on_disconnect);
  if (on_disconnect == "continue") {
    o.on_disconnect = DisconnectPolicy::kContinue;
  } else if (on_disconnect == "cancel") {
    o.on_disconnect = DisconnectPolicy::kCancel;
  } else {
    std::fprintf(stderr, "membraned: --on-disconnect '%s' is not one of: continue, cancel\n",
                 on_disconnect.c_str());
    return false;
  }
  if (!ReadSecrets(o)) return false;
  if (o.queue < 0 || o.max_calls < 0 || o.max_upload_bytes <= 0 || o.max_points <= 0 ||
      o.max_result_bytes <= 0 ||
      o.voxel_budget < 0 || o.result_ttl_seconds < 0 || o.grace_seconds < 0 ||
      o.decoder_timeout_seconds <= 0 || !(o.stall_seconds >= 0) || !(o.max_job_seconds >= 0) ||
      !(o.progress_after_seconds >= 0)) {
    std::fprintf(stderr,
                 "membraned: --queue, --max-calls, --grace-seconds, --result-ttl-seconds, "
                 "--stall-seconds, --progress-after-seconds, --max-job-seconds and "
                 "--voxel-budget must be >= 0; "
                 "the other limits > 0\n");
    return false;
  }
  return true;
}

// Abseil flag names are C++ identifiers (--grace_seconds); operators and our docs write
// --grace-seconds. Rewrites the dashes of each "--name[=value]" name to underscores.
std::vector<char*> UnderscoreFlagNames(int argc, char** argv, std::vector<std::string>& storage) {
  storage.assign(argv, argv + argc);
  std::vector<char*> out;
  for (std::string& arg : storage) {
    if (arg.rfind("--", 0) == 0) {
      const size_t end = std::min(arg.find('='), arg.size());
      for (size_t i = 2; i < end; ++i) {
        if (arg[i] == '-') arg[i] = '_';
      }
    }
    out.push_back(arg.data());
  }
  return out;
}

// "membraned VERSION (BUILD_TYPE build)", from the build (server/CMakeLists.txt).
std::string VersionLine() {
  return absl::StrCat("membraned ", MEMBRANE_VERSION, " (", MEMBRANE_BUILD_TYPE, " build)");
}

// The flags of this file, written as operators type them (--grace-seconds), with their
// defaults: Abseil's own --help lists only flags of files named after the program, which
// server/main.cc is not.
void PrintHelp() {
  std::printf("Usage: membraned [--FLAG=VALUE ...]\n%s\n\nFlags:\n",
              "The membrane reconstruction server (proto/membrane/v1). Runs until SIGTERM or "
              "SIGINT, then lets running jobs finish for --grace-seconds.");
  std::vector<const absl::CommandLineFlag*> flags;
  for (const auto& [name, flag] : absl::GetAllFlags()) {
    if (absl::EndsWith(flag->Filename(), "server/main.cc")) flags.push_back(flag);
  }
  std::sort(flags.begin(), flags.end(), [](const auto* a, const auto* b) {
    return a->Name() < b->Name();
  });
  for (const absl::CommandLineFlag* flag : flags) {
    std::printf("  --%s (default: %s)\n      %s\n",
                absl::StrReplaceAll(flag->Name(), {{"_", "-"}}).c_str(),
                flag->DefaultValue().empty() ? "\"\"" : flag->DefaultValue().c_str(),
                flag->Help().c_str());
  }
  std::printf("  --help\n      print this help and exit\n  --version\n      print the version "
              "and exit\n\nExit status: 0 stopped by a signal; 2 a flag is wrong; 4 it cannot "
              "listen or open its store.\n");
}

int Main(int argc, char** argv) {
  // --help and --version are answered before Abseil parses: its own ones filter the flags by
  // the program's file name and exit with 1.
  for (int i = 1; i < argc; ++i) {
    const absl::string_view arg = argv[i];
    if (arg == "--help" || arg == "-h" || arg == "--helpfull") {
      PrintHelp();
      return 0;
    }
    if (arg == "--version") {
      std::printf("%s\n", VersionLine().c_str());
      return 0;
    }
  }
  absl::SetProgramUsageMessage("membrane reconstruction server; see --help");
  std::vector<std::string> storage;
  std::vector<char*> args = UnderscoreFlagNames(argc, argv, storage);
  absl::ParseCommandLine(static_cast<int>(args.size()), args.data());
  ServerOptions options;
  if (!OptionsFromFlags(options)) return 2;
  options.malloc_settings = UseMallocPolicyUnlessChosen() ? "one-arena" : "environment";
  // Block the stop signals before any thread starts, so that only sigwait below sees them.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  MembraneServer server(options);
  absl::StatusOr<int> port = server.Start(absl::GetFlag(FLAGS_listen));
  if (!port.ok()) {
    std::fprintf(stderr, "membraned: %s\n", std::string(port.status().message()).c_str());
    return absl::IsInvalidArgument(port.status()) ? 2 : 4;
  }
  int signal_number = 0;
  sigwait(&stop_signals, &signal_number);
  server.Shutdown(absl::Seconds(options.grace_seconds));
  server.Wait();
  // Nothing is left to do: the jobs' ends are in the store and every call has ended. What a
  // teardown would still run only delays the exit that the pod's grace period counts: the
  // metrics server's listener (civetweb) polls in 2 s quanta before it sees its stop, and
  // gRPC's library shutdown waits up to 10 s for any of its objects still alive.
  std::fflush(nullptr);
  std::_Exit(0);
}

}  // namespace
}  // namespace membrane::server

int main(int argc, char** argv) {
  // The heap on huge pages: the process starts again once for it, before anything else runs.
  membrane::RestartWithHugePageHeap("/proc/self/exe", argv);
  return membrane::server::Main(argc, argv);
}
