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

namespace membrane::testing {
namespace {

using ::testing::HasSubstr;

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

TEST_F(ServiceTest, BearerSchemeIsCaseInsensitiveAndTheTokenIsNot) {
  options_.bearer_token = "s3cret";
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
