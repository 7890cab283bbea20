#include "client/health_command.h"

#include <cstdio>
#include <memory>
#include <string>

#include <grpcpp/client_context.h>

#include "CLI/CLI.hpp"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "client/flag_checks.h"
#include "client/remote_reconstruction.h"
#include "client/rpc_errors.h"
#include "client/server_connection.h"
#include "grpc/health/v1/health.grpc.pb.h"

namespace membrane::client {
namespace {

struct HealthFlags {
  ConnectionFlags connection;
  double timeout = 5;
};

absl::Status RunHealth(const HealthFlags& flags) {
  if (absl::Status s = CheckRealRange("--timeout", flags.timeout, 0.01, 3600, "seconds");
      !s.ok()) {
    return s;
  }
  absl::StatusOr<ServerConnection> server = LoadServerConnection(flags.connection);
  if (!server.ok()) return server.status();
  // Health needs no token (container probes have none), but a token given is sent.
  auto stub = grpc::health::v1::Health::NewStub(Connect(*server));
  grpc::ClientContext context;
  Authorize(context, *server);
  context.set_deadline(absl::ToChronoTime(absl::Now() + absl::Seconds(flags.timeout)));
  grpc::health::v1::HealthCheckRequest request;
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = stub->Check(&context, request, &response);
  if (!status.ok()) return FromGrpcStatus(status, server->address);
  const std::string name =
      grpc::health::v1::HealthCheckResponse::ServingStatus_Name(response.status());
  std::printf("%s\n", name.c_str());
  if (response.status() == grpc::health::v1::HealthCheckResponse::SERVING) {
    return absl::OkStatus();
  }
  return absl::UnavailableError(absl::StrCat("server ", server->address, " is ", name));
}

}  // namespace

Command AddHealthCommand(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand("health", "ask a membrane server whether it is serving");
  auto flags = std::make_shared<HealthFlags>();
  AddConnectionFlags(*app, flags->connection);
  app->add_option("--timeout", flags->timeout, "seconds to wait for the answer")
      ->capture_default_str();
  return Command{app, [flags] { return RunHealth(*flags); }};
}

}  // namespace membrane::client
