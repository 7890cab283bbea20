// Where membraned listens and how it is reached: addresses checked at both ends, one server per
// port, health by service name, the bearer scheme in any case.
#include <memory>
#include <string>

#include <grpcpp/grpcpp.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "proto/endpoint_address.h"
#include "server/membrane_server.h"
#include "tests/server/service_fixture.h"
#include "tests/support/scratch_dir.h"

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(EndpointAddressTest, HostAndPortInRangeAreAccepted) {
  for (const char* address : {"127.0.0.1:50051", "localhost:1", "[::1]:65535",
                              "dns:///scanner.example:443", "unix:/run/membrane.sock"}) {
    EXPECT_TRUE(CheckEndpointAddress("--server", address, PortZero::kRefused).ok()) << address;
  }
  EXPECT_TRUE(CheckEndpointAddress("--listen", "0.0.0.0:0", PortZero::kAllowed).ok());
}

TEST(EndpointAddressTest, PortOutOfRangeNamesTheFlagAndThePort) {
  const absl::Status s = CheckEndpointAddress("--server", "127.0.0.1:99999", PortZero::kRefused);
  EXPECT_TRUE(absl::IsInvalidArgument(s));
  EXPECT_THAT(s.message(), HasSubstr("--server '127.0.0.1:99999'"));
  EXPECT_THAT(s.message(), HasSubstr("port '99999' is not a number in 1..65535"));
}

TEST(EndpointAddressTest, MalformedAddressesAreRefused) {
  for (const char* address : {"127.0.0.1", "127.0.0.1:", ":50051", "host:5oo51", "::1:50051",
                              "[::1:50051", "host:-1", "host:0", "unix:"}) {
    EXPECT_TRUE(absl::IsInvalidArgument(
        CheckEndpointAddress("--server", address, PortZero::kRefused)))
        << address;
  }
}

TEST_F(ServiceTest, ListenAddressWithAPortOutOfRangeIsInvalidArgument) {
  server::MembraneServer server(options_, &clock_);
  const absl::StatusOr<int> port = server.Start("127.0.0.1:99999");
  ASSERT_FALSE(port.ok());
  EXPECT_TRUE(absl::IsInvalidArgument(port.status())) << port.status();
  EXPECT_THAT(port.status().message(), HasSubstr("--listen"));
}

TEST_F(ServiceTest, SecondServerOnAPortInUseIsRefused) {
  StartServer();
  server::MembraneServer second(options_, &clock_);
  const absl::StatusOr<int> port = second.Start(address_);
  ASSERT_FALSE(port.ok()) << "a second server started on " << address_;
  EXPECT_THAT(port.status().message(), HasSubstr("cannot listen on " + address_));
  EXPECT_EQ(Health(), "SERVING");  // the first one keeps serving
}

TEST_F(ServiceTest, HealthAnswersForTheServiceByName) {
  StartServer();
  EXPECT_EQ(Health("membrane.v1.Reconstruction"), "SERVING");
  EXPECT_THAT(Health("no.such.Service"), HasSubstr("ERROR"));
}

