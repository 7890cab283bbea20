// Every call of membrane.v1.Reconstruction against an in-process server over a real channel.
#include <array>
#include <atomic>
#include <cmath>
#include <chrono>
#include <cstring>
#include <ctime>
#include <thread>

#include <gmock/gmock.h>
#include <grpcpp/create_channel.h>
#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "core/io/draco_codec.h"
#include "core/mesh/mesh_check.h"
#include "google/rpc/error_details.pb.h"
#include "google/rpc/status.pb.h"
#include "core/synth/synthesize.h"
#include "proto/crc32c.h"
#include "proto/job_routing.h"
#include "server/job_runner.h"
#include "tests/server/http_get.h"
#include "tests/server/service_fixture.h"
#include "tests/support/plane_edge_cloud.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;

// Waits (at most `seconds`) until GetJob reports a finished job; returns its last state.
v1::Job WaitUntilDone(v1::Reconstruction::Stub& stub, const std::string& id, double seconds) {
  const absl::Time end = absl::Now() + absl::Seconds(seconds);
  v1::Job job;
  while (absl::Now() < end) {
    grpc::ClientContext context;
    v1::GetJobRequest request;
    request.set_job_id(id);
    if (stub.GetJob(&context, request, &job).ok() &&
        (job.state() == v1::SUCCEEDED || job.state() == v1::FAILED ||
         job.state() == v1::CANCELLED)) {
      return job;
    }
    absl::SleepFor(absl::Milliseconds(10));
  }
  return job;
}

// GetJob of `id` now.
v1::Job GetJob(v1::Reconstruction::Stub& stub, const std::string& id) {
  grpc::ClientContext context;
  v1::GetJobRequest request;
  request.set_job_id(id);
  v1::Job job;
  EXPECT_TRUE(stub.GetJob(&context, request, &job).ok()) << id;
  return job;
}

// Waits (at most 60 s) until the job `id` is in `stage`; whether it got there.
bool WaitForStage(v1::Reconstruction::Stub& stub, const std::string& id,
                  const std::string& stage) {
  return WaitFor([&] { return GetJob(stub, id).stage() == stage; }, 60);
}

// CPU seconds this process has used, all threads: the server's worker included, time it
// spends descheduled on a loaded machine not.
double ProcessCpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + ts.tv_nsec * 1e-9;
}

TEST_F(ServiceTest, ReconstructStreamsAcceptedStagesGenerationsAndTheMesh) {
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 5000), {});
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  ASSERT_FALSE(r.events.empty());
  EXPECT_TRUE(r.events.front().has_accepted());
  EXPECT_EQ(r.FinalState(), v1::SUCCEEDED);
  const std::vector<v1::GenerationEvent> generations = r.Generations();
  ASSERT_FALSE(generations.empty());
  for (size_t i = 0; i < generations.size(); ++i) {
    EXPECT_EQ(generations[i].generation(), static_cast<int>(i) + 1);
    EXPECT_EQ(generations[i].planned_generations(), static_cast<int>(generations.size()));
  }
  EXPECT_EQ(generations.back().plate_size(), 1);
  absl::StatusOr<TriangleMesh> mesh = DecodeDracoMesh(r.Mesh());
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_GT(mesh->faces.size(), 100u);
}

// The mesh comes back on the job's quantization grid, and the statistics describe those
// positions: decoded, it checks as they say (before, this cloud's 11-bit mesh had 57 crossing
// face pairs that the statistics did not show).
TEST_F(ServiceTest, QuantizedMeshDecodesFreeOfCrossings) {
  StartServer();
  v1::Parameters p;
  p.set_quantization(11);
  const CallResult r = Reconstruct(DracoCloud("cube-pinholes", 20000), p);
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  absl::StatusOr<TriangleMesh> mesh = DecodeDracoMesh(r.Mesh());
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const MeshReport check = CheckMesh(*mesh);
  EXPECT_TRUE(check.closed && check.manifold && check.oriented);
  EXPECT_EQ(check.self_intersections, 0);
  EXPECT_EQ(check.degenerate_faces, 0);
  std::string json;
  for (const v1::JobEvent& e : r.events) {
    if (e.has_result()) json = e.result().statistics_json();
  }
  EXPECT_NE(json.find("\"quantization\": {\"requested_bits\": 11, \"bits\": 11"),
            std::string::npos)
      << json;
}

// A job's fit and check may use several threads (--job-threads); the mesh is the same.
TEST_F(ServiceTest, JobThreadsGiveTheSameMesh) {
  const std::string upload = DracoCloud("torus", 20000);
  std::vector<std::string> meshes;
  for (int threads : {1, 3}) {
    options_.job_threads = threads;
    StartServer();
    const CallResult r = Reconstruct(upload, {});
    ASSERT_TRUE(r.status.ok()) << r.status.error_message();
    ASSERT_EQ(r.FinalState(), v1::SUCCEEDED);
    meshes.push_back(r.Mesh());
    server_->Shutdown(absl::ZeroDuration());
    server_.reset();
  }
  ASSERT_FALSE(meshes[0].empty());
  EXPECT_TRUE(meshes[0] == meshes[1]) << "the meshes differ";
}

TEST(JobThreadsTest, FixedOrTheCoresSharedAmongTheRunningJobs) {
  server::ServerOptions o;
  o.cores = 8;
  o.job_threads = 3;
  EXPECT_EQ(server::JobThreads(o, 1), 3);
  EXPECT_EQ(server::JobThreads(o, 5), 3);
  o.job_threads = 0;
  EXPECT_EQ(server::JobThreads(o, 1), 8);
  EXPECT_EQ(server::JobThreads(o, 2), 4);
  EXPECT_EQ(server::JobThreads(o, 3), 2);
  EXPECT_EQ(server::JobThreads(o, 9), 1);
  EXPECT_EQ(server::JobThreads(o, 0), 8);
}

