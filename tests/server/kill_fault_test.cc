// membraned --store-dir killed with SIGKILL at random moments while its clients, which know
// only their job ids, follow their jobs: every job accepted ends SUCCEEDED with the mesh an
// undisturbed run makes, and none is submitted twice.
//
// MEMBRANE_KILL_CYCLES sets the number of kills (default 20; tests/server/kill_soak.sh runs
// more) and MEMBRANE_KILL_SEED the random moments (default: a new seed, printed).
#include <signal.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <grpc/grpc.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>

#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "proto/crc32c.h"
#include "tests/server/draco_upload.h"
#include "tests/server/membraned_process.h"
#include "tests/server/subprocess.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

int EnvInt(const char* name, int otherwise) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? std::atoi(value) : otherwise;
}

// A channel that reconnects within a quarter of a second of the server's return (gRPC's
// default backoff grows to two minutes).
std::unique_ptr<v1::Reconstruction::Stub> Connect(const std::string& address) {
  grpc::ChannelArguments args;
  args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 50);
  args.SetInt(GRPC_ARG_MIN_RECONNECT_BACKOFF_MS, 50);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 250);
  return v1::Reconstruction::NewStub(
      grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args));
}

void SetDeadline(grpc::ClientContext& context, absl::Duration timeout) {
  context.set_deadline(absl::ToChronoTime(absl::Now() + timeout));
  // A call made while the server is down waits for it rather than failing at once.
  context.set_wait_for_ready(true);
}

// Sends `upload` once; the job id once the server says Accepted, or "" when the call ended
// first (the server was killed, or refused it). The call is then dropped: the job is followed
// by its id only.
std::string Submit(v1::Reconstruction::Stub& stub, const std::string& upload) {
  grpc::ClientContext context;
  SetDeadline(context, absl::Seconds(20));
  auto stream = stub.Reconstruct(&context);
  v1::ReconstructRequest header;
  header.mutable_header()->set_upload_bytes(upload.size());
  header.mutable_header()->set_upload_crc32c(Crc32c(upload));
  bool sent = stream->Write(header);
  for (size_t at = 0; sent && at < upload.size(); at += 1 << 20) {
    v1::ReconstructRequest chunk;
    chunk.set_chunk(upload.substr(at, 1 << 20));
    sent = stream->Write(chunk);
  }
  if (sent) stream->WritesDone();
  std::string id;
  v1::JobEvent event;
  while (id.empty() && stream->Read(&event)) {
    if (event.has_accepted()) id = event.accepted().job_id();
  }
  context.TryCancel();
  stream->Finish();
  return id;
}

struct Outcome {
  v1::JobState state = v1::JOB_STATE_UNSPECIFIED;
  std::string message;
  std::string mesh;
  int watches = 0;
};

// Follows job `id` with WatchJob, calling again whenever a call breaks, until its JobDone, a
// NOT_FOUND (the job was lost), or `timeout`.
Outcome Follow(v1::Reconstruction::Stub& stub, const std::string& id, absl::Duration timeout) {
  const absl::Time end = absl::Now() + timeout;
  Outcome outcome;
  while (absl::Now() < end) {
    ++outcome.watches;
    grpc::ClientContext context;
    SetDeadline(context, end - absl::Now());
    v1::WatchJobRequest request;
    request.set_job_id(id);
    auto reader = stub.WatchJob(&context, request);
    std::string mesh;
    v1::JobEvent event;
    while (reader->Read(&event)) {
      if (event.has_mesh_chunk()) mesh += event.mesh_chunk();
      if (event.has_done()) {
        outcome.state = event.done().state();
        outcome.message = event.done().status().message();
        outcome.mesh = std::move(mesh);
        context.TryCancel();
        reader->Finish();
        return outcome;
      }
    }
    const grpc::Status status = reader->Finish();
    if (status.error_code() == grpc::StatusCode::NOT_FOUND) {
      outcome.message = status.error_message();
      return outcome;
    }
  }
  outcome.message = "not done in time";
  return outcome;
}

// One job a client submitted and follows.
struct Followed {
  std::string id;
  size_t cloud = 0;
  Outcome outcome;
};

