// The balancer of deploy/nginx in front of two named membraned replicas: every call is
// balanced, and a call about a job reaches the replica holding it through the membrane-replica
// header the client sends (proto/job_routing.h).
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "absl/time/clock.h"
#include "core/io/file_bytes.h"
#include "proto/job_routing.h"
#include "tests/support/cli_runner.h"
#include "tests/server/membraned_process.h"
#include "tests/server/subprocess.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

constexpr char kNginx[] = "/usr/sbin/nginx";

// A loopback port free at the time of the call (nginx cannot listen on port 0 and say which
// it took); another process could take it before nginx does, which the test would report.
int FreePort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t size = sizeof address;
  int port = 0;
  if (fd >= 0 && bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size) == 0) {
    port = ntohs(address.sin_port);
  }
  if (fd >= 0) close(fd);
  return port;
}

// The directives every nginx of these tests needs to run unprivileged in `dir`, at the top of
// its configuration and inside http {}.
std::string MainDirectives(const ScratchDir& dir) {
  return absl::StrCat("pid ", dir.File("nginx.pid"), ";\n");
}
std::string TempDirectives(const ScratchDir& dir) {
  std::string text;
  for (const char* kind : {"client_body", "proxy", "fastcgi", "uwsgi", "scgi"}) {
    absl::StrAppend(&text, "  ", kind, "_temp_path ", dir.File(kind), ";\n");
  }
  return text;
}

class BalancerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (access(kNginx, X_OK) != 0) {
      GTEST_SKIP() << kNginx << " is not installed (deploy/install-deps.sh installs "
                   << "nginx-light): the balancer tests are skipped";
    }
  }

  // `nginx -t` on `config`: its exit status, and its output in `output`.
  int TestConfig(const std::string& config, std::string& output) {
    const std::string path = dir_.File("test.conf");
    EXPECT_TRUE(WriteFileBytes(path, config).ok());
    Subprocess nginx({kNginx, "-t", "-p", dir_.path(), "-c", path}, dir_.File("t.out"),
                     dir_.File("t.err"));
    const int status = nginx.Wait(20);
    output = ReadText(dir_.File("t.err"));
    return status;
  }

  CliResult Run(const std::vector<std::string>& args) { return RunMembrane(args, dir_.path()); }

  // nginx with the shipped configuration (LoopbackConfig) in front of `r0` and `r1` as
  // membraned-0 and membraned-1, once it passes health checks through; its address in
  // `address`. Null, the test failed, when it does not start.
  std::unique_ptr<Subprocess> StartBalancer(const MembranedProcess& r0,
                                            const MembranedProcess& r1, std::string& address);

  ScratchDir dir_;
};

// The shipped configuration (deploy/nginx/nginx.conf) made to run here: the cluster's names
// become upstreams of loopback addresses (`upstreams` is the text of their blocks), its
// resolver (the cluster's DNS) one that answers nothing, and it listens on `listen`.
std::string LoopbackConfig(const ScratchDir& dir, const std::string& upstreams,
                           const std::string& listen) {
  const std::string shipped =
      ReadText(std::string(MEMBRANE_SOURCE_DIR) + "/deploy/nginx/nginx.conf");
  std::string config = shipped;
  const std::vector<std::pair<std::string, std::string>> edits = {
      {"resolver kube-dns.kube-system.svc.cluster.local", "resolver 127.0.0.1"},
      {"pid /tmp/nginx.pid;", MainDirectives(dir)},
      {"http {\n", "http {\n" + TempDirectives(dir) + upstreams},
      {"\"${replica}.membraned-pods.default.svc.cluster.local:50051\"", "\"${replica}\""},
      {"default \"membraned.default.svc.cluster.local:50051\"", "default membraned-any"},
      {"listen 50051 http2;", "listen " + listen + " http2;"}};
  for (const auto& [from, to] : edits) {
    EXPECT_NE(config.find(from), std::string::npos) << "deploy/nginx/nginx.conf lost: " << from;
    config = absl::StrReplaceAll(config, {{from, to}});
  }
  return config;
}