// Each client sees its own jobs only: another's job is NOT_FOUND for GetJob, WatchJob and
// CancelJob, as an unknown one, and missing from ListJobs; an operator sees and cancels every
// job, and the job's client learns who cancelled it. The log names clients, never tokens.
TEST_F(ServiceTest, JobsAreSeenOnlyByTheirClientAndOperators) {
  options_.clients = {{"alice", "tok-alice"}, {"bob", "tok-bob"}, {"ops", "tok-ops", true}};
  ::testing::internal::CaptureStderr();
  HoldDecodes();
  StartServer();
  const auto context_of = [](const std::string& token) {
    auto context = std::make_unique<grpc::ClientContext>();
    context->AddMetadata("authorization", "Bearer " + token);
    return context;
  };
  const auto get = [&](const std::string& token, const std::string& id) {
    v1::GetJobRequest request;
    request.set_job_id(id);
    v1::Job job;
    return stub_->GetJob(context_of(token).get(), request, &job);
  };
  const auto cancel = [&](const std::string& token, const std::string& id) {
    v1::CancelJobRequest request;
    request.set_job_id(id);
    v1::Job job;
    return stub_->CancelJob(context_of(token).get(), request, &job);
  };
  const auto listed = [&](const std::string& token) {
    v1::ListJobsResponse list;
    EXPECT_TRUE(stub_->ListJobs(context_of(token).get(), {}, &list).ok());
    std::vector<std::string> ids;
    for (const v1::Job& job : list.jobs()) ids.push_back(job.id() + ":" + job.client());
    return ids;
  };
  token_ = "tok-alice";
  gate_->Open();  // for the job that finishes
  const CallResult done = Reconstruct(DracoCloud("sphere", 2000), {});
  ASSERT_TRUE(done.status.ok()) << done.status.error_message();
  const std::string id = done.JobId();
  const std::string running = StartHeldJob();
  ASSERT_FALSE(running.empty());

  EXPECT_TRUE(get("tok-alice", id).ok());
  const grpc::Status other = get("tok-bob", id);
  EXPECT_EQ(other.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(other.error_message(), "no job '" + id + "' (unknown, or its result expired)");
  EXPECT_EQ(cancel("tok-bob", running).error_code(), grpc::StatusCode::NOT_FOUND);
  token_ = "tok-bob";
  EXPECT_EQ(Watch(id).status.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_THAT(listed("tok-bob"), ::testing::IsEmpty());
  EXPECT_THAT(listed("tok-alice"),
              ::testing::UnorderedElementsAre(id + ":alice", running + ":alice"));
  EXPECT_EQ(listed("tok-ops").size(), 2u);

  ASSERT_TRUE(cancel("tok-ops", running).ok());
  token_ = "tok-alice";
  const CallResult cancelled = Watch(running);
  EXPECT_EQ(cancelled.status.error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_THAT(cancelled.status.error_message(), HasSubstr("cancelled by operator 'ops'"));
  server_->Shutdown(absl::ZeroDuration());
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(log, HasSubstr("event=job_accepted job=" + id + " peer="));
  EXPECT_THAT(log, HasSubstr("client=alice"));
  EXPECT_THAT(log, HasSubstr("event=job_cancel_requested job=" + running));
  EXPECT_THAT(log, HasSubstr("client=ops"));
  EXPECT_THAT(log, Not(HasSubstr("tok-")));
  EXPECT_THAT(log, HasSubstr("token=\"3 clients\""));
}

// The store keeps whose a job is: after a restart on the same directory it is still its
// client's alone.
TEST_F(ServiceTest, StoredJobsStayTheirClients) {
  ScratchDir dir;
  options_.store_dir = dir.File("jobs");
  options_.clients = {{"alice", "tok-alice"}, {"bob", "tok-bob"}};
  StartServer();
  token_ = "tok-alice";
  const CallResult r = Reconstruct(DracoCloud("sphere", 2000), {});
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  server_->Shutdown(absl::ZeroDuration());
  server_.reset();
  StartServer();
  EXPECT_EQ(Watch(r.JobId()).FinalState(), v1::SUCCEEDED);
  token_ = "tok-bob";
  EXPECT_EQ(Watch(r.JobId()).status.error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST_F(ServiceTest, BearerSchemeIsCaseInsensitiveAndTheTokenIsNot) {
  options_.clients = {{"station-1", "s3cret"}};
  StartServer();
  auto list_with = [&](const std::string& authorization) {
    grpc::ClientContext context;
    context.AddMetadata("authorization", authorization);
    v1::ListJobsResponse list;
    return stub_->ListJobs(&context, {}, &list).error_code();
  };
  EXPECT_EQ(list_with("Bearer s3cret"), grpc::StatusCode::OK);
  EXPECT_EQ(list_with("bearer s3cret"), grpc::StatusCode::OK);
  EXPECT_EQ(list_with("BEARER s3cret"), grpc::StatusCode::OK);
  EXPECT_EQ(list_with("Bearer S3CRET"), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(list_with("Basic s3cret"), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(list_with("Bearers3cret"), grpc::StatusCode::UNAUTHENTICATED);
}

}  // namespace
}  // namespace membrane::testing
