// Load: 32 clients at once against one membraned process, each submitting jobs and following,
// cancelling or dropping them; a busy answer (full queue) is retried. Every accepted job must
// end as its client expects, and once the results have expired membraned's resident memory
// must be back near what it was after a warm-up.
#include <sys/types.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "proto/crc32c.h"
#include "tests/support/cli_runner.h"
#include "tests/server/http_get.h"
#include "tests/server/membraned_process.h"
#include "tests/server/subprocess.h"
#include "tests/support/scratch_dir.h"

// A namespace of its own: the suite's sources may be compiled as one unit.
namespace membrane::testing::load_test {
namespace {

constexpr int kClients = 32;
constexpr int kJobsPerClient = 3;

// What a client does with its job once accepted.
enum class Conduct { kFollow, kCancel, kDrop };

// What a client saw of one job.
struct Outcome {
  std::string id;
  Conduct conduct = Conduct::kFollow;
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  bool mesh_matches = false;  // the mesh bytes match the ResultHeader's size and CRC-32C
  std::string error;          // what went wrong on the client's side, if anything
};

// VmRSS of process `pid`, in bytes.
int64_t RssBytes(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6)) * 1024;
  }
  return -1;
}

void SetDeadline(grpc::ClientContext& context, double seconds) {
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
}

// Reads the events of a call to its end into `out`: the final state, and whether the mesh
// chunks match the ResultHeader.
template <typename Reader>
void ReadToEnd(Reader& reader, Outcome& out) {
  v1::JobEvent event;
  std::string mesh;
  uint64_t mesh_bytes = 0;
  uint32_t mesh_crc = 0;
  while (reader.Read(&event)) {
    if (event.has_result()) {
      mesh_bytes = event.result().mesh_bytes();
      mesh_crc = event.result().mesh_crc32c();
    }
    if (event.has_mesh_chunk()) mesh += event.mesh_chunk();
    if (event.has_done()) out.state = event.done().state();
  }
  out.mesh_matches = mesh_bytes > 0 && mesh.size() == mesh_bytes && Crc32c(mesh) == mesh_crc;
}

// One client: submits `upload` until accepted (a busy or unavailable answer is retried after a
// short, jittered pause, as membrane does), then follows, cancels or drops its job.
Outcome RunClient(v1::Reconstruction::Stub& stub, const std::string& upload, Conduct conduct,
                  uint32_t seed) {
  Outcome out;
  out.conduct = conduct;
  std::mt19937 random(seed);
  const absl::Time give_up = absl::Now() + absl::Seconds(240);
  while (out.id.empty()) {
    if (absl::Now() > give_up) {
      out.error = "never accepted";
      return out;
    }
    grpc::ClientContext context;
    SetDeadline(context, 240);
    auto stream = stub.Reconstruct(&context);
    v1::ReconstructRequest header;
    header.mutable_header()->set_upload_bytes(upload.size());
    header.mutable_header()->set_upload_crc32c(Crc32c(upload));
    v1::ReconstructRequest chunk;
    chunk.set_chunk(upload);
    stream->Write(header);
    stream->Write(chunk);
    stream->WritesDone();
    v1::JobEvent first;
    if (stream->Read(&first) && first.has_accepted()) {
      out.id = first.accepted().job_id();
      if (conduct == Conduct::kFollow) {
        ReadToEnd(*stream, out);
        stream->Finish();
      } else if (conduct == Conduct::kCancel) {
        grpc::ClientContext cancel_context;
        SetDeadline(cancel_context, 30);
        v1::CancelJobRequest request;
        request.set_job_id(out.id);
        v1::Job job;
        const grpc::Status s = stub.CancelJob(&cancel_context, request, &job);
        if (!s.ok()) out.error = "CancelJob: " + s.error_message();
        ReadToEnd(*stream, out);
        stream->Finish();
      } else {
        context.TryCancel();  // the client goes away; the job goes on (--on-disconnect=continue)
        stream->Finish();
        grpc::ClientContext watch_context;
        SetDeadline(watch_context, 240);
        v1::WatchJobRequest request;
        request.set_job_id(out.id);
        auto reader = stub.WatchJob(&watch_context, request);
        ReadToEnd(*reader, out);
        const grpc::Status s = reader->Finish();
        if (!s.ok()) out.error = "WatchJob: " + s.error_message();
      }
      return out;
    }
    const grpc::Status s = stream->Finish();
    if (s.error_code() != grpc::StatusCode::RESOURCE_EXHAUSTED &&
        s.error_code() != grpc::StatusCode::UNAVAILABLE) {
      out.error = "refused: " + s.error_message();
      return out;
    }
    // A client's backoff, not a wait for an event: the server said to come back later.
    std::this_thread::sleep_for(std::chrono::milliseconds(50 + random() % 150));
  }
  return out;
}

// Jobs the server still lists.
int ListedJobs(v1::Reconstruction::Stub& stub) {
  grpc::ClientContext context;
  SetDeadline(context, 30);
  v1::ListJobsResponse list;
  if (!stub.ListJobs(&context, {}, &list).ok()) return -1;
  return list.jobs_size();
}

// Runs one client per conduct in `conducts` at once; their outcomes.
std::vector<Outcome> RunClients(v1::Reconstruction::Stub& stub, const std::string& upload,
                                const std::vector<Conduct>& conducts) {
  std::vector<Outcome> outcomes(conducts.size());
  std::vector<std::thread> threads;
  for (size_t i = 0; i < conducts.size(); ++i) {
    threads.emplace_back([&, i] {
      outcomes[i] = RunClient(stub, upload, conducts[i], static_cast<uint32_t>(i));
    });
  }
  for (std::thread& t : threads) t.join();
  return outcomes;
}

