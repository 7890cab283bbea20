// membraned and membrane as processes on a free loopback port, driven as a user would.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include <grpcpp/client_context.h>
#include <grpcpp/create_channel.h>
#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "absl/time/clock.h"
#include "core/base/malloc_policy.h"
#include "core/io/file_bytes.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "core/pipeline/machine_memory.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "proto/crc32c.h"
#include "tests/support/cli_runner.h"
#include "tests/support/plane_edge_cloud.h"
#include "tests/support/survey_cloud.h"
#include "tests/support/scratch_dir.h"
#include "tests/server/draco_upload.h"
#include "tests/server/gated_decoder.h"
#include "tests/server/http_get.h"
#include "tests/server/membraned_process.h"
#include "tests/server/subprocess.h"
#include "tests/support/shared_data.h"

namespace membrane::testing {
namespace {

class EndToEndTest : public ::testing::Test {
 protected:
  // Starts membraned on 127.0.0.1:0 with `flags`; reads its port from the log.
  void StartServer(std::vector<std::string> flags = {}) {
    MembranedProcess server = StartMembraned(dir_, "membraned", flags);
    server_ = std::move(server.process);
    log_ = server.log;
    address_ = server.address;
    ASSERT_FALSE(address_.empty());
  }

  CliResult Run(std::vector<std::string> args) { return RunMembrane(args, dir_.path()); }

  // A `membrane` client running in the background.
  std::unique_ptr<Subprocess> RunInBackground(const std::vector<std::string>& args,
                                              const std::string& name) {
    std::vector<std::string> argv = {MEMBRANE_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    return std::make_unique<Subprocess>(argv, dir_.File(name + ".out"), dir_.File(name + ".err"));
  }

  std::string Synth(const std::string& shape, int points) {
    const std::string path = dir_.File(shape + std::to_string(points) + ".ply");
    EXPECT_EQ(Run({"synth", shape, "-o", path, "--points", std::to_string(points)}).exit_code, 0);
    return path;
  }

  void ExpectHealthy() { EXPECT_EQ(Run({"health", "--server", address_}).exit_code, 0); }

  // Flags for StartServer that hold every decode at gate_ until the test opens it
  // (GatedDecoder): a job then runs, in its decode, for as long as the test wants, whatever
  // the machine's load. The decode's wall-clock limit then bounds a failure only.
  std::vector<std::string> HoldDecodes() {
    const std::string membraned = MEMBRANED_BINARY;
    gate_ = std::make_unique<GatedDecoder>(
        dir_, membraned.substr(0, membraned.rfind('/')) + "/membrane-decode");
    return {"--decoder_path=" + gate_->path(), "--decoder_timeout_seconds=600"};
  }

  // `flags` and `more`, for StartServer.
  static std::vector<std::string> Flags(std::vector<std::string> flags,
                                        const std::vector<std::string>& more) {
    flags.insert(flags.end(), more.begin(), more.end());
    return flags;
  }

  ScratchDir dir_;
  std::string log_;
  std::string address_;
  // Before server_: a server killed outright leaves its held decodes to the gate's end.
  std::unique_ptr<GatedDecoder> gate_;
  std::unique_ptr<Subprocess> server_;
};

void WriteText(const std::string& path, const std::string& text) {
  ASSERT_TRUE(WriteFileBytes(path, text).ok()) << path;
}

// The "k/N" of each "shrink: generation k/N" line, in order.
std::vector<int> GenerationNumbers(const std::string& err) {
  std::vector<int> numbers;
  const std::regex line("shrink: generation (\\d+)/\\d+, plate size");
  for (auto it = std::sregex_iterator(err.begin(), err.end(), line); it != std::sregex_iterator();
       ++it) {
    numbers.push_back(std::stoi((*it)[1].str()));
  }
  return numbers;
}

TEST_F(EndToEndTest, ProgressArrivesOncePerGenerationInOrder) {
  StartServer();
  const std::string cloud = Synth("torus", 20000);
  const CliResult r =
      Run({"reconstruct", cloud, "-o", dir_.File("mesh.ply"), "--server", address_});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<int> numbers = GenerationNumbers(r.err);
  ASSERT_FALSE(numbers.empty()) << r.err;
  for (size_t i = 0; i < numbers.size(); ++i) EXPECT_EQ(numbers[i], static_cast<int>(i) + 1);
  EXPECT_EQ(Run({"check", dir_.File("mesh.ply")}).exit_code, 0);
}

TEST_F(EndToEndTest, KeptHandleRetryRowsReplaceTheFirstRunsRows) {
  // The spot scan is the real cloud whose first shrink leaves handles that the handle retry
  // removes (docs/engine-decisions.md): its rows arrive after the first run's and replace them.
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  StartServer();
  const CliResult r =
      Run({"reconstruct", data_dir + "/clouds/spot-scan.ply", "-o", dir_.File("spot.ply"),
           "--server", address_, "--stats-json", dir_.File("spot.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<int> numbers = GenerationNumbers(r.err);
  ASSERT_EQ(numbers.size(), 11u) << r.err;  // 8 generations, then 6 to 8 again
  EXPECT_EQ(numbers[8], 6) << r.err;
  EXPECT_NE(r.err.find("(handle retry, kept)"), std::string::npos) << r.err;
  // The table: one row per generation, the last three marked, then what the mark means.
  const std::regex row("\\n +\\d+ \\| +\\d+ \\| +\\d+ \\| +\\d+ \\| +[0-9.]+( \\*)?");
  int rows = 0, marked = 0;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), row);
       it != std::sregex_iterator(); ++it) {
    ++rows;
    marked += (*it)[1].matched;
  }
  EXPECT_EQ(rows, 8) << r.out;
  EXPECT_EQ(marked, 3) << r.out;
  EXPECT_NE(r.out.find("* run again by the handle retry"), std::string::npos) << r.out;
  const std::string json = ReadText(dir_.File("spot.json"));
  EXPECT_NE(json.find("\"handle_retry\": {\"ran\": true, \"kept\": true, \"from_generation\": 6"),
            std::string::npos)
      << json;
  EXPECT_NE(r.out.find("genus [0]"), std::string::npos) << r.out;
}

TEST_F(EndToEndTest, LosslessUploadGivesTheSameMeshAsLocal) {
  StartServer();
  const std::string cloud = Synth("sphere", 10000);
  ASSERT_EQ(Run({"reconstruct", cloud, "-o", dir_.File("remote.ply"), "--server", address_,
                 "--quantization", "0", "--stats-json", dir_.File("remote.json")})
                .exit_code,
            0);
  ASSERT_EQ(Run({"reconstruct", cloud, "-o", dir_.File("local.ply"), "--local"}).exit_code, 0);
  absl::StatusOr<TriangleMesh> remote = ReadMesh(dir_.File("remote.ply"));
  absl::StatusOr<TriangleMesh> local = ReadMesh(dir_.File("local.ply"));
  ASSERT_TRUE(remote.ok() && local.ok());
  EXPECT_EQ(remote->faces.size(), local->faces.size());
  // Draco may reorder vertices; the sets are the same.
  std::sort(remote->vertices.begin(), remote->vertices.end());
  std::sort(local->vertices.begin(), local->vertices.end());
  EXPECT_EQ(remote->vertices, local->vertices);
  EXPECT_NE(ReadText(dir_.File("remote.json")).find("\"generations\""), std::string::npos);
}

// The "voxel_size" and "grid" of a statistics JSON, as text.
std::string GridOf(const std::string& json) {
  std::smatch voxel, grid;
  if (!std::regex_search(json, voxel, std::regex("\"voxel_size\": [^,]+")) ||
      !std::regex_search(json, grid, std::regex("\"grid\": \\[[^\\]]+\\]"))) {
    return "no voxel_size or grid in: " + json.substr(0, 200);
  }
  return voxel.str() + " " + grid.str();
}

// The default 11-bit upload merges points closer than its step, and formula (1) counts
// distinct points, so on the upload alone the server would pick a coarser grid than --local
// (3M sphere points: 693^3 instead of 712^3). The client sends the formula-(1) voxel of the
// cloud as read.
TEST_F(EndToEndTest, DefaultUploadGetsLocalsGridWhenQuantizationMergesPoints) {
  StartServer();
  absl::StatusOr<PointCloud> sphere = ReadPointCloud(Synth("sphere", 20000));
  ASSERT_TRUE(sphere.ok());
  // Each point twice, 1e-5 apart: distinct in the file, one point on an 11-bit grid.
  const size_t n = sphere->points.size();
  for (size_t i = 0; i < n; ++i) {
    Point3f p = sphere->points[i];
    for (float& c : p) c += 1e-5f;
    sphere->points.push_back(p);
  }
  const std::string cloud = dir_.File("pairs.ply");
  ASSERT_TRUE(WritePointCloud(*sphere, cloud).ok());
  ASSERT_EQ(Run({"reconstruct", cloud, "-o", dir_.File("remote.ply"), "--server", address_,
                 "--stats-json", dir_.File("remote.json")})
                .exit_code,
            0);
  ASSERT_EQ(Run({"reconstruct", cloud, "-o", dir_.File("local.ply"), "--local", "--stats-json",
                 dir_.File("local.json")})
                .exit_code,
            0);
  EXPECT_EQ(GridOf(ReadText(dir_.File("remote.json"))), GridOf(ReadText(dir_.File("local.json"))));
}

// Every "genus" array of a statistics JSON (the membrane's, the mesh's), in order.
std::string GenusOf(const std::string& json) {
  std::string genus;
  const std::regex array("\"genus\": \\[[^\\]]*\\]");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), array);
       it != std::sregex_iterator(); ++it) {
    genus += it->str() + " ";
  }
  return genus.empty() ? "no genus in: " + json.substr(0, 200) : genus;
}