std::unique_ptr<Subprocess> BalancerTest::StartBalancer(const MembranedProcess& r0,
                                                        const MembranedProcess& r1,
                                                        std::string& address) {
  const int port = FreePort();
  EXPECT_GT(port, 0);
  address = absl::StrCat("127.0.0.1:", port);
  const std::string upstreams = absl::StrCat(
      "  upstream membraned-0 { server ", r0.address, "; }\n",
      "  upstream membraned-1 { server ", r1.address, "; }\n",
      "  upstream membraned-any { server ", r0.address, "; server ", r1.address, "; }\n");
  std::string output;
  if (TestConfig(LoopbackConfig(dir_, upstreams, address), output) != 0) {
    ADD_FAILURE() << output;
    return nullptr;
  }
  auto nginx = std::make_unique<Subprocess>(
      std::vector<std::string>{kNginx, "-p", dir_.path(), "-c", dir_.File("test.conf"), "-g",
                               "daemon off;"},
      dir_.File("nginx.out"), dir_.File("nginx.err"));
  // Health through the balancer once nginx listens.
  int health = -1;
  for (int attempt = 0; attempt < 50 && health != 0; ++attempt) {
    health = Run({"health", "--server", address, "--timeout", "1"}).exit_code;
    if (health != 0) absl::SleepFor(absl::Milliseconds(100));
  }
  if (health != 0) {
    ADD_FAILURE() << ReadText(dir_.File("nginx.err"));
    return nullptr;
  }
  return nginx;
}

TEST_F(BalancerTest, ShippedConfigurationIsValid) {
  std::string output;
  EXPECT_EQ(TestConfig(LoopbackConfig(dir_, "", "127.0.0.1:1"), output), 0) << output;
}