// With --job-threads 0 a lone job gets every core; its statistics say how many threads ran.
TEST_F(ServiceTest, LoneJobGetsEveryCoreWithAutomaticThreads) {
  options_.job_threads = 0;
  options_.cores = 3;
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 5000), {});
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  std::string json;
  for (const v1::JobEvent& e : r.events) {
    if (e.has_result()) json = e.result().statistics_json();
  }
  EXPECT_NE(json.find("\"threads\": 3"), std::string::npos) << json;
}

TEST_F(ServiceTest, ResultCarriesTheStatisticsJson) {
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 5000), {});
  ASSERT_TRUE(r.status.ok());
  std::string json;
  for (const v1::JobEvent& e : r.events) {
    if (e.has_result()) json = e.result().statistics_json();
  }
  for (const char* key : {"\"points\": 5000", "\"generations\"", "\"membrane\"", "\"mesh\"",
                          "\"seconds\"", "\"peak_rss_bytes\"", "\"decode\"", "\"encode\""}) {
    EXPECT_NE(json.find(key), std::string::npos) << key;
  }
}

TEST_F(ServiceTest, OutOfRangeParameterIsInvalidArgumentNamingTheFieldAndRange) {
  StartServer();
  v1::Parameters p;
  p.set_initial_plate(200000);
  const CallResult r = Reconstruct(DracoCloud("sphere", 1000), p);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("initial_plate 200000 is out of range [0, 100000]"),
            std::string::npos)
      << r.status.error_message();
  v1::Parameters q;
  q.set_quantization(31);
  EXPECT_NE(Reconstruct(DracoCloud("sphere", 1000), q).status.error_message().find("quantization"),
            std::string::npos);
  v1::Parameters s;
  s.set_schedule("spiral");
  EXPECT_EQ(Reconstruct(DracoCloud("sphere", 1000), s).status.error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
}