// The statistics' value of `key` (a number), as text.
std::string NumberOf(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": [-0-9.e+]+"))) {
    return "no " + key + " in: " + json.substr(0, 200);
  }
  return m.str();
}

// A dense scan whose noise raises the default voxel: the client plans it on the cloud as read
// and sends how (Parameters.voxel_plan), so that the server reports the same formula-(1) size
// and noise and guards the interior as --local does (DenseScanGuard: the grid is far under the
// guard's own width).
TEST_F(EndToEndTest, NoiseRaisedVoxelIsGuardedThroughTheServerAsLocally) {
  StartServer();
  const std::string cloud = dir_.File("noisy.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "400000", "--noise", "0.002",
                 "--holes", "2", "--seed", "3"})
                .exit_code,
            0);
  const CliResult remote = Run({"reconstruct", cloud, "-o", dir_.File("remote.ply"), "--server",
                                address_, "--stats-json", dir_.File("remote.json")});
  ASSERT_EQ(remote.exit_code, 0) << remote.err;
  EXPECT_NE(remote.err.find("so that the membrane closes over the surface"), std::string::npos)
      << remote.err;
  const CliResult local = Run({"reconstruct", cloud, "-o", dir_.File("local.ply"), "--local",
                               "--stats-json", dir_.File("local.json")});
  ASSERT_EQ(local.exit_code, 0) << local.err;
  const std::string remote_json = ReadText(dir_.File("remote.json"));
  const std::string local_json = ReadText(dir_.File("local.json"));
  EXPECT_EQ(GridOf(remote_json), GridOf(local_json));
  for (const std::string key : {"formula_voxel_size", "point_noise", "frozen_voxels"}) {
    EXPECT_EQ(NumberOf(remote_json, key), NumberOf(local_json, key));
  }
  EXPECT_EQ(NumberOf(local_json, "levels"), "\"levels\": 1");
  EXPECT_EQ(GenusOf(remote_json), GenusOf(local_json));
}

// The 11-bit upload of this cloud has a box a plane shorter or longer than the cloud's at this
// voxel (Draco moves the extreme points by up to half a step): the client sends the cloud's
// box (Parameters.grid_box) and keeps each point in its voxel (SnapKeepingVoxels), and the
// server's grid, hard voxels and genus are --local's.
TEST_F(EndToEndTest, QuantizedUploadGetsLocalsGridThroughTheCloudsBox) {
  StartServer();
  const PlaneEdgeCloud c = MakePlaneEdgeCloud(10000);
  ASSERT_NE(c.data_dims, c.quantized_data_dims);
  const std::string cloud = dir_.File("edge.ply");
  ASSERT_TRUE(WritePointCloud(c.cloud, cloud).ok());
  const std::string voxel = absl::StrFormat("%.17g", c.voxel_size);
  const CliResult remote =
      Run({"reconstruct", cloud, "-o", dir_.File("remote.ply"), "--server", address_,
           "--voxel-size", voxel, "--stats-json", dir_.File("remote.json")});
  ASSERT_EQ(remote.exit_code, 0) << remote.err;
  EXPECT_NE(remote.err.find(absl::StrCat(c.bits, "-bit positions")), std::string::npos)
      << remote.err;
  const CliResult local = Run({"reconstruct", cloud, "-o", dir_.File("local.ply"), "--local",
                               "--voxel-size", voxel, "--stats-json", dir_.File("local.json")});
  ASSERT_EQ(local.exit_code, 0) << local.err;
  const std::string remote_json = ReadText(dir_.File("remote.json"));
  const std::string local_json = ReadText(dir_.File("local.json"));
  EXPECT_EQ(GridOf(remote_json), GridOf(local_json));
  EXPECT_NE(remote_json.find(absl::StrCat("\"data_grid\": [", c.data_dims[0], ", ",
                                          c.data_dims[1], ", ", c.data_dims[2], "]")),
            std::string::npos)
      << remote_json;
  EXPECT_EQ(GenusOf(remote_json), GenusOf(local_json));
  const std::regex hard("\"hard_voxels\": \\d+");
  std::smatch remote_hard, local_hard;
  ASSERT_TRUE(std::regex_search(remote_json, remote_hard, hard)) << remote_json;
  ASSERT_TRUE(std::regex_search(local_json, local_hard, hard)) << local_json;
  EXPECT_EQ(remote_hard.str(), local_hard.str());
  EXPECT_NE(remote.err.find("of the file's and in its voxel"), std::string::npos) << remote.err;
}