// Waits (up to 60 s) until the server lists no job: the results' TTL has passed and a list
// dropped them.
bool WaitUntilExpired(v1::Reconstruction::Stub& stub) {
  const absl::Time end = absl::Now() + absl::Seconds(60);
  while (ListedJobs(stub) != 0) {
    if (absl::Now() > end) return false;
    absl::SleepFor(absl::Milliseconds(100));
  }
  return true;
}

TEST(LoadTest, ThirtyTwoClientsWithCancelsAndDropsLoseNothingAndMemoryComesBack) {
  ScratchDir dir;
  const std::string cloud = dir.File("sphere.drc");
  ASSERT_EQ(RunMembrane({"synth", "sphere", "-o", cloud, "--points", "4000"}, dir.path())
                .exit_code,
            0);
  const std::string upload = ReadText(cloud);
  ASSERT_FALSE(upload.empty());
  MembranedProcess server =
      StartMembraned(dir, "membraned",
                     {"--workers=2", "--queue=8", "--job-threads=1", "--result-ttl-seconds=1",
                      "--retry-delay-seconds=0.1", "--metrics-listen=127.0.0.1:0"});
  ASSERT_FALSE(server.address.empty());
  std::smatch m;
  const std::string log = ReadText(server.log);
  ASSERT_TRUE(std::regex_search(log, m, std::regex("metrics_port=(\\d+)"))) << log;
  const int metrics_port = std::stoi(m[1].str());
  auto stub = v1::Reconstruction::NewStub(
      grpc::CreateChannel(server.address, grpc::InsecureChannelCredentials()));

  // A warm-up as wide as the load, so that the baseline holds what a served load leaves by
  // design (gRPC's threads and buffers, the allocator's arenas), expired to nothing.
  const std::vector<Conduct> warm_up(kClients, Conduct::kFollow);
  for (const Outcome& o : RunClients(*stub, upload, warm_up)) {
    ASSERT_EQ(o.state, v1::SUCCEEDED) << o.id << " " << o.error;
  }
  ASSERT_TRUE(WaitUntilExpired(*stub));
  const int64_t baseline = RssBytes(server.process->pid());

  std::vector<Conduct> conducts;
  for (int i = 0; i < kClients * kJobsPerClient; ++i) {
    conducts.push_back(i % 4 == 2 ? Conduct::kCancel
                                  : i % 4 == 3 ? Conduct::kDrop : Conduct::kFollow);
  }
  std::vector<Outcome> outcomes;
  for (int round = 0; round < kJobsPerClient; ++round) {
    const std::vector<Conduct> these(conducts.begin() + round * kClients,
                                     conducts.begin() + (round + 1) * kClients);
    for (Outcome& o : RunClients(*stub, upload, these)) outcomes.push_back(std::move(o));
  }
  const int64_t loaded = RssBytes(server.process->pid());

  std::map<std::string, int> ids;
  int cancelled = 0;
  for (const Outcome& o : outcomes) {
    ASSERT_FALSE(o.id.empty()) << o.error;
    EXPECT_TRUE(o.error.empty()) << o.id << ": " << o.error;
    ++ids[o.id];
    if (o.conduct == Conduct::kCancel && o.state == v1::CANCELLED) {
      ++cancelled;
      continue;
    }
    // Followed, re-attached after a drop, or cancelled too late: the whole mesh.
    EXPECT_EQ(o.state, v1::SUCCEEDED) << o.id;
    EXPECT_TRUE(o.mesh_matches) << o.id;
  }
  EXPECT_EQ(ids.size(), outcomes.size()) << "a job id was given twice";
  const std::string metrics = HttpGet(metrics_port, "/metrics");
  const int accepted = kClients + static_cast<int>(outcomes.size());
  EXPECT_EQ(MetricValue(metrics, "membrane_jobs_accepted_total"), accepted) << metrics;
  // Every accepted job ended once, in the state its client saw.
  const double succeeded =
      MetricValue(metrics, "membrane_jobs_finished_total{code=\"OK\",state=\"SUCCEEDED\"}");
  const double cancelled_metric = std::max(
      0.0,
      MetricValue(metrics, "membrane_jobs_finished_total{code=\"CANCELLED\",state=\"CANCELLED\"}"));
  EXPECT_EQ(succeeded + cancelled_metric, accepted) << metrics;
  EXPECT_EQ(cancelled_metric, cancelled) << metrics;

  ASSERT_TRUE(WaitUntilExpired(*stub));
  const int64_t expired = RssBytes(server.process->pid());
  std::printf("membraned RSS: %.1f MB after the warm-up expired, %.1f MB after %zu jobs of %d "
              "clients, %.1f MB once expired\n",
              baseline / 1e6, loaded / 1e6, outcomes.size(), kClients, expired / 1e6);
  // Near the baseline: what a job leaves goes back when it ends, and a result's mesh when it
  // expires (server/memory_release.h); 8 MB is the slack of the arenas' fragmentation.
  EXPECT_LT(expired, baseline + (8 << 20))
      << "baseline " << baseline << " bytes, after the load " << expired;
}

}  // namespace
}  // namespace membrane::testing::load_test