TEST(KillFaultTest, EveryAcceptedJobSucceedsThroughSigkills) {
  const int cycles = EnvInt("MEMBRANE_KILL_CYCLES", 20);
  const unsigned seed = static_cast<unsigned>(EnvInt("MEMBRANE_KILL_SEED", std::random_device{}()));
  std::cerr << "MEMBRANE_KILL_CYCLES=" << cycles << " MEMBRANE_KILL_SEED=" << seed << "\n";
  std::mt19937 random(seed);
  ScratchDir dir;
  const std::vector<std::string> flags = {"--store-dir=" + dir.File("jobs"), "--queue=64",
                                          "--job-threads=1"};
  MembranedProcess server = StartMembraned(dir, "membraned-0", flags);
  ASSERT_FALSE(server.address.empty());
  const std::string address = server.address;
  std::vector<std::string> logs = {server.log};
  const std::vector<std::string> clouds = {LosslessDracoCloud("sphere", 4000),
                                           LosslessDracoCloud("torus", 4000),
                                           LosslessDracoCloud("two-spheres", 3000)};
  // The meshes of an undisturbed run.
  std::vector<std::string> expected;
  {
    auto stub = Connect(address);
    for (const std::string& cloud : clouds) {
      const std::string id = Submit(*stub, cloud);
      ASSERT_FALSE(id.empty());
      const Outcome undisturbed = Follow(*stub, id, absl::Seconds(60));
      ASSERT_EQ(undisturbed.state, v1::SUCCEEDED) << undisturbed.message;
      expected.push_back(undisturbed.mesh);
    }
  }

  absl::Mutex mutex;
  std::vector<std::unique_ptr<Followed>> jobs;  // guarded by mutex while clients run
  std::vector<std::thread> clients;
  int submissions = 0;
  const auto client = [&](size_t cloud) {
    auto stub = Connect(address);
    auto job = std::make_unique<Followed>();
    job->id = Submit(*stub, clouds[cloud]);
    if (job->id.empty()) return;  // not accepted: nothing was promised
    job->cloud = cloud;
    Followed* followed = job.get();
    {
      absl::MutexLock lock(&mutex);
      jobs.push_back(std::move(job));
    }
    followed->outcome = Follow(*stub, followed->id, absl::Minutes(5));
  };
  std::uniform_int_distribution<size_t> which(0, clouds.size() - 1);
  std::uniform_int_distribution<int> moment_ms(0, 600);
  for (int cycle = 1; cycle <= cycles; ++cycle) {
    for (int i = 0; i < 2; ++i) {
      clients.emplace_back(client, which(random));
      ++submissions;
    }
    // The fault itself: a kill at a moment nobody chose.
    absl::SleepFor(absl::Milliseconds(moment_ms(random)));
    server.process->Signal(SIGKILL);
    server.process->Wait(10);
    server = StartMembraned(dir, "membraned-" + std::to_string(cycle),
                            {flags[0], flags[1], flags[2], "--listen=" + address});
    ASSERT_EQ(server.address, address) << "restart " << cycle;
    logs.push_back(server.log);
  }
  for (std::thread& t : clients) t.join();

  int succeeded = 0, lost = 0;
  for (const std::unique_ptr<Followed>& job : jobs) {
    const bool same = job->outcome.state == v1::SUCCEEDED &&
                      job->outcome.mesh == expected[job->cloud];
    succeeded += same;
    lost += !same;
    EXPECT_TRUE(same) << "job " << job->id << ": " << v1::JobState_Name(job->outcome.state)
                      << " " << job->outcome.message << " (mesh of "
                      << job->outcome.mesh.size() << " bytes, "
                      << expected[job->cloud].size() << " expected)";
  }
  // What a client was given stays given: each result delivered before some kill is served
  // again, the same, by the last server (an end is on disk before it is sent).
  {
    auto stub = Connect(address);
    int changed = 0;
    for (const std::unique_ptr<Followed>& job : jobs) {
      if (job->outcome.state != v1::SUCCEEDED) continue;
      const Outcome again = Follow(*stub, job->id, absl::Seconds(30));
      const bool same = again.state == v1::SUCCEEDED && again.mesh == job->outcome.mesh;
      changed += !same;
      EXPECT_TRUE(same) << "job " << job->id << " was delivered SUCCEEDED, and is now "
                        << v1::JobState_Name(again.state) << " " << again.message;
    }
    std::cerr << changed << " delivered results changed after the kills\n";
  }
  // Each job accepted once: the servers' logs name no id twice in job_accepted, and every id
  // a client followed is among them.
  std::vector<std::string> accepted;
  int resumed = 0;
  for (const std::string& log_path : logs) {
    const std::string log = ReadText(log_path);
    for (size_t at = log.find("event=job_accepted job="); at != std::string::npos;
         at = log.find("event=job_accepted job=", at + 1)) {
      const size_t start = at + std::strlen("event=job_accepted job=");
      accepted.push_back(log.substr(start, log.find(' ', start) - start));
    }
    for (size_t at = log.find("event=job_resumed"); at != std::string::npos;
         at = log.find("event=job_resumed", at + 1)) {
      ++resumed;
    }
  }
  std::vector<std::string> sorted = accepted;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end())
      << "a job id was accepted twice";
  for (const std::unique_ptr<Followed>& job : jobs) {
    EXPECT_TRUE(std::binary_search(sorted.begin(), sorted.end(), job->id)) << job->id;
  }
  std::cerr << cycles << " kills: " << submissions << " submissions, " << jobs.size()
            << " accepted, " << succeeded << " succeeded with the undisturbed mesh, " << lost
            << " lost; " << resumed << " resumptions\n";
  // Kills come at random moments, but not so early that nothing is accepted.
  EXPECT_GT(jobs.size(), static_cast<size_t>(cycles) / 2);
}

}  // namespace
}  // namespace membrane::testing