// A dense cloud is sent with enough bits for its voxel: 400k sphere points make a 258^3 grid,
// and 11 bits would be a step of 0.25 voxel.
TEST_F(EndToEndTest, DenseCloudIsSentWithMoreBitsUnlessTheyAreGiven) {
  StartServer();
  const std::string cloud = Synth("sphere", 400000);
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("dense.ply"), "--server",
                           address_, "--stats-json", dir_.File("dense.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("12-bit positions"), std::string::npos) << r.err;
  const CliResult given = Run({"reconstruct", Synth("sphere", 20000), "-o",
                               dir_.File("given.ply"), "--server", address_, "--quantization",
                               "9"});
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_NE(given.err.find("9-bit positions"), std::string::npos) << given.err;
}

TEST_F(EndToEndTest, TenMillionPointCloudGoesThroughInChunks) {
  StartServer();
  const std::string cloud = dir_.File("big.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "10000000"}).exit_code, 0);
  // A coarse grid: formula (1) for 10M points would be over the voxel budget.
  const CliResult r =
      Run({"reconstruct", cloud, "-o", dir_.File("mesh.ply"), "--server", address_,
           "--voxel-size", "0.05", "--surface", "cuberille", "--stats-json",
           dir_.File("stats.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("upload (\\d+) bytes"))) << r.out;
  EXPECT_GT(std::stoll(m[1].str()), 4 << 20) << "the upload must need more than one message";
  EXPECT_NE(ReadText(dir_.File("stats.json")).find("\"points\": 10000000"), std::string::npos);
  EXPECT_EQ(Run({"check", dir_.File("mesh.ply")}).exit_code, 0);
  ExpectHealthy();
}

TEST_F(EndToEndTest, DroppedClientReattachesAndGetsItsMesh) {
  StartServer({"--on_disconnect=continue"});
  const std::string cloud = Synth("torus", 20000);
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("mesh.obj"), "--server",
                           address_, "--drop-after-events", "4"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("re-attaching to job"), std::string::npos) << r.err;
  // Each generation shown once although the watch replays the job's events.
  const std::vector<int> numbers = GenerationNumbers(r.err);
  for (size_t i = 0; i < numbers.size(); ++i) EXPECT_EQ(numbers[i], static_cast<int>(i) + 1);
  EXPECT_EQ(Run({"check", dir_.File("mesh.obj")}).exit_code, 0);
}

TEST_F(EndToEndTest, BusyServerIsRetriedWithBackoffThenExitFour) {
  StartServer(Flags({"--queue=0", "--retry_delay_seconds=0.3"}, HoldDecodes()));
  // The held job keeps the one worker until it is cancelled below.
  auto slow = RunInBackground({"reconstruct", Synth("sphere", 3000), "-o", dir_.File("slow.ply"),
                               "--server", address_, "-q"},
                              "slow");
  ASSERT_TRUE(gate_->WaitForDecodes(1)) << ReadText(log_);
  // Asked again until the timeout, however many attempts that takes: 0.3 s (the server's
  // delay), then 0.5, 1, 2 and 4 s of backoff, each with up to 20% more, so the sixth refusal
  // comes within 9.4 s. The client stops waiting as soon as the next attempt would fall past
  // its timeout: a timeout under 9.4 s would leave that sixth attempt to the jitter.
  const CliResult busy = Run({"reconstruct", Synth("sphere", 1000), "-o", dir_.File("b.ply"),
                              "--server", address_, "--timeout", "12"});
  EXPECT_EQ(busy.exit_code, 4) << busy.err;
  EXPECT_NE(busy.err.find("timed out after 12 s"), std::string::npos) << busy.err;
  size_t retries = 0;
  for (size_t at = busy.err.find("server busy"); at != std::string::npos;
       at = busy.err.find("server busy", at + 1)) {
    ++retries;
  }
  EXPECT_GE(retries, 6u) << busy.err;
  // Cancel the slow job by its id: its client exits 5, the worker is free again.
  const CliResult list = Run({"jobs", "list", "--server", address_});
  ASSERT_EQ(list.exit_code, 0);
  const std::string id = list.out.substr(0, list.out.find(' '));
  EXPECT_EQ(Run({"jobs", "cancel", id, "--server", address_}).exit_code, 0);
  EXPECT_EQ(slow->Wait(10), 5);
  const CliResult get = Run({"jobs", "get", id, "--server", address_});
  EXPECT_NE(get.out.find("state: CANCELLED"), std::string::npos) << get.out;
  ExpectHealthy();
}

// With every call thread busy (--max-calls), gRPC itself refuses calls. The client takes that
// for a busy server, as a full queue: it retries, and exits 4 at its timeout, not 3.
TEST_F(EndToEndTest, ServerOutOfCallThreadsIsRetriedThenExitFour) {
  StartServer(Flags({"--max-calls=1"}, HoldDecodes()));
  auto slow = RunInBackground({"reconstruct", Synth("sphere", 3000), "-o", dir_.File("slow.ply"),
                               "--server", address_, "-q"},
                              "slow");
  ASSERT_TRUE(gate_->WaitForDecodes(1)) << ReadText(log_);
  const CliResult list = Run({"jobs", "list", "--server", address_});
  ASSERT_EQ(list.exit_code, 0) << list.err;
  const std::string id = list.out.substr(0, list.out.find(' '));
  // Watchers of the running job hold the call threads the limit leaves (with gRPC's pollers).
  std::vector<std::unique_ptr<Subprocess>> watchers;
  for (int i = 0; i < 4; ++i) {
    watchers.push_back(RunInBackground({"jobs", "watch", id, "--server", address_, "-q"},
                                       "watch" + std::to_string(i)));
  }
  absl::SleepFor(absl::Seconds(1));
  const CliResult busy = Run({"reconstruct", Synth("sphere", 1000), "-o", dir_.File("b.ply"),
                              "--server", address_, "--timeout", "2"});
  EXPECT_EQ(busy.exit_code, 4) << busy.err;
  EXPECT_NE(busy.err.find("server busy (Server Threadpool Exhausted); retrying"),
            std::string::npos)
      << busy.err;
  // The container probes still pass: health does not need one of those threads.
  const CliResult health = Run({"health", "--server", address_});
  EXPECT_EQ(health.exit_code, 0) << health.err;
  EXPECT_EQ(health.out, "SERVING\n");
  for (auto& w : watchers) w->Signal(SIGTERM);
  slow->Signal(SIGTERM);
  for (auto& w : watchers) w->Wait(10);
  slow->Wait(10);
}

// membraned --metrics-listen: the port is in the server_started line, and a scrape counts
// the job a client ran.
TEST_F(EndToEndTest, MetricsEndpointCountsAJob) {
  StartServer({"--metrics-listen=127.0.0.1:0"});
  std::smatch m;
  const std::string log = ReadText(log_);
  ASSERT_TRUE(std::regex_search(log, m, std::regex("metrics_port=(\\d+)"))) << log;
  const int port = std::stoi(m[1].str());
  ASSERT_EQ(Run({"reconstruct", Synth("sphere", 2000), "-o", dir_.File("m.ply"), "--server",
                 address_, "-q"})
                .exit_code,
            0);
  const std::string metrics = HttpGet(port, "/metrics");
  EXPECT_EQ(
      MetricValue(metrics, "membrane_jobs_finished_total{code=\"OK\",state=\"SUCCEEDED\"}"), 1)
      << metrics;
  EXPECT_EQ(HttpGet(port, "/nothing-here"), "");
}

// membraned --store-dir killed outright (no shutdown at all): once restarted on the same
// directory it serves the finished job's mesh again, and runs the job it was running again,
// under its id, from the upload it kept.
TEST_F(EndToEndTest, StoreDirKeepsResultsAcrossACrash) {
  const std::string store = "--store-dir=" + dir_.File("jobs");
  StartServer(Flags({store}, HoldDecodes()));
  const std::string cloud = Synth("sphere", 20000);
  gate_->Open();  // for the job that finishes
  const CliResult done = Run({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--server",
                              address_, "-q"});
  ASSERT_EQ(done.exit_code, 0) << done.err;
  const CliResult list = Run({"jobs", "list", "--server", address_});
  const std::string finished = list.out.substr(0, list.out.find(' '));
  auto slow = RunInBackground({"reconstruct", Synth("sphere", 3000), "-o", dir_.File("s.ply"),
                               "--server", address_, "-q"},
                              "slow");
  // The held job is the second to reach the gate. Bounded generously: on a loaded machine the
  // client reads and uploads its cloud slowly. Its job_accepted line, which names it, may come
  // after its decode started (the worker can start it while the handler writes it to the
  // store).
  std::string log;
  const auto twice = [&](const std::string& event) {
    const size_t first = log.find(event);
    return first != std::string::npos && log.find(event, first + 1) != std::string::npos;
  };
  const auto started_twice = [&] {
    log = ReadText(log_);
    return gate_->Decodes() >= 2 && twice("event=job_accepted");
  };
  const absl::Time end = absl::Now() + absl::Seconds(120);
  while (!started_twice() && absl::Now() < end) absl::SleepFor(absl::Milliseconds(50));
  ASSERT_TRUE(started_twice()) << log;
  server_->Signal(SIGKILL);
  server_->Wait(10);
  slow->Signal(SIGKILL);  // its client is not under test: it would retry for a while
  slow->Wait(10);
  std::string running;
  const std::regex accepted("event=job_accepted job=([0-9a-f]+)");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), accepted);
       it != std::sregex_iterator(); ++it) {
    if ((*it)[1].str() != finished) running = (*it)[1].str();
  }
  ASSERT_FALSE(running.empty()) << log;

  // A log of its own: the first one already says server_started.
  MembranedProcess restarted = StartMembraned(dir_, "restarted", {store});
  ASSERT_FALSE(restarted.address.empty());
  address_ = restarted.address;
  const std::string restarted_log = ReadText(restarted.log);
  EXPECT_NE(restarted_log.find("event=store_loaded"), std::string::npos);
  EXPECT_NE(restarted_log.find("event=job_resumed job=" + running), std::string::npos)
      << restarted_log;
  const CliResult watch = Run({"jobs", "watch", finished, "-o", dir_.File("again.ply"),
                               "--server", address_, "-q"});
  EXPECT_EQ(watch.exit_code, 0) << watch.err;
  EXPECT_TRUE(ReadText(dir_.File("again.ply")) == ReadText(dir_.File("m.ply")))
      << "the stored mesh differs";
  // The resumed job runs from its start, with the server's own decoder: on a loaded machine
  // past the watch's default 30 s, so the bound is only a failure's.
  const CliResult resumed = Run({"jobs", "watch", running, "-o", dir_.File("resumed.ply"),
                                 "--server", address_, "-q", "--timeout", "600"});
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(Run({"check", dir_.File("resumed.ply")}).exit_code, 0);
}

// A client whose job was running when the server was killed (and restarted on the same
// address and store) follows its job by id to its mesh: the same job, not a second one.
TEST_F(EndToEndTest, ClientGetsItsMeshFromTheSameJobAfterACrash) {
  const std::string store = "--store-dir=" + dir_.File("jobs");
  StartServer({store});
  const std::string cloud = Synth("sphere", 20000);
  auto client = RunInBackground({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--server",
                                 address_, "--voxel-size", "0.012", "--timeout", "120"},
                                "client");
  // Logged once the job is on disk, before the client hears it was accepted.
  const std::string log = WaitForText(log_, "event=job_accepted", 20);
  std::smatch id;
  ASSERT_TRUE(std::regex_search(log, id, std::regex("event=job_accepted job=([0-9a-f]+)"))) << log;
  server_->Signal(SIGKILL);
  server_->Wait(10);
  MembranedProcess restarted =
      StartMembraned(dir_, "restarted", {store, "--listen=" + address_});
  ASSERT_EQ(restarted.address, address_);
  EXPECT_EQ(client->Wait(120), 0) << ReadText(dir_.File("client.err"));
  const std::string err = ReadText(dir_.File("client.err"));
  EXPECT_EQ(err.find("sending the cloud again"), std::string::npos) << err;
  const std::string restarted_log = ReadText(restarted.log);
  EXPECT_NE(restarted_log.find("event=job_resumed job=" + id[1].str()), std::string::npos)
      << restarted_log;
  EXPECT_EQ(restarted_log.find("event=job_accepted"), std::string::npos) << restarted_log;
  EXPECT_EQ(Run({"check", dir_.File("m.ply")}).exit_code, 0);
}

// A client started while its server is down (a restart, a rescheduled pod) waits for the
// server and gets its mesh once the server is back; so does a client that a full queue was
// refusing when the server went away.
TEST_F(EndToEndTest, ClientWaitsForAServerThatComesBack) {
  StartServer(Flags({"--queue=0", "--retry_delay_seconds=0.3"}, HoldDecodes()));
  const std::string address = address_;
  const std::string cloud = Synth("sphere", 3000);
  auto slow = RunInBackground(
      {"reconstruct", cloud, "-o", dir_.File("s.ply"), "--server", address, "-q"}, "slow");
  ASSERT_TRUE(gate_->WaitForDecodes(1)) << ReadText(log_);
  auto refused = RunInBackground({"reconstruct", cloud, "-o", dir_.File("refused.ply"),
                                  "--server", address, "--timeout", "120"},
                                 "refused");
  ASSERT_NE(WaitForText(dir_.File("refused.err"), "server busy", 60).find("server busy"),
            std::string::npos);
  server_->Signal(SIGKILL);
  server_->Wait(10);
  ASSERT_NE(WaitForText(dir_.File("refused.err"), "server unreachable", 60)
                .find("server unreachable"),
            std::string::npos);
  auto late = RunInBackground({"reconstruct", cloud, "-o", dir_.File("late.ply"), "--server",
                               address, "--timeout", "120"},
                              "late");
  ASSERT_NE(WaitForText(dir_.File("late.err"), "server unreachable", 60)
                .find("server unreachable"),
            std::string::npos);
  MembranedProcess back = StartMembraned(dir_, "back", {"--listen=" + address});
  ASSERT_EQ(back.address, address);
  EXPECT_EQ(refused->Wait(120), 0) << ReadText(dir_.File("refused.err"));
  EXPECT_EQ(late->Wait(120), 0) << ReadText(dir_.File("late.err"));
  EXPECT_EQ(Run({"check", dir_.File("refused.ply")}).exit_code, 0);
  EXPECT_EQ(Run({"check", dir_.File("late.ply")}).exit_code, 0);
  slow->Wait(30);
}

// SIGTERM leaves the store as a crash does: the running job finishes within the grace period,
// the queued one stays queued on disk and runs at the next start, under its id.
TEST_F(EndToEndTest, StopKeepsQueuedJobsForTheNextStart) {
  const std::string store = "--store-dir=" + dir_.File("jobs");
  // The first job runs until the gate opens, after the stop: the grace period only bounds a
  // failure, never the test's normal course.
  StartServer(Flags({store, "--grace_seconds=600"}, HoldDecodes()));
  const std::string cloud = Synth("sphere", 20000);
  auto first = RunInBackground({"reconstruct", Synth("sphere", 10000), "-o", dir_.File("a.ply"),
                                "--server", address_, "-q"},
                               "first");
  std::string log = WaitForText(log_, "event=job_started", 60);
  std::smatch started;
  ASSERT_TRUE(std::regex_search(log, started, std::regex("event=job_started job=([0-9a-f]+)")))
      << log;
  const std::string running_id = started[1].str();
  ASSERT_TRUE(gate_->WaitForDecodes(1)) << ReadText(log_);
  // Not quiet: its client says when the server has the job, and where in the queue.
  auto second = RunInBackground(
      {"reconstruct", cloud, "-o", dir_.File("b.ply"), "--server", address_}, "second");
  const std::string second_err = WaitForText(dir_.File("second.err"), "accepted", 60);
  std::smatch accepted;
  ASSERT_TRUE(std::regex_search(second_err, accepted,
                                std::regex("job ([0-9a-f]+) accepted, queue position 1")))
      << second_err;
  const std::string queued_id = accepted[1].str();
  ASSERT_NE(queued_id, running_id);
  server_->Signal(SIGTERM);
  ASSERT_NE(WaitForText(log_, "event=server_stopping", 60).find("event=server_stopping"),
            std::string::npos)
      << ReadText(log_);
  gate_->Open();
  EXPECT_EQ(server_->Wait(600), 0);
  log = ReadText(log_);
  EXPECT_NE(log.find("outcome=OK"), std::string::npos) << log;  // the running job finished
  EXPECT_EQ(log.find("outcome=CANCELLED"), std::string::npos) << log;
  EXPECT_EQ(first->Wait(60), 0) << ReadText(dir_.File("first.err"));
  second->Signal(SIGKILL);
  second->Wait(10);
  MembranedProcess restarted = StartMembraned(dir_, "restarted", {store});
  ASSERT_FALSE(restarted.address.empty());
  EXPECT_NE(ReadText(restarted.log).find("event=job_resumed job=" + queued_id),
            std::string::npos)
      << log << ReadText(restarted.log);
  const CliResult watch = Run({"jobs", "watch", queued_id, "-o", dir_.File("b.ply"),
                               "--server", restarted.address, "-q"});
  EXPECT_EQ(watch.exit_code, 0) << watch.err;
  EXPECT_EQ(Run({"check", dir_.File("b.ply")}).exit_code, 0);
}

// A store directory that cannot be written is a start-up error: one line, a non-zero exit.
// /proc/self/fdinfo exists and refuses new files even to root.
TEST_F(EndToEndTest, UnwritableStoreDirFailsTheStart) {
  Subprocess server({MEMBRANED_BINARY, "--listen=127.0.0.1:0", "--store-dir=/proc/self/fdinfo"},
                    dir_.File("ro.out"), dir_.File("ro.err"));
  EXPECT_EQ(server.Wait(30), 4);
  const std::string err = ReadText(dir_.File("ro.err"));
  EXPECT_NE(err.find("membraned: the job store /proc/self/fdinfo cannot be written"),
            std::string::npos)
      << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

TEST_F(EndToEndTest, TimeoutCancelsTheJobOnTheServer) {
  StartServer(HoldDecodes());
  const CliResult r = Run({"reconstruct", Synth("sphere", 3000), "-o", dir_.File("m.ply"),
                           "--server", address_, "--timeout", "1"});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  const std::string log = WaitForText(log_, "outcome=CANCELLED", 5);
  EXPECT_NE(log.find("deadline"), std::string::npos) << log;
  ExpectHealthy();
}

// Ctrl-C on `reconstruct --server` leaves the accepted job running and prints the command
// that gets its mesh, or cancels it with --on-interrupt=cancel; either way one line, exit 130.
TEST_F(EndToEndTest, InterruptLeavesTheJobRunningAndSaysHowToFollowIt) {
  StartServer(HoldDecodes());
  auto slow = RunInBackground(
      {"reconstruct", Synth("sphere", 3000), "-o", dir_.File("s.ply"), "--server", address_},
      "slow");
  const std::string accepted = WaitForText(dir_.File("slow.err"), "accepted", 20);
  ASSERT_NE(accepted.find("accepted"), std::string::npos) << accepted;
  slow->Signal(SIGINT);
  EXPECT_EQ(slow->Wait(10), 130);
  const std::vector<std::string> errors = ErrorLines(ReadText(dir_.File("slow.err")));
  ASSERT_EQ(errors.size(), 1u) << ReadText(dir_.File("slow.err"));
  const CliResult list = Run({"jobs", "list", "--server", address_});
  ASSERT_EQ(list.exit_code, 0);
  const std::string id = list.out.substr(0, list.out.find(' '));
  EXPECT_NE(errors[0].find("job " + id + " goes on"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("membrane jobs watch " + id + " --server " + address_ + " -o " +
                           dir_.File("s.ply")),
            std::string::npos)
      << errors[0];
  const CliResult get = Run({"jobs", "get", id, "--server", address_});
  EXPECT_EQ(get.out.find("state: CANCELLED"), std::string::npos) << get.out;
  EXPECT_EQ(Run({"jobs", "cancel", id, "--server", address_}).exit_code, 0);
}

TEST_F(EndToEndTest, InterruptWithOnInterruptCancelCancelsTheJob) {
  StartServer(HoldDecodes());
  auto slow = RunInBackground({"reconstruct", Synth("sphere", 3000), "-o", dir_.File("s.ply"),
                               "--server", address_, "--on-interrupt", "cancel"},
                              "slow");
  const std::string accepted = WaitForText(dir_.File("slow.err"), "accepted", 20);
  ASSERT_NE(accepted.find("accepted"), std::string::npos) << accepted;
  slow->Signal(SIGINT);
  EXPECT_EQ(slow->Wait(10), 130);
  const std::string err = ReadText(dir_.File("slow.err"));
  EXPECT_NE(err.find("cancelled on " + address_), std::string::npos) << err;
  // Logged whether or not the worker had started the job when the cancel came (a loaded
  // machine can leave it queued that long).
  const std::string log = WaitForText(log_, "outcome=CANCELLED", 10);
  EXPECT_NE(log.find("outcome=CANCELLED"), std::string::npos) << log;
  ExpectHealthy();
}

// A job can be accepted and cancelled before a worker starts it (on a loaded machine, even
// with a worker idle): its end is logged as a run's is. Here it waits behind a held job.
TEST_F(EndToEndTest, InterruptWithOnInterruptCancelLogsTheEndOfAQueuedJob) {
  StartServer(Flags({"--workers=1"}, HoldDecodes()));
  const std::string cloud = Synth("sphere", 3000);
  auto first = RunInBackground(
      {"reconstruct", cloud, "-o", dir_.File("a.ply"), "--server", address_, "-q"}, "first");
  ASSERT_TRUE(gate_->WaitForDecodes(1)) << ReadText(log_);
  auto second = RunInBackground({"reconstruct", cloud, "-o", dir_.File("b.ply"), "--server",
                                 address_, "--on-interrupt", "cancel"},
                                "second");
  const std::string accepted = WaitForText(dir_.File("second.err"), "accepted", 60);
  std::smatch id;
  ASSERT_TRUE(
      std::regex_search(accepted, id, std::regex("job ([0-9a-f]+) accepted, queue position 1")))
      << accepted;
  second->Signal(SIGINT);
  EXPECT_EQ(second->Wait(10), 130);
  const std::string ended = "event=job_finished job=" + id[1].str() + " outcome=CANCELLED";
  const std::string log = WaitForText(log_, ended, 10);
  EXPECT_NE(log.find(ended), std::string::npos) << log;
  EXPECT_EQ(log.find("event=job_started job=" + id[1].str()), std::string::npos) << log;
  gate_->Open();
  EXPECT_EQ(first->Wait(60), 0) << ReadText(dir_.File("first.err"));
}

TEST_F(EndToEndTest, JobsGetWatchAndUnknownIds) {
  StartServer();
  ASSERT_EQ(Run({"reconstruct", Synth("sphere", 3000), "-o", dir_.File("a.ply"), "--server",
                 address_})
                .exit_code,
            0);
  const CliResult list = Run({"jobs", "list", "--server", address_});
  ASSERT_EQ(list.exit_code, 0);
  const std::string id = list.out.substr(0, list.out.find(' '));
  EXPECT_NE(list.out.find("SUCCEEDED"), std::string::npos);
  const CliResult watch =
      Run({"jobs", "watch", id, "--server", address_, "-o", dir_.File("again.drc")});
  EXPECT_EQ(watch.exit_code, 0) << watch.err;
  EXPECT_EQ(Run({"check", dir_.File("again.drc")}).exit_code, 0);
  EXPECT_EQ(Run({"jobs", "get", "nope", "--server", address_}).exit_code, 3);
  // --json: the proto's JSON mapping, one object per line, for scripts.
  const CliResult list_json = Run({"jobs", "list", "--server", address_, "--json"});
  ASSERT_EQ(list_json.exit_code, 0) << list_json.err;
  EXPECT_EQ(list_json.out.rfind("{\"jobs\":[{", 0), 0u) << list_json.out;
  EXPECT_NE(list_json.out.find("\"id\":\"" + id + "\""), std::string::npos) << list_json.out;
  const CliResult get_json = Run({"jobs", "get", id, "--server", address_, "--json"});
  ASSERT_EQ(get_json.exit_code, 0) << get_json.err;
  EXPECT_NE(get_json.out.find("\"state\":\"SUCCEEDED\""), std::string::npos) << get_json.out;
  EXPECT_EQ(std::count(get_json.out.begin(), get_json.out.end(), '\n'), 1) << get_json.out;
}

// --server in a pipe: the cloud from stdin, the mesh to stdout (the same bytes as to a file),
// the table and the summary on stderr.
TEST_F(EndToEndTest, ReconstructReadsStdinAndWritesStdoutThroughTheServer) {
  StartServer();
  const std::string cloud = Synth("sphere", 3000);
  const CliResult file =
      RunMembrane({"reconstruct", cloud, "-o", dir_.File("m.ply"), "--server", address_},
                  dir_.path());
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const CliResult piped =
      RunMembrane({"reconstruct", "-", "-o", "-", "--server", address_}, dir_.path(), cloud);
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.out, ReadWholeFile(dir_.File("m.ply")));
  EXPECT_NE(piped.err.find("plate size | soft voxels"), std::string::npos) << piped.err;
  EXPECT_NE(piped.err.find("encode: stdout"), std::string::npos) << piped.err;
}

// Over --server, long stages show a fraction and their time as --local does: the server sends
// StageProgress (here for every stage: --progress-after-seconds=0), the client prints it.
TEST_F(EndToEndTest, StageProgressArrivesFromTheServer) {
  StartServer({"--progress-after-seconds=0"});
  const CliResult r =
      Run({"reconstruct", Synth("torus", 20000), "-o", dir_.File("m.ply"), "--server", address_});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("\nsurface: 100% in "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\ncheck: 100% in "), std::string::npos) << r.err;
  // jobs watch replays them with the job's other events.
  const CliResult list = Run({"jobs", "list", "--server", address_});
  ASSERT_EQ(list.exit_code, 0);
  const CliResult watch =
      Run({"jobs", "watch", list.out.substr(0, list.out.find(' ')), "--server", address_});
  ASSERT_EQ(watch.exit_code, 0) << watch.err;
  EXPECT_NE(watch.err.find("\nsurface: 100% in "), std::string::npos) << watch.err;
}

// A job submitted as a client without Draco submits it (client/python): asking for the mesh
// as binary PLY. Follows the job to its end; returns its id, and the PLY received in `ply`.
std::string SubmitPlyJob(const std::string& address, const std::string& cloud,
                         std::string& ply) {
  auto stub = v1::Reconstruction::NewStub(
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  auto stream = stub->Reconstruct(&context);
  v1::ReconstructRequest header;
  header.mutable_header()->mutable_parameters()->set_mesh_format(v1::MESH_FORMAT_PLY);
  header.mutable_header()->set_upload_bytes(cloud.size());
  header.mutable_header()->set_upload_crc32c(Crc32c(cloud));
  v1::ReconstructRequest chunk;
  chunk.set_chunk(cloud);
  EXPECT_TRUE(stream->Write(header) && stream->Write(chunk));
  stream->WritesDone();
  std::string id;
  v1::JobEvent event;
  while (stream->Read(&event)) {
    if (event.has_accepted()) id = event.accepted().job_id();
    if (event.has_mesh_chunk()) ply += event.mesh_chunk();
  }
  const grpc::Status status = stream->Finish();
  EXPECT_TRUE(status.ok()) << status.error_message();
  return id;
}

// `jobs watch` of a job that asked for PLY writes the format of -o's extension: the PLY as it
// came for .ply, the same mesh decoded and written again for the others.
TEST_F(EndToEndTest, JobsWatchWritesAPlyJobsMeshInTheOutputsFormat) {
  StartServer();
  std::string received;
  const std::string id = SubmitPlyJob(address_, LosslessDracoCloud("torus", 20000), received);
  ASSERT_FALSE(id.empty());
  ASSERT_EQ(received.rfind("ply\nformat binary_little_endian", 0), 0u);
  absl::StatusOr<TriangleMesh> sent = ReadMeshFromBuffer(received, FileFormat::kPly);
  ASSERT_TRUE(sent.ok()) << sent.status();
  for (const char* name : {"w.ply", "w.obj", "w.stl", "w.drc"}) {
    const CliResult watch = Run({"jobs", "watch", id, "--server", address_, "-o", dir_.File(name)});
    ASSERT_EQ(watch.exit_code, 0) << name << watch.err;
    absl::StatusOr<TriangleMesh> mesh = ReadMesh(dir_.File(name));
    ASSERT_TRUE(mesh.ok()) << name << mesh.status();
    EXPECT_EQ(mesh->faces.size(), sent->faces.size()) << name;
    const CliResult check = Run({"check", dir_.File(name)});
    EXPECT_EQ(check.exit_code, 0) << name << check.out << check.err;
    EXPECT_NE(check.out.find("genus: [1]"), std::string::npos) << name << check.out;
  }
  EXPECT_EQ(ReadWholeFile(dir_.File("w.ply")), received);
}

// A georeferenced scan goes up in its moved float32 positions with its origin beside them, and
// comes back at its coordinates, through the call and through `jobs watch` alike.
TEST_F(EndToEndTest, GeoreferencedCloudComesBackAtItsCoordinates) {
  StartServer();
  const std::string cloud = dir_.File("survey.xyz");
  WriteSurveyCopy(Synth("sphere", 3000), cloud);
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("survey.obj"), "--server",
                           address_, "--stats-json", dir_.File("survey.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(ReadWholeFile(dir_.File("survey.json")).find("\"origin\": [51234"),
            std::string::npos);
  const CliResult list = Run({"jobs", "list", "--server", address_});
  ASSERT_EQ(list.exit_code, 0);
  const std::string id = list.out.substr(0, list.out.find(' '));
  ASSERT_EQ(Run({"jobs", "watch", id, "--server", address_, "-o", dir_.File("again.ply")})
                .exit_code,
            0);
  for (const char* name : {"survey.obj", "again.ply"}) {
    absl::StatusOr<TriangleMesh> mesh = ReadMesh(dir_.File(name));
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    const std::array<double, 3> centre = FileBoxCentre(*mesh);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(centre[k], kSurveyOffset[k], 0.05) << name << k;
    EXPECT_EQ(Run({"check", dir_.File(name)}).exit_code, 0) << name;
  }
  // .drc holds float32 only: refused before the upload, and `jobs watch` refuses it too.
  const CliResult drc =
      Run({"reconstruct", cloud, "-o", dir_.File("survey.drc"), "--server", address_});
  EXPECT_EQ(drc.exit_code, 3);
  EXPECT_NE(drc.err.find("write .ply or .obj"), std::string::npos) << drc.err;
  EXPECT_EQ(drc.err.find("accepted"), std::string::npos) << drc.err;
  EXPECT_EQ(Run({"jobs", "watch", id, "--server", address_, "-o", dir_.File("w.drc")}).exit_code,
            3);
}

TEST_F(EndToEndTest, GridOverTheServersVoxelBudgetExitsThree) {
  // The client checks its flags too; the server's own check is covered in process. Here: a
  // grid over the server's voxel budget.
  StartServer({"--voxel_budget=1000"});
  const CliResult r =
      Run({"reconstruct", Synth("sphere", 3000), "-o", dir_.File("a.ply"), "--server", address_});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  ExpectHealthy();
}

TEST_F(EndToEndTest, NoServerExitsFour) {
  const CliResult r = Run({"reconstruct", Synth("sphere", 1000), "-o", dir_.File("a.ply"),
                           "--server", "127.0.0.1:1", "--timeout", "2"});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(Run({"health", "--server", "127.0.0.1:1", "--timeout", "1"}).exit_code, 0);
}

TEST_F(EndToEndTest, SigtermStopsTheServerGracefully) {
  StartServer();
  ExpectHealthy();
  server_->Signal(SIGTERM);
  EXPECT_EQ(server_->Wait(10), 0);
  EXPECT_NE(ReadText(log_).find("event=server_stopped"), std::string::npos);
}

// The server's warnings reach the --server client's stderr after its summary, as --local's do,
// and `jobs watch` prints them too: at a voxel size given near formula (1)'s (0.035 for 20k
// points on the unit sphere), noise 0.05 scatters the points over more than a voxel. By default
// the client plans the voxel for the noise, as --local does, sends that size, and prints the
// note saying so itself (the server, given a size, has nothing to say).
TEST_F(EndToEndTest, ScatteredCloudsWarningIsPrintedByTheClient) {
  StartServer();
  const std::string cloud = dir_.File("noisy.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "20000", "--noise", "0.05"})
                .exit_code,
            0);
  const CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("noisy_mesh.ply"), "--server",
                           address_, "--quiet", "--surface", "cuberille", "--voxel-size", "0.035"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("warning: the points scatter about their surface", 0), 0u) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("job ([0-9a-f]+):"))) << r.out;
  const CliResult watched = Run({"jobs", "watch", m[1].str(), "--server", address_, "--quiet"});
  ASSERT_EQ(watched.exit_code, 0) << watched.err;
  EXPECT_EQ(watched.err, r.err);

  const CliResult planned = Run({"reconstruct", cloud, "-o", dir_.File("planned.ply"), "--server",
                                 address_, "--quiet", "--surface", "cuberille"});
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  EXPECT_EQ(planned.err.rfind("warning: the points scatter across their surface", 0), 0u)
      << planned.err;
  EXPECT_EQ(std::count(planned.err.begin(), planned.err.end(), '\n'), 1) << planned.err;
  const CliResult local = Run({"reconstruct", cloud, "-o", dir_.File("local.ply"), "--local",
                               "--quiet", "--surface", "cuberille"});
  ASSERT_EQ(local.exit_code, 0) << local.err;
  EXPECT_EQ(local.err, planned.err);
}