// Parameters.target_faces: the job's mesh is decimated, its statistics say how; below 4 the
// job is refused before it is accepted.
TEST_F(ServiceTest, TargetFacesDecimatesTheResultAndIsValidated) {
  StartServer();
  v1::Parameters p;
  p.set_target_faces(300);
  const CallResult r = Reconstruct(DracoCloud("sphere", 5000), p);
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  std::string json;
  for (const v1::JobEvent& e : r.events) {
    if (e.has_result()) json = e.result().statistics_json();
  }
  EXPECT_NE(json.find("\"decimation\": {\"target_faces\": 300,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"decimate\": "), std::string::npos) << json;
  v1::Parameters small;
  small.set_target_faces(3);
  const CallResult refused = Reconstruct(DracoCloud("sphere", 1000), small);
  EXPECT_EQ(refused.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(refused.status.error_message().find("target_faces 3 is out of range [4, "),
            std::string::npos)
      << refused.status.error_message();
}

TEST_F(ServiceTest, OriginOfOtherThanThreeFiniteValuesIsInvalidArgument) {
  StartServer();
  v1::Parameters two;
  two.add_origin(512346);
  two.add_origin(4123457);
  const CallResult r = Reconstruct(DracoCloud("sphere", 1000), two);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(r.status.error_message().find("origin has 2 values"), std::string::npos)
      << r.status.error_message();
  v1::Parameters nan;
  for (double v : {1.0, std::nan(""), 2.0}) nan.add_origin(v);
  const CallResult n = Reconstruct(DracoCloud("sphere", 1000), nan);
  EXPECT_EQ(n.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(n.status.error_message().find("origin value nan"), std::string::npos)
      << n.status.error_message();
}

// The server computes in the uploaded positions and keeps the client's origin beside them.
TEST_F(ServiceTest, OriginIsKeptInTheStatisticsAndTheJob) {
  StartServer();
  v1::Parameters p;
  for (double v : {512346.0, 4123457.0, 0.0}) p.add_origin(v);
  const CallResult r = Reconstruct(DracoCloud("sphere", 3000), p);
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  std::string json, id;
  for (const v1::JobEvent& e : r.events) {
    if (e.has_result()) json = e.result().statistics_json();
    if (e.has_accepted()) id = e.accepted().job_id();
  }
  EXPECT_NE(json.find("\"origin\": [512346, 4123457, 0]"), std::string::npos) << json;
  const v1::Job job = WaitUntilDone(*stub_, id, 10);
  ASSERT_EQ(job.parameters().origin_size(), 3);
  EXPECT_EQ(job.parameters().origin(1), 4123457.0);
}

// "[a, b, c]" as the statistics JSON writes an integer array.
std::string JsonDims(const std::array<int, 3>& dims) {
  return absl::StrCat("[", dims[0], ", ", dims[1], ", ", dims[2], "]");
}

// The statistics JSON of a call's result, or empty.
std::string ResultStatistics(const CallResult& r) {
  for (const v1::JobEvent& e : r.events) {
    if (e.has_result()) return e.result().statistics_json();
  }
  return "";
}

v1::GridBox GridBoxOf(const Box3d& box) {
  v1::GridBox b;
  b.set_min_x(box.min[0]);
  b.set_min_y(box.min[1]);
  b.set_min_z(box.min[2]);
  b.set_max_x(box.max[0]);
  b.set_max_y(box.max[1]);
  b.set_max_z(box.max[2]);
  return b;
}

// An 11-bit upload whose own box is a plane shorter or longer than its cloud's: with the
// cloud's box in Parameters.grid_box, the job's grid is the cloud's; without, the upload's own.
TEST_F(ServiceTest, GridBoxGivesAQuantizedUploadItsCloudsGrid) {
  StartServer();
  const PlaneEdgeCloud c = MakePlaneEdgeCloud(10000);
  DracoOptions draco;
  draco.position_quantization_bits = c.bits;
  absl::StatusOr<DracoEncoding> upload = EncodeDracoPointCloud(c.cloud, draco);
  ASSERT_TRUE(upload.ok()) << upload.status();
  v1::Parameters p;
  p.set_voxel_size(c.voxel_size);
  const CallResult own = Reconstruct(upload->bytes, p);
  ASSERT_TRUE(own.status.ok()) << own.status.error_message();
  EXPECT_THAT(ResultStatistics(own),
              HasSubstr("\"data_grid\": " + JsonDims(c.quantized_data_dims)));
  *p.mutable_grid_box() = GridBoxOf(c.box);
  const CallResult boxed = Reconstruct(upload->bytes, p);
  ASSERT_TRUE(boxed.status.ok()) << boxed.status.error_message();
  EXPECT_THAT(ResultStatistics(boxed), HasSubstr("\"data_grid\": " + JsonDims(c.data_dims)));
  EXPECT_THAT(ResultStatistics(boxed), HasSubstr("\"genus\": [0]"));
  const v1::Job job = WaitUntilDone(*stub_, boxed.JobId(), 10);
  EXPECT_EQ(job.parameters().grid_box().max_z(), c.box.max[2]);
}

// A box that is not finite or is inverted is refused before the job is accepted; one that does
// not hold the decoded points within 1/8 voxel fails the job; each names grid_box.
TEST_F(ServiceTest, BadGridBoxIsInvalidArgumentNamingTheField) {
  StartServer();
  const std::string upload = DracoCloud("sphere", 2000);
  const Box3d sphere = {{-1.01, -1.01, -1.01}, {1.01, 1.01, 1.01}};
  v1::Parameters p;
  p.set_voxel_size(0.1);
  *p.mutable_grid_box() = GridBoxOf(sphere);
  p.mutable_grid_box()->set_max_y(std::nan(""));
  const CallResult nan = Reconstruct(upload, p);
  EXPECT_EQ(nan.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(nan.status.error_message(), HasSubstr("grid_box y: max nan is not finite"));
  EXPECT_TRUE(nan.events.empty());

  *p.mutable_grid_box() = GridBoxOf(sphere);
  p.mutable_grid_box()->set_min_x(2);
  const CallResult inverted = Reconstruct(upload, p);
  EXPECT_EQ(inverted.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(inverted.status.error_message(), HasSubstr("grid_box x: min 2 is not below max"));

  *p.mutable_grid_box() = GridBoxOf(sphere);
  p.mutable_grid_box()->set_max_z(0.5);  // the sphere's top half outside
  const CallResult outside = Reconstruct(upload, p);
  EXPECT_EQ(outside.FinalState(), v1::FAILED);
  EXPECT_EQ(outside.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(outside.status.error_message(),
              HasSubstr("grid_box does not contain the points: their z max"));
}

TEST_F(ServiceTest, GetJobAndListJobsShowAFinishedJobAndItsResultIsFetchableAgain) {
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 3000), {});
  ASSERT_TRUE(r.status.ok());
  const std::string id = r.JobId();
  grpc::ClientContext get_context;
  v1::GetJobRequest get;
  get.set_job_id(id);
  v1::Job job;
  ASSERT_TRUE(stub_->GetJob(&get_context, get, &job).ok());
  EXPECT_EQ(job.state(), v1::SUCCEEDED);
  EXPECT_GT(job.mesh_bytes(), 0u);
  grpc::ClientContext list_context;
  v1::ListJobsResponse list;
  ASSERT_TRUE(stub_->ListJobs(&list_context, {}, &list).ok());
  ASSERT_EQ(list.jobs_size(), 1);
  EXPECT_EQ(list.jobs(0).id(), id);
  // WatchJob on a finished job: the snapshot at once, then the whole result again.
  const CallResult again = Watch(id);
  ASSERT_TRUE(again.status.ok());
  EXPECT_TRUE(again.events.front().has_snapshot());
  EXPECT_EQ(again.Mesh(), r.Mesh());
  EXPECT_EQ(again.Generations().size(), r.Generations().size());
}

TEST_F(ServiceTest, UnknownJobIsNotFound) {
  StartServer();
  grpc::ClientContext context;
  v1::GetJobRequest request;
  request.set_job_id("nope");
  v1::Job job;
  EXPECT_EQ(stub_->GetJob(&context, request, &job).error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(Watch("nope").status.error_code(), grpc::StatusCode::NOT_FOUND);
}

// Whatever a client sends comes back bounded and escaped: a status carrying a 3 MiB schedule
// or a 1 MiB job id would not fit gRPC's 8 KB of trailers, and the client would see
// RESOURCE_EXHAUSTED instead of what is wrong.
TEST_F(ServiceTest, HugeOrHostileStringsComeBackBoundedInTheRightStatus) {
  StartServer();
  v1::Parameters p;
  p.set_schedule("\x1b[2J" + std::string(3 << 20, 'h'));
  const CallResult r = Reconstruct(DracoCloud("sphere", 1000), p);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_LT(r.status.error_message().size(), 512u);
  EXPECT_NE(r.status.error_message().find("schedule '\\x1b[2Jhhh"), std::string::npos)
      << r.status.error_message();
  EXPECT_NE(r.status.error_message().find("...(3145732 bytes)' is not one of: halving, linear"),
            std::string::npos)
      << r.status.error_message();
  v1::Parameters q;
  q.set_surface(std::string(1 << 20, '\0'));
  const CallResult s = Reconstruct(DracoCloud("sphere", 1000), q);
  EXPECT_EQ(s.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(s.status.error_message().find("surface '\\x00\\x00"), std::string::npos);

  const std::string id = std::string(1 << 20, 'a') + "\n";
  grpc::ClientContext context;
  v1::GetJobRequest request;
  request.set_job_id(id);
  v1::Job job;
  const grpc::Status get = stub_->GetJob(&context, request, &job);
  EXPECT_EQ(get.error_code(), grpc::StatusCode::NOT_FOUND) << get.error_message().size();
  EXPECT_LT(get.error_message().size(), 512u);
  const CallResult watch = Watch("membraned-9." + id);
  EXPECT_EQ(watch.status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_NE(watch.status.error_message().find("it belongs to replica 'membraned-9'"),
            std::string::npos)
      << watch.status.error_message();
}

// A named replica's job ids carry its name; a call about another replica's job, which a
// balancer routed wrongly, is NOT_FOUND with both names and the header to route on.
TEST_F(ServiceTest, NamedReplicaPrefixesItsJobIdsAndNamesTheOwnerOfOthers) {
  options_.replica = "membraned-1";
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 2000), {});
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  EXPECT_EQ(ReplicaOfJobId(r.JobId()), "membraned-1") << r.JobId();
  EXPECT_TRUE(Watch(r.JobId()).status.ok());
  {
    grpc::ClientContext context;
    context.AddMetadata(kReplicaHeader, "membraned-0");
    v1::ListJobsResponse list;
    const grpc::Status s = stub_->ListJobs(&context, {}, &list);
    EXPECT_EQ(s.error_code(), grpc::StatusCode::NOT_FOUND);
    EXPECT_EQ(s.error_message(),
              "the jobs of replica 'membraned-0' were asked for, and this is 'membraned-1' (the "
              "balancer must route on the membrane-replica header)");
  }
  {
    grpc::ClientContext context;
    context.AddMetadata(kReplicaHeader, "membraned-1");
    v1::ListJobsResponse list;
    ASSERT_TRUE(stub_->ListJobs(&context, {}, &list).ok());
    EXPECT_EQ(list.jobs_size(), 1);
  }
  const CallResult other = Watch("membraned-0.0123456789abcdef");
  EXPECT_EQ(other.status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(other.status.error_message(),
            "no job 'membraned-0.0123456789abcdef' here: it belongs to replica 'membraned-0', and "
            "this is 'membraned-1' (the balancer must route on the membrane-replica header)");
}

// With --store-dir, a result outlives the server: a new server on the same directory serves
// the job again, mesh and all.
TEST_F(ServiceTest, StoredResultsOutliveTheServer) {
  ScratchDir dir;
  options_.store_dir = dir.File("jobs");
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 3000), {});
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  server_->Shutdown(absl::ZeroDuration());
  server_.reset();
  StartServer();
  const CallResult again = Watch(r.JobId());
  ASSERT_TRUE(again.status.ok()) << again.status.error_message();
  EXPECT_EQ(again.FinalState(), v1::SUCCEEDED);
  EXPECT_TRUE(again.Mesh() == r.Mesh()) << "the stored mesh differs";
  EXPECT_EQ(again.Generations().size(), r.Generations().size());
}

TEST_F(ServiceTest, ResultsExpireAfterTheirTimeToLive) {
  options_.result_ttl_seconds = 60;
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 2000), {});
  ASSERT_TRUE(r.status.ok());
  clock_.Advance(absl::Seconds(30));
  EXPECT_TRUE(Watch(r.JobId()).status.ok()) << "expired within its time to live";
  clock_.Advance(absl::Seconds(31));
  EXPECT_EQ(Watch(r.JobId()).status.error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST_F(ServiceTest, CancelJobStopsARunningJobWithin100MsAndFreesTheWorker) {
  StartServer();
  // The one test whose job computes when cancelled: the latency under test is a compute
  // stage's (the shrink's), and it is CPU time, so a job of several CPU seconds (a fine grid)
  // is still in its shrink when the cancel comes, whatever the load.
  v1::Parameters fine_grid;
  fine_grid.set_voxel_size(0.008);
  const std::string id = StartJobInBackground(DracoCloud("sphere", 30000), fine_grid);
  ASSERT_FALSE(id.empty());
  ASSERT_TRUE(WaitForStage(*stub_, id, "shrink"));
  grpc::ClientContext context;
  v1::CancelJobRequest request;
  request.set_job_id(id);
  v1::Job job;
  // The latency is CPU time (the job runs one thread, fixture's --job-threads 1), not wall
  // time: a worker that a loaded machine does not schedule does no work either.
  const double asked = ProcessCpuSeconds();
  ASSERT_TRUE(stub_->CancelJob(&context, request, &job).ok());
  const v1::Job done = WaitUntilDone(*stub_, id, 30);
  EXPECT_LT(ProcessCpuSeconds() - asked, 0.1 + 0.05) << "stage when cancelled: " << job.stage();
  EXPECT_EQ(done.state(), v1::CANCELLED);
  EXPECT_NE(done.error().message().find("cancelled by the client"), std::string::npos);
  // The worker is free: a small job runs at once.
  const CallResult next = Reconstruct(DracoCloud("sphere", 2000), {}, {}, 20);
  EXPECT_TRUE(next.status.ok()) << next.status.error_message();
}

// --max-job-seconds: a job running past it ends FAILED DEADLINE_EXCEEDED, and the worker is
// free again.
TEST_F(ServiceTest, JobRunningPastMaxJobSecondsFailsDeadlineExceeded) {
  options_.max_job_seconds = 60;
  HoldDecodes();
  StartServer();
  const std::string id = StartHeldJob();
  ASSERT_FALSE(id.empty());
  clock_.Advance(absl::Seconds(61));
  const v1::Job done = WaitUntilDone(*stub_, id, 30);
  EXPECT_EQ(done.state(), v1::FAILED);
  EXPECT_EQ(done.error().code(), static_cast<int>(grpc::StatusCode::DEADLINE_EXCEEDED));
  EXPECT_NE(done.error().message().find("--max-job-seconds of 60 s"), std::string::npos)
      << done.error().message();
  gate_->Open();  // for the next job
  const CallResult next = Reconstruct(DracoCloud("sphere", 2000), {}, {}, 20);
  EXPECT_TRUE(next.status.ok()) << next.status.error_message();
}

// What the estimates say cannot finish within --max-job-seconds is refused before it runs:
// Draco's 30-bit encoding at the upload's header, a fine grid before it is allocated.
TEST_F(ServiceTest, JobsOverMaxJobSecondsByTheEstimatesAreRefusedBeforeTheyRun) {
  options_.max_job_seconds = 5;
  options_.job_threads = 1;  // the grid's floor is divided by the job's threads
  StartServer();
  v1::Parameters fine_bits;
  fine_bits.set_quantization(30);
  const CallResult bits = Reconstruct(DracoCloud("sphere", 3000), fine_bits);
  EXPECT_EQ(bits.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_TRUE(bits.JobId().empty());
  EXPECT_NE(bits.status.error_message().find("quantization 30 takes at least 26.8 s to encode"),
            std::string::npos)
      << bits.status.error_message();
  v1::Parameters fine_grid;
  fine_grid.set_voxel_size(0.003);  // about 300M voxels: at least 6 s on one thread
  const CallResult grid = Reconstruct(DracoCloud("sphere", 3000), fine_grid);
  EXPECT_EQ(grid.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_EQ(grid.FinalState(), v1::FAILED);
  EXPECT_NE(grid.status.error_message().find("over the server's --max-job-seconds of 5 s"),
            std::string::npos)
      << grid.status.error_message();
  for (const v1::JobEvent& e : grid.events) {
    EXPECT_FALSE(e.has_stage() && e.stage().stage() == "shrink") << "the job ran";
  }
}

TEST_F(ServiceTest, ExpiredDeadlineCancelsTheJob) {
  HoldDecodes();
  StartServer();
  const CallResult r = Reconstruct(DracoCloud("sphere", 2000), {}, {}, 1.5);
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::DEADLINE_EXCEEDED);
  const std::string id = r.JobId();
  ASSERT_FALSE(id.empty());
  // Generous: ctest runs this beside heavy tests. The 100 ms bound is asserted by the
  // CancelJob test above, on an idle worker.
  const v1::Job done = WaitUntilDone(*stub_, id, 5);
  EXPECT_EQ(done.state(), v1::CANCELLED);
  EXPECT_NE(done.error().message().find("deadline"), std::string::npos);
}

TEST_F(ServiceTest, DroppedCallCancelsTheJobWhenConfigured) {
  options_.on_disconnect = server::DisconnectPolicy::kCancel;
  HoldDecodes();
  StartServer();
  const std::string id = StartHeldJob();
  ASSERT_FALSE(id.empty());
  background_contexts_.back()->TryCancel();
  const v1::Job done = WaitUntilDone(*stub_, id, 3);
  EXPECT_EQ(done.state(), v1::CANCELLED);
  EXPECT_NE(done.error().message().find("disconnected"), std::string::npos)
      << done.error().message();
}

TEST_F(ServiceTest, FullQueueIsResourceExhaustedWithARetryDelay) {
  HoldDecodes();
  StartServer();  // 1 worker, queue of 1
  ASSERT_FALSE(StartHeldJob().empty());                                       // running
  ASSERT_FALSE(StartJobInBackground(DracoCloud("sphere", 2000), {}).empty());  // queued
  const CallResult r = Reconstruct(DracoCloud("sphere", 1000), {}, {}, 10);
  ASSERT_EQ(r.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  google::rpc::Status details;
  ASSERT_TRUE(details.ParseFromString(r.status.error_details()));
  ASSERT_EQ(details.details_size(), 1);
  google::rpc::RetryInfo retry;
  ASSERT_TRUE(details.details(0).UnpackTo(&retry));
  EXPECT_EQ(retry.retry_delay().seconds() * 1000 + retry.retry_delay().nanos() / 1000000, 500);
}

// --metrics-listen serves Prometheus text: jobs by outcome (whoever ended them), refused
// calls by code, stage seconds, and the queue and workers as they are at the scrape.
TEST_F(ServiceTest, MetricsCountJobsRefusalsAndStages) {
  options_.metrics_listen = "127.0.0.1:0";
  HoldDecodes();
  StartServer();  // 1 worker, queue of 1
  ASSERT_GT(server_->metrics_port(), 0);
  const int port = server_->metrics_port();
  std::string m = HttpGet(port, "/metrics");
  EXPECT_EQ(MetricValue(m, "membrane_jobs_accepted_total"), 0) << m;
  EXPECT_EQ(MetricValue(m, "membrane_job_seconds_count{state=\"FAILED\"}"), 0) << m;

  gate_->Open();  // for the job that succeeds
  ASSERT_TRUE(Reconstruct(DracoCloud("sphere", 2000), {}).status.ok());
  UploadTweaks corrupt;
  corrupt.wrong_checksum = true;
  EXPECT_EQ(Reconstruct(DracoCloud("sphere", 2000), {}, corrupt).status.error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
  const std::string running = StartHeldJob();
  const std::string queued = StartJobInBackground(DracoCloud("sphere", 2000), {});
  ASSERT_FALSE(running.empty());
  ASSERT_FALSE(queued.empty());
  m = HttpGet(port, "/metrics");
  EXPECT_EQ(MetricValue(m, "membrane_jobs_queued"), 1) << m;
  EXPECT_EQ(MetricValue(m, "membrane_jobs_running"), 1) << m;
  EXPECT_EQ(MetricValue(m, "membrane_workers"), 1) << m;
  EXPECT_EQ(MetricValue(m, "membrane_queue_limit"), 1) << m;
  // The queued job ends without a worker: cancelled where it waits.
  for (const std::string& id : {queued, running}) {
    grpc::ClientContext context;
    v1::CancelJobRequest request;
    request.set_job_id(id);
    v1::Job job;
    ASSERT_TRUE(stub_->CancelJob(&context, request, &job).ok());
    EXPECT_EQ(WaitUntilDone(*stub_, id, 5).state(), v1::CANCELLED);
  }
  m = HttpGet(port, "/metrics");
  EXPECT_EQ(MetricValue(m, "membrane_jobs_accepted_total"), 3) << m;
  EXPECT_EQ(MetricValue(m, "membrane_reconstruct_refused_total{code=\"INVALID_ARGUMENT\"}"), 1)
      << m;
  EXPECT_EQ(MetricValue(m, "membrane_jobs_finished_total{code=\"OK\",state=\"SUCCEEDED\"}"), 1)
      << m;
  EXPECT_EQ(
      MetricValue(m, "membrane_jobs_finished_total{code=\"CANCELLED\",state=\"CANCELLED\"}"), 2)
      << m;
  EXPECT_EQ(MetricValue(m, "membrane_job_seconds_count{state=\"CANCELLED\"}"), 2) << m;
  EXPECT_EQ(MetricValue(m, "membrane_stage_seconds_count{stage=\"encode\"}"), 1) << m;
  // The cancelled running job was cancelled in its decode.
  EXPECT_EQ(MetricValue(m, "membrane_stage_seconds_count{stage=\"decode\"}"), 1) << m;
  EXPECT_GT(MetricValue(m, "membrane_mesh_bytes_total"), 0) << m;
  // The worker leaves its cancelled job a moment after the job says CANCELLED.
  for (int i = 0; i < 50 && MetricValue(m, "membrane_jobs_running") != 0; ++i) {
    absl::SleepFor(absl::Milliseconds(100));
    m = HttpGet(port, "/metrics");
  }
  EXPECT_EQ(MetricValue(m, "membrane_jobs_queued"), 0) << m;
  EXPECT_EQ(MetricValue(m, "membrane_jobs_running"), 0) << m;
}

// The metrics endpoint serves scrapes beside requests that never arrive whole: twice as many
// of those as it has threads do not block a scrape, and each is ended by its request timeout.
TEST_F(ServiceTest, HalfSentMetricsRequestsDoNotBlockScrapes) {
  options_.metrics_listen = "127.0.0.1:0";
  StartServer();
  const int port = server_->metrics_port();
  std::vector<int> stalled;
  for (int i = 0; i < 8; ++i) {
    stalled.push_back(OpenHalfSentRequest(port));
    ASSERT_GE(stalled.back(), 0);
  }
  // HttpGet gives up after 5 s without an answer.
  for (int scrape = 0; scrape < 3; ++scrape) {
    EXPECT_EQ(MetricValue(HttpGet(port, "/metrics"), "membrane_workers"), 1) << scrape;
  }
  for (const int fd : stalled) EXPECT_TRUE(ServerEndsConnection(fd, 20));
}

// An address that cannot be bound fails the start, naming the flag.
TEST_F(ServiceTest, UnboundMetricsAddressFailsTheStart) {
  options_.metrics_listen = "256.0.0.1:1";
  server::MembraneServer server(options_);
  const absl::StatusOr<int> port = server.Start("127.0.0.1:0");
  ASSERT_FALSE(port.ok());
  EXPECT_EQ(port.status().code(), absl::StatusCode::kUnavailable);
  EXPECT_NE(port.status().message().find("--metrics-listen"), std::string::npos) << port.status();
}

// Uploads are held from their header until their job is decoded, within
// --upload-memory-bytes: a full queue of large uploads cannot take the machine's memory.
TEST_F(ServiceTest, UploadsHeldOverTheirMemoryAreRefusedUntilOneIsReleased) {
  const std::string cloud = DracoCloud("sphere", 2000);  // StartHeldJob's
  options_.upload_memory_bytes = 2 * static_cast<int64_t>(cloud.size());  // two at a time
  HoldDecodes();
  StartServer();  // 1 worker, queue of 1
  const std::string running = StartHeldJob();  // holds its upload: it is not decoded yet
  ASSERT_FALSE(running.empty());
  const std::string queued = StartJobInBackground(cloud, {});  // holds the rest
  ASSERT_FALSE(queued.empty());
  const CallResult busy = Reconstruct(cloud, {}, {}, 10);
  ASSERT_EQ(busy.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(busy.status.error_message().find("--upload-memory-bytes"), std::string::npos)
      << busy.status.error_message();
  google::rpc::Status details;
  ASSERT_TRUE(details.ParseFromString(busy.status.error_details()));
  EXPECT_EQ(details.details_size(), 1);  // RetryInfo: it fits once another is released
  // Cancelling the queued job gives its upload back: the same upload is taken now.
  grpc::ClientContext context;
  v1::CancelJobRequest request;
  request.set_job_id(queued);
  v1::Job job;
  ASSERT_TRUE(stub_->CancelJob(&context, request, &job).ok());
  ASSERT_FALSE(StartJobInBackground(cloud, {}).empty());  // queued behind the running job
  // Once decoded, the running job's upload is given back: with the next job held at the gate
  // in its turn, holding its own, one more upload fits.
  gate_->Open();
  ASSERT_TRUE(gate_->WaitForDecodes(2));
  EXPECT_FALSE(StartJobInBackground(cloud, {}).empty());
}

TEST_F(ServiceTest, UploadOverTheWholeUploadMemoryIsRefusedWithoutRetry) {
  const std::string cloud = DracoCloud("sphere", 2000);
  options_.upload_memory_bytes = static_cast<int64_t>(cloud.size()) - 1;
  StartServer();
  const CallResult r = Reconstruct(cloud, {}, {}, 10);
  ASSERT_EQ(r.status.error_code(), grpc::StatusCode::RESOURCE_EXHAUSTED);
  EXPECT_NE(r.status.error_message().find("over the server's memory for uploads"),
            std::string::npos)
      << r.status.error_message();
  EXPECT_TRUE(r.status.error_details().empty());  // no RetryInfo: it never fits
}

// A cloud scattered over more than a voxel succeeds, and the voxelize stage's FINISHED event
// carries the warning the statistics hold, for the client to print; a clean cloud's carries none.
TEST_F(ServiceTest, ScatteredCloudsWarningComesWithTheVoxelizeStage) {
  StartServer();
  SynthOptions synth{.shape = "sphere", .points = 20000, .noise = 0.05, .seed = 3};
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(synth);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoPointCloud(*cloud, DracoOptions{});
  ASSERT_TRUE(encoded.ok());
  v1::Parameters cuberille;
  cuberille.set_surface("cuberille");
  for (const auto& [upload, warned] :
       {std::pair{encoded->bytes, true}, std::pair{DracoCloud("sphere", 20000), false}}) {
    const CallResult r = Reconstruct(upload, cuberille);
    ASSERT_TRUE(r.status.ok()) << r.status.error_message();
    std::vector<std::string> warnings;
    std::string statistics;
    for (const v1::JobEvent& e : r.events) {
      if (e.has_stage() && e.stage().phase() == v1::StageEvent::FINISHED) {
        for (const std::string& w : e.stage().warnings()) {
          EXPECT_EQ(e.stage().stage(), "voxelize");
          warnings.push_back(w);
        }
      }
      if (e.has_result()) statistics = e.result().statistics_json();
    }
    ASSERT_EQ(warnings.size(), warned ? 1u : 0u);
    if (warned) {
      EXPECT_NE(warnings[0].find("scatter"), std::string::npos) << warnings[0];
      EXPECT_NE(statistics.find(warnings[0]), std::string::npos) << statistics;
    } else {
      EXPECT_NE(statistics.find("\"warnings\": []"), std::string::npos) << statistics;
    }
  }
}

// Each open call holds a thread of the sync server: past --max-calls, calls are refused with
// RESOURCE_EXHAUSTED instead of threads piling up, and the server serves again once they end.
TEST_F(ServiceTest, CallsPastTheLimitAreResourceExhausted) {
  options_.max_calls = 6;
  HoldDecodes();
  StartServer();
  const std::string id = StartHeldJob();
  ASSERT_FALSE(id.empty());
  std::vector<std::thread> watchers;
  std::vector<grpc::ClientContext> contexts(12);
  std::atomic<int> refused{0};
  for (grpc::ClientContext& context : contexts) {
    watchers.emplace_back([&, this] {
      v1::WatchJobRequest request;
      request.set_job_id(id);
      auto reader = stub_->WatchJob(&context, request);
      v1::JobEvent event;
      while (reader->Read(&event)) {
      }
      const grpc::Status s = reader->Finish();
      // The client tells this refusal (busy: retry) from our limits by gRPC's own message.
      if (s.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED &&
          s.error_message() == "Server Threadpool Exhausted")
        ++refused;
    });
  }
  EXPECT_TRUE(WaitFor([&] { return refused.load() > 0; }, 30));
  // Health is a callback service, outside the sync server's threads: a liveness probe is still
  // answered, so a busy pod is not restarted (and its running jobs ended) for being busy.
  EXPECT_EQ(Health(), "SERVING");
  for (grpc::ClientContext& context : contexts) context.TryCancel();
  for (std::thread& t : watchers) t.join();
  // The handlers see their calls cancelled within their next wait for events.
  grpc::Status cancelled;
  for (int attempt = 0; attempt < 50; ++attempt) {
    grpc::ClientContext context;
    v1::CancelJobRequest request;
    request.set_job_id(id);
    v1::Job job;
    cancelled = stub_->CancelJob(&context, request, &job);
    if (cancelled.ok()) break;
    absl::SleepFor(absl::Milliseconds(100));
  }
  EXPECT_TRUE(cancelled.ok()) << cancelled.error_message();
  EXPECT_EQ(Health(), "SERVING");
}

// A client that stops sending halfway (alive enough to answer keepalive pings) does not hold
// its call and its upload's memory for ever: the call is cancelled once nothing arrived for
// --stall-seconds, and its memory serves the next upload.
TEST_F(ServiceTest, StalledUploadIsCancelledAndItsMemoryGivenBack) {
  const std::string cloud = DracoCloud("sphere", 20000);
  options_.stall_seconds = 60;
  options_.upload_memory_bytes = static_cast<int64_t>(cloud.size());
  options_.metrics_listen = "127.0.0.1:0";
  StartServer();
  UploadTweaks stall;
  stall.send_bytes = cloud.size() / 2;
  stall.stall = true;
  ::testing::internal::CaptureStderr();
  const CallResult stalled = Reconstruct(cloud, {}, stall, 30);
  // Cancelled by the server: else the call would have run into its deadline.
  EXPECT_EQ(stalled.status.error_code(), grpc::StatusCode::CANCELLED)
      << stalled.status.error_message();
  EXPECT_TRUE(stalled.JobId().empty());
  // The client hears of the cancel before the handler has returned the buffer's memory.
  EXPECT_TRUE(WaitFor(
      [&] {
        return MetricValue(HttpGet(server_->metrics_port(), "/metrics"),
                           "membrane_upload_held_bytes") == 0;
      },
      30));
  const CallResult next = Reconstruct(cloud, {}, {}, 30);
  EXPECT_TRUE(next.status.ok()) << next.status.error_message();
  // Logged (before the memory the next upload needed came back) with the caller's address,
  // which the cancelled call's context no longer knows.
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(log.find("event=upload_rejected peer=ipv4:127.0.0.1:"), std::string::npos) << log;
}

// Progress is bytes: a client that keeps its upload open with empty chunks, or with a few
// bytes now and then (under kStallProgressBytes per --stall-seconds), is cut as one that
// sends nothing; each cut is counted.
TEST_F(ServiceTest, EmptyChunksOrATrickleDoNotKeepAnUploadAlive) {
  const std::string cloud = DracoCloud("sphere", 20000);
  options_.stall_seconds = 60;
  options_.metrics_listen = "127.0.0.1:0";
  StartServer();
  for (const size_t bytes : {size_t{0}, size_t{100}}) {
    UploadTweaks trickle;
    trickle.announced_bytes = 1 << 20;
    trickle.send_bytes = 0;
    trickle.stall = true;
    trickle.stall_step = absl::Seconds(15);  // a chunk every quarter of the limit
    trickle.trickle = true;
    trickle.trickle_bytes = bytes;
    const CallResult r = Reconstruct(cloud, {}, trickle, 30);
    // Had a chunk counted as progress, the call would have run into its deadline.
    EXPECT_EQ(r.status.error_code(), grpc::StatusCode::CANCELLED)
        << bytes << " bytes a chunk: " << r.status.error_message();
  }
  EXPECT_EQ(MetricValue(HttpGet(server_->metrics_port(), "/metrics"),
                        "membrane_calls_stalled_total"),
            2);
}

// A client that reads none of the events (flow control then holds the server's writes) does not
// hold its call for ever: the write is cancelled after --stall-seconds, and the job, which the
// call no longer follows, still ends and keeps its result.
TEST_F(ServiceTest, ClientThatReadsNothingIsCutOffAndTheJobGoesOn) {
  options_.stall_seconds = 60;
  options_.metrics_listen = "127.0.0.1:0";
  StartServer();
  // A small receive window and no window growth: the mesh cannot all be in flight unread.
  grpc::ChannelArguments args;
  args.SetInt(GRPC_ARG_HTTP2_BDP_PROBE, 0);
  args.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, 8192);
  auto stub = v1::Reconstruction::NewStub(
      grpc::CreateCustomChannel(address_, grpc::InsecureChannelCredentials(), args));
  const std::string upload = DracoCloud("sphere", 100000);
  grpc::ClientContext context;
  auto stream = stub->Reconstruct(&context);
  v1::ReconstructRequest header;
  header.mutable_header()->set_upload_bytes(upload.size());
  header.mutable_header()->set_upload_crc32c(Crc32c(upload));
  ASSERT_TRUE(stream->Write(header));
  for (size_t at = 0; at < upload.size(); at += 1 << 20) {
    v1::ReconstructRequest chunk;
    chunk.set_chunk(upload.substr(at, 1 << 20));
    ASSERT_TRUE(stream->Write(chunk));
  }
  stream->WritesDone();
  // Read nothing until the only job has ended (watched through the fixture's own channel).
  v1::Job job;
  WaitFor(
      [&] {
        grpc::ClientContext list_context;
        v1::ListJobsResponse list;
        if (stub_->ListJobs(&list_context, {}, &list).ok() && list.jobs_size() == 1)
          job = list.jobs(0);
        return job.state() == v1::SUCCEEDED || job.state() == v1::FAILED;
      },
      60);
  ASSERT_EQ(job.state(), v1::SUCCEEDED);
  ::testing::internal::CaptureStderr();
  // Then past the stall limit with the mesh unread, until the server has cut the call.
  WhileTimeFlies(absl::Seconds(20), nullptr, [&] {
    EXPECT_TRUE(WaitFor(
        [&] {
          return MetricValue(HttpGet(server_->metrics_port(), "/metrics"),
                             "membrane_calls_stalled_total") == 1;
        },
        30));
  });
  v1::JobEvent event;
  while (stream->Read(&event)) {
  }
  // Had the server waited for us, every event would have come and the call ended OK.
  EXPECT_EQ(stream->Finish().error_code(), grpc::StatusCode::CANCELLED);
  const CallResult watched = Watch(job.id());
  EXPECT_TRUE(watched.status.ok()) << watched.status.error_message();
  EXPECT_FALSE(watched.Mesh().empty());
  // Logged with the caller's address, which the cancelled call's context no longer knows; by
  // the time the server has stopped, which waits for every handler.
  server_->Shutdown(absl::ZeroDuration());
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(log.find("event=call_dropped job=" + job.id() + " peer=ipv4:127.0.0.1:"),
            std::string::npos)
      << log;
}

TEST_F(ServiceTest, QueuedJobReportsItsPosition) {
  HoldDecodes();
  StartServer();
  // On the worker, held in its decode: else the second job would be second in the queue.
  const std::string running = StartHeldJob();
  ASSERT_FALSE(running.empty());
  const std::string queued = StartJobInBackground(DracoCloud("sphere", 2000), {});
  grpc::ClientContext context;
  v1::GetJobRequest request;
  request.set_job_id(queued);
  v1::Job job;
  ASSERT_TRUE(stub_->GetJob(&context, request, &job).ok());
  EXPECT_EQ(job.state(), v1::QUEUED);
  EXPECT_EQ(job.queue_position(), 1);
}

TEST_F(ServiceTest, WatchJobReattachesToARunningJobAndGetsItsMesh) {
  StartServer();
  const std::string id = StartJobInBackground(DracoCloud("sphere", 30000), {});
  ASSERT_FALSE(id.empty());
  const CallResult watched = Watch(id);
  ASSERT_TRUE(watched.status.ok()) << watched.status.error_message();
  EXPECT_TRUE(watched.events.front().has_snapshot());
  EXPECT_EQ(watched.FinalState(), v1::SUCCEEDED);
  EXPECT_TRUE(DecodeDracoMesh(watched.Mesh()).ok());
}

TEST_F(ServiceTest, ShutdownMakesHealthNotServingAndRefusesNewJobs) {
  // A held job keeps the shutdown in its grace period, with the gRPC server still up, until
  // the new job has its answer: the service itself refuses it. (With nothing running the
  // server can be gone by the time the call arrives, and gRPC cancels it instead.)
  HoldDecodes();
  StartServer();
  EXPECT_EQ(Health(), "SERVING");
  ASSERT_FALSE(StartHeldJob().empty());
  std::thread stopper([this] { server_->Shutdown(absl::Seconds(60)); });
  std::string health;
  WaitFor(
      [&] {
        health = Health();
        return health != "SERVING";
      },
      30);
  const CallResult r = Reconstruct(DracoCloud("sphere", 1000), {}, {}, 30);
  gate_->Open();  // the held job ends, and the shutdown with it
  stopper.join();
  EXPECT_TRUE(health == "NOT_SERVING" || health.rfind("ERROR", 0) == 0) << health;
  EXPECT_EQ(r.status.error_code(), grpc::StatusCode::UNAVAILABLE);
}

TEST_F(ServiceTest, ShutdownCancelsJobsStillRunningAfterTheGracePeriod) {
  HoldDecodes();
  StartServer();
  ASSERT_FALSE(StartHeldJob().empty());
  const absl::Time start = absl::Now();
  server_->Shutdown(absl::Milliseconds(300));
  EXPECT_LT(absl::Now() - start, absl::Seconds(3));
}

}  // namespace
}  // namespace membrane::testing