// Two replicas behind the shipped configuration: new jobs go to both in turn, every call about
// a job reaches its replica however the others are balanced, and a call about a replica that
// is gone gets a gRPC status the client can print.
TEST_F(BalancerTest, CallsAboutAJobReachTheReplicaHoldingIt) {
  MembranedProcess r0 = StartMembraned(dir_, "r0", {"--replica=membraned-0"});
  MembranedProcess r1 = StartMembraned(dir_, "r1", {"--replica=membraned-1"});
  ASSERT_FALSE(r0.address.empty());
  ASSERT_FALSE(r1.address.empty());
  std::string balancer;
  std::unique_ptr<Subprocess> nginx = StartBalancer(r0, r1, balancer);
  ASSERT_NE(nginx, nullptr);

  const std::string cloud = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "20000"}).exit_code, 0);
  std::vector<std::string> ids;
  std::set<std::string> replicas;
  for (int i = 0; i < 2; ++i) {
    const std::string mesh = dir_.File("m" + std::to_string(i) + ".ply");
    const CliResult r = Run({"reconstruct", cloud, "-o", mesh, "--server", balancer, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.err << ReadText(dir_.File("nginx.err"));
    const size_t at = r.out.find("job ");
    ASSERT_NE(at, std::string::npos) << r.out;
    ids.push_back(r.out.substr(at + 4, r.out.find(':', at) - at - 4));
    replicas.insert(std::string(ReplicaOfJobId(ids.back())));
  }
  EXPECT_EQ(replicas, (std::set<std::string>{"membraned-0", "membraned-1"}));
  // Balanced in turn, half of these would reach the other replica without the header.
  for (int round = 0; round < 2; ++round) {
    for (const std::string& id : ids) {
      const CliResult get = Run({"jobs", "get", id, "--server", balancer});
      EXPECT_EQ(get.exit_code, 0) << id << ": " << get.err;
      EXPECT_NE(get.out.find("state: SUCCEEDED"), std::string::npos) << get.out;
    }
  }
  const CliResult watch =
      Run({"jobs", "watch", ids[1], "-o", dir_.File("w.ply"), "--server", balancer, "-q"});
  EXPECT_EQ(watch.exit_code, 0) << watch.err;
  EXPECT_TRUE(ReadText(dir_.File("w.ply")) == ReadText(dir_.File("m1.ply")))
      << "the watched mesh is not the one reconstructed";
  // Each replica's jobs, asked through the balancer; a replica it cannot reach is NOT_FOUND.
  for (const std::string& id : ids) {
    const std::string replica(ReplicaOfJobId(id));
    const CliResult list = Run({"jobs", "list", "--server", balancer, "--replica", replica});
    EXPECT_EQ(list.exit_code, 0) << list.err;
    EXPECT_EQ(list.out.rfind(id + " SUCCEEDED", 0), 0u) << list.out;
    EXPECT_EQ(list.out.find('\n'), list.out.size() - 1) << "one job each: " << list.out;
  }
  EXPECT_EQ(Run({"jobs", "list", "--server", balancer, "--replica", "Membraned"}).exit_code, 3);
  // A client whose call drops mid-job re-attaches through the balancer: its WatchJob, the next
  // call, would go to the other replica in turn without the header.
  const CliResult dropped = Run({"reconstruct", cloud, "-o", dir_.File("d.ply"), "--server",
                                 balancer, "--drop-after-events", "4"});
  EXPECT_EQ(dropped.exit_code, 0) << dropped.err;
  EXPECT_NE(dropped.err.find("re-attaching to job"), std::string::npos) << dropped.err;
  EXPECT_TRUE(ReadText(dir_.File("d.ply")) == ReadText(dir_.File("m0.ply")))
      << "the re-attached mesh is not the one reconstructed";
  // A replica the balancer cannot reach (here: no such upstream, and a resolver that answers
  // nothing; in a cluster: a pod that ended): NOT_FOUND, said in one line.
  const CliResult gone = Run({"jobs", "get", "membraned-7.0123456789abcdef", "--server", balancer});
  EXPECT_EQ(gone.exit_code, 3) << gone.err;
  EXPECT_EQ(ErrorLines(gone.err),
            std::vector<std::string>{"membrane: server: replica membraned-7 is not reachable: it "
                                     "ended, and its jobs with it"})
      << gone.err;
  nginx->Signal(SIGTERM);
  nginx->Wait(10);
}

// Behind the balancer as on one server, a client sees its own jobs only, on whichever
// replica they are: another client's job is NOT_FOUND (exit 3) to get, watch and cancel; an
// operator's token sees it.
TEST_F(BalancerTest, EachClientSeesOnlyItsJobsThroughTheBalancer) {
  ASSERT_TRUE(WriteFileBytes(dir_.File("clients"), "alice tok-alice\nbob tok-bob\n"
                                                   "ops tok-ops operator\n")
                  .ok());
  for (const auto& [name, token] : {std::pair{"alice", "tok-alice"}, std::pair{"bob", "tok-bob"},
                                    std::pair{"ops", "tok-ops"}}) {
    ASSERT_TRUE(WriteFileBytes(dir_.File(name), std::string(token) + "\n").ok());
  }
  const std::string tokens = "--token-file=" + dir_.File("clients");
  MembranedProcess r0 = StartMembraned(dir_, "r0", {"--replica=membraned-0", tokens});
  MembranedProcess r1 = StartMembraned(dir_, "r1", {"--replica=membraned-1", tokens});
  ASSERT_FALSE(r0.address.empty());
  ASSERT_FALSE(r1.address.empty());
  std::string balancer;
  std::unique_ptr<Subprocess> nginx = StartBalancer(r0, r1, balancer);
  ASSERT_NE(nginx, nullptr);
  const auto as = [&](const std::string& client, std::vector<std::string> args) {
    args.insert(args.end(), {"--server", balancer, "--token-file", dir_.File(client)});
    return Run(args);
  };
  const std::string cloud = dir_.File("sphere.ply");
  ASSERT_EQ(Run({"synth", "sphere", "-o", cloud, "--points", "5000"}).exit_code, 0);
  std::vector<std::string> ids;
  for (int i = 0; i < 2; ++i) {  // one job on each replica
    const CliResult r = as("alice", {"reconstruct", cloud, "-o", dir_.File("a.ply"), "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const size_t at = r.out.find("job ");
    ASSERT_NE(at, std::string::npos) << r.out;
    ids.push_back(r.out.substr(at + 4, r.out.find(':', at) - at - 4));
  }
  for (const std::string& id : ids) {
    EXPECT_EQ(as("alice", {"jobs", "get", id}).exit_code, 0) << id;
    const CliResult get = as("bob", {"jobs", "get", id});
    EXPECT_EQ(get.exit_code, 3) << get.err;
    EXPECT_NE(get.err.find("no job '" + id + "' (unknown"), std::string::npos) << get.err;
    EXPECT_EQ(as("bob", {"jobs", "watch", id, "-o", dir_.File("b.ply")}).exit_code, 3);
    EXPECT_EQ(as("bob", {"jobs", "cancel", id}).exit_code, 3);
    const std::string replica(ReplicaOfJobId(id));
    EXPECT_EQ(as("bob", {"jobs", "list", "--replica", replica}).out, "");
    EXPECT_EQ(as("ops", {"jobs", "list", "--replica", replica}).out.rfind(id, 0), 0u);
    EXPECT_EQ(as("ops", {"jobs", "get", id}).exit_code, 0);
  }
  EXPECT_NE(ReadText(r0.log).find("client=alice"), std::string::npos);
  EXPECT_EQ(ReadText(r0.log).find("tok-"), std::string::npos);
  nginx->Signal(SIGTERM);
  nginx->Wait(10);
}

}  // namespace
}  // namespace membrane::testing