// Without --memory-budget-bytes a noisy upload must still be refused rather than take the
// machine: the default budget is 3/4 of its memory (or of the container's limit), in the log.
TEST_F(EndToEndTest, DefaultMemoryLimitsAreShareOfTheMachine) {
  StartServer();
  const MachineMemory machine = ReadMachineMemory();
  ASSERT_GT(machine.total_bytes, 0);
  const std::string log = ReadText(log_);
  EXPECT_NE(log.find("memory_budget_bytes=" + std::to_string(machine.total_bytes / 4 * 3)),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("memory_budget_from=\"3/4 of " + machine.total_source + "\""),
            std::string::npos)
      << log;
  // Uploads held at once (arriving, queued, decoding) get an eighth, beside the budget.
  EXPECT_NE(log.find("upload_memory_bytes=" + std::to_string(machine.total_bytes / 8)),
            std::string::npos)
      << log;
}

// membraned starts itself again once, its heap advised huge pages by glibc, where the kernel
// gives them only to advised memory; that tunable is not the operator's choice of malloc's
// settings, so the one-arena policy stands.
TEST_F(EndToEndTest, ServerRunsOnHugePagesWithTheOneArenaPolicy) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  if (std::getenv("GLIBC_TUNABLES") != nullptr || std::getenv("MALLOC_ARENA_MAX") != nullptr) {
    GTEST_SKIP() << "malloc's settings are chosen in this test's environment";
  }
  StartServer();
  // The environment the running image started with, its entries separated by NULs.
  const std::vector<std::string> environment = absl::StrSplit(
      ReadText("/proc/" + std::to_string(server_->pid()) + "/environ"), absl::ByChar('\0'));
  const bool advised = std::find(environment.begin(), environment.end(),
                                 "GLIBC_TUNABLES=glibc.malloc.hugetlb=1") != environment.end();
  EXPECT_EQ(advised, KernelGivesHugePagesOnlyWhenAdvised());
  const std::string log = ReadText(log_);
  EXPECT_NE(log.find("malloc=one-arena"), std::string::npos) << log;
}

