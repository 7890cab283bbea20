// A membrane client against a server that predates uploads in parts (a replica not yet
// upgraded): a fake membraned that reads the upload as one Draco cloud and leaves
// Accepted.upload_parts unset. The client must not let it reconstruct the first part alone:
// it cancels that job and sends the cloud again as one Draco cloud.
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include <grpcpp/security/server_credentials.h>
#include <grpcpp/server.h>
#include <grpcpp/server_builder.h>
#include <gtest/gtest.h>

#include "absl/base/thread_annotations.h"
#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "core/io/draco_codec.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "tests/support/cli_runner.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

// What each Reconstruct call brought: its part table and how many points its bytes decode to
// as one Draco cloud (what an old server reads).
struct Submission {
  int parts = 0;
  int64_t points_as_one_cloud = 0;
};

class OldServer final : public v1::Reconstruction::Service {
 public:
  grpc::Status Reconstruct(
      grpc::ServerContext* /*context*/,
      grpc::ServerReaderWriter<v1::JobEvent, v1::ReconstructRequest>* stream) override {
    v1::ReconstructRequest request;
    std::string upload;
    int parts = 0;
    while (stream->Read(&request)) {
      if (request.has_header()) parts = request.header().upload_part_bytes_size();
      if (request.has_chunk()) upload += request.chunk();
    }
    absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloud(upload);
    std::string id;
    {
      absl::MutexLock lock(&mutex_);
      submissions_.push_back(
          {parts, decoded.ok() ? static_cast<int64_t>(decoded->cloud.points.size()) : -1});
      id = absl::StrCat("old", submissions_.size());
    }
    v1::JobEvent event;
    event.mutable_accepted()->set_job_id(id);
    event.mutable_accepted()->set_queue_position(1);
    if (!stream->Write(event)) return grpc::Status::OK;
    // The job ends here, failed, so that the test needs no mesh: what matters is what was sent.
    v1::JobEvent done;
    done.mutable_done()->set_state(v1::FAILED);
    done.mutable_done()->mutable_status()->set_code(grpc::StatusCode::INVALID_ARGUMENT);
    done.mutable_done()->mutable_status()->set_message("the old server stops here");
    stream->Write(done);
    return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, "the old server stops here");
  }

  grpc::Status CancelJob(grpc::ServerContext* /*context*/, const v1::CancelJobRequest* request,
                         v1::Job* job) override {
    absl::MutexLock lock(&mutex_);
    cancelled_.push_back(request->job_id());
    job->set_id(request->job_id());
    job->set_state(v1::CANCELLED);
    return grpc::Status::OK;
  }

  std::vector<Submission> submissions() const {
    absl::MutexLock lock(&mutex_);
    return submissions_;
  }
  std::vector<std::string> cancelled() const {
    absl::MutexLock lock(&mutex_);
    return cancelled_;
  }

 private:
  mutable absl::Mutex mutex_;
  std::vector<Submission> submissions_ ABSL_GUARDED_BY(mutex_);
  std::vector<std::string> cancelled_ ABSL_GUARDED_BY(mutex_);
};

TEST(OldServerTest, ACloudInPartsIsSentAgainAsOneCloudAndTheFirstJobCancelled) {
  OldServer service;
  int port = 0;
  grpc::ServerBuilder builder;
  builder.AddListeningPort("127.0.0.1:0", grpc::InsecureServerCredentials(), &port);
  builder.RegisterService(&service);
  std::unique_ptr<grpc::Server> server = builder.BuildAndStart();
  ASSERT_NE(server, nullptr);
  ASSERT_GT(port, 0);

  ScratchDir dir;
  const std::string cloud = dir.File("sphere.ply");
  constexpr int kPoints = 600'000;  // over the client's threshold for parts
  ASSERT_EQ(RunMembrane({"synth", "sphere", "-o", cloud, "--points", absl::StrCat(kPoints)},
                        dir.path())
                .exit_code,
            0);
  const CliResult r = RunMembrane({"reconstruct", cloud, "-o", dir.File("mesh.ply"), "--server",
                                   absl::StrCat("127.0.0.1:", port)},
                                  dir.path());
  server->Shutdown();

  const std::vector<Submission> sent = service.submissions();
  ASSERT_EQ(sent.size(), 2u) << r.err;
  EXPECT_GT(sent[0].parts, 1) << "the client sends a cloud of 600k points in parts";
  EXPECT_LT(sent[0].points_as_one_cloud, kPoints) << "read as one cloud: the first part alone";
  EXPECT_EQ(service.cancelled(), std::vector<std::string>{"old1"});
  EXPECT_EQ(sent[1].parts, 0);
  EXPECT_EQ(sent[1].points_as_one_cloud, kPoints);
  EXPECT_NE(r.err.find("the server reads no upload in parts (it predates them): job old1 "
                       "cancelled; sending the cloud as one Draco cloud"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex("bytes as Draco in \\d+ parts"))) << r.err;
  // The second job's own end reaches the user as any failed job's does (INVALID_ARGUMENT:
  // exit 3).
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("the old server stops here"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace membrane::testing