TEST_F(EndToEndTest, NegativeMemoryBudgetIsRefusedAtStart) {
  Subprocess bad({MEMBRANED_BINARY, "--listen=127.0.0.1:0", "--memory-budget-bytes=-2"},
                 dir_.File("bad.out"), dir_.File("bad.err"));
  EXPECT_EQ(bad.Wait(10), 2);
  EXPECT_NE(ReadText(dir_.File("bad.err")).find("--memory-budget-bytes -2"), std::string::npos)
      << ReadText(dir_.File("bad.err"));
}

TEST_F(EndToEndTest, MembranedHelpListsItsFlagsAndVersionNamesTheBuild) {
  Subprocess help({MEMBRANED_BINARY, "--help"}, dir_.File("help.out"), dir_.File("help.err"));
  EXPECT_EQ(help.Wait(10), 0);
  const std::string text = ReadText(dir_.File("help.out"));
  for (const char* flag : {"--listen", "--grace-seconds", "--store-dir", "--token-file"}) {
    EXPECT_NE(text.find(flag), std::string::npos) << flag << " missing from:\n" << text;
  }
  Subprocess version({MEMBRANED_BINARY, "--version"}, dir_.File("v.out"), dir_.File("v.err"));
  EXPECT_EQ(version.Wait(10), 0);
  EXPECT_EQ(ReadText(dir_.File("v.out")),
            std::string("membraned ") + MEMBRANE_VERSION + " (" + MEMBRANE_BUILD_TYPE + " build)\n");
}

TEST_F(EndToEndTest, ListenAddressWithAPortOutOfRangeIsAFlagError) {
  Subprocess bad({MEMBRANED_BINARY, "--listen=127.0.0.1:99999"}, dir_.File("bad.out"),
                 dir_.File("bad.err"));
  EXPECT_EQ(bad.Wait(10), 2);
  EXPECT_NE(ReadText(dir_.File("bad.err")).find("port '99999' is not a number in 0..65535"),
            std::string::npos)
      << ReadText(dir_.File("bad.err"));
}

TEST_F(EndToEndTest, TokenIsNeededOnEveryCallButHealth) {
  WriteText(dir_.File("token"), "  s3cret-token\n");
  WriteText(dir_.File("wrong"), "not-the-token\n");
  StartServer({"--token_file=" + dir_.File("token")});
  const std::string cloud = Synth("sphere", 3000);
  const std::string out = dir_.File("a.ply");
  CliResult r = Run({"reconstruct", cloud, "-o", out, "--server", address_});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("needs a bearer token"), std::string::npos) << r.err;
  r = Run({"reconstruct", cloud, "-o", out, "--server", address_, "--token-file",
           dir_.File("wrong")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("bearer token is not this server's"), std::string::npos) << r.err;
  EXPECT_EQ(Run({"jobs", "list", "--server", address_}).exit_code, 3);
  r = Run({"reconstruct", cloud, "-o", out, "--server", address_, "--token-file",
           dir_.File("token")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = Run({"jobs", "list", "--server", address_, "--token-file", dir_.File("token")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("SUCCEEDED"), std::string::npos) << r.out;
  ExpectHealthy();  // probes carry no token
  EXPECT_NE(ReadText(log_).find("event=call_unauthenticated"), std::string::npos);
}

TEST_F(EndToEndTest, TokenAndCaFilesAreChecked) {
  WriteText(dir_.File("empty"), "\n");
  WriteText(dir_.File("not-pem"), "hello\n");
  CliResult r = Run({"reconstruct", Synth("sphere", 1000), "-o", dir_.File("a.ply"),
                     "--server", "127.0.0.1:1", "--token-file", dir_.File("empty")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("--token-file: " + dir_.File("empty") + " holds no token"),
            std::string::npos)
      << r.err;
  r = Run({"health", "--server", "127.0.0.1:1", "--tls-ca", dir_.File("not-pem")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("holds no PEM certificate"), std::string::npos) << r.err;
  r = Run({"jobs", "list", "--server", "127.0.0.1:1", "--token-file", dir_.File("missing")});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  // The server refuses to start on a half TLS configuration or an unreadable token file.
  Subprocess half({MEMBRANED_BINARY, "--listen=127.0.0.1:0", "--tls_cert=" + dir_.File("not-pem")},
                  dir_.File("half.out"), dir_.File("half.err"));
  EXPECT_EQ(half.Wait(10), 2);
  EXPECT_NE(ReadText(dir_.File("half.err")).find("--tls-cert and --tls-key go together"),
            std::string::npos);
  Subprocess no_token({MEMBRANED_BINARY, "--listen=127.0.0.1:0",
                       "--token_file=" + dir_.File("missing")},
                      dir_.File("no_token.out"), dir_.File("no_token.err"));
  EXPECT_EQ(no_token.Wait(10), 2);
}

TEST_F(EndToEndTest, TlsServerIsReachedWithItsCaOnly) {
  // A throwaway self-signed certificate for the loopback address (install-deps.sh installs
  // openssl).
  const std::string key = dir_.File("key.pem"), cert = dir_.File("cert.pem");
  const std::string make_cert =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=localhost "
      "-addext subjectAltName=IP:127.0.0.1,DNS:localhost -keyout " + key + " -out " + cert +
      " >" + dir_.File("openssl.log") + " 2>&1";
  if (std::system(make_cert.c_str()) != 0) {
    GTEST_SKIP() << "openssl could not make a test certificate (deploy/install-deps.sh "
                    "installs it): " << ReadText(dir_.File("openssl.log"));
  }
  StartServer({"--tls_cert=" + cert, "--tls_key=" + key});
  EXPECT_NE(ReadText(log_).find("tls=on"), std::string::npos);
  const std::string cloud = Synth("torus", 5000);
  CliResult r = Run({"reconstruct", cloud, "-o", dir_.File("a.ply"), "--server", address_,
                     "--tls-ca", cert});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Run({"check", dir_.File("a.ply")}).exit_code, 0);
  EXPECT_EQ(Run({"health", "--server", address_, "--tls-ca", cert}).exit_code, 0);
  EXPECT_EQ(Run({"jobs", "list", "--server", address_, "--tls-ca", cert}).exit_code, 0);
  // Plaintext against a TLS port never completes a handshake: unavailable, exit 4.
  r = Run({"reconstruct", cloud, "-o", dir_.File("b.ply"), "--server", address_, "--timeout",
           "2"});
  EXPECT_EQ(r.exit_code, 4) << r.err;
}

}  // namespace
}  // namespace membrane::testing
