#include "client/server_connection.h"

#include <grpc/grpc.h>
#include <grpcpp/create_channel.h>
#include <grpcpp/security/credentials.h>

#include "CLI/CLI.hpp"
#include "absl/status/status.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "core/io/file_bytes.h"
#include "core/io/token_file.h"
#include "membrane/v1/reconstruction.grpc.pb.h"
#include "proto/endpoint_address.h"
#include "proto/job_routing.h"

namespace membrane::client {

CLI::Option* AddConnectionFlags(CLI::App& app, ConnectionFlags& flags) {
  CLI::Option* server =
      app.add_option("--server", flags.server, "HOST:PORT of a membrane server")
          ->capture_default_str();
  app.add_option("--token-file", flags.token_file,
                 "file holding the bearer token of a server started with --token-file");
  app.add_option("--tls-ca", flags.tls_ca,
                 "PEM file of the CA that signed the server's certificate (enables TLS)");
  return server;
}

absl::StatusOr<ServerConnection> LoadServerConnection(const ConnectionFlags& flags) {
  ServerConnection c;
  if (absl::Status s = CheckEndpointAddress("--server", flags.server, PortZero::kRefused);
      !s.ok()) {
    return s;
  }
  c.address = flags.server;
  if (!flags.token_file.empty()) {
    absl::StatusOr<std::string> token = ReadTokenFile(flags.token_file);
    if (!token.ok()) {
      return absl::InvalidArgumentError(absl::StrCat("--token-file: ", token.status().message()));
    }
    c.token = *std::move(token);
  }
  if (!flags.tls_ca.empty()) {
    absl::StatusOr<std::string> pem = ReadFileBytes(flags.tls_ca);
    if (!pem.ok()) {
      return absl::InvalidArgumentError(absl::StrCat("--tls-ca: ", pem.status().message()));
    }
    if (!absl::StrContains(*pem, "-----BEGIN CERTIFICATE-----")) {
      return absl::InvalidArgumentError(
          absl::StrCat("--tls-ca: ", flags.tls_ca, " holds no PEM certificate"));
    }
    c.tls_ca_pem = *std::move(pem);
  }
  return c;
}

std::shared_ptr<grpc::Channel> Connect(const ServerConnection& connection) {
  grpc::ChannelArguments args;
  args.SetMaxReceiveMessageSize(4 << 20);
  // A lost connection is tried again at most a second apart (gRPC's default backs off to 2
  // minutes): a client waiting for a restarted server (RetryWait) gets it within a second of
  // its return.
  args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 100);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 1000);
  std::shared_ptr<grpc::ChannelCredentials> credentials = grpc::InsecureChannelCredentials();
  if (!connection.tls_ca_pem.empty()) {
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = connection.tls_ca_pem;
    credentials = grpc::SslCredentials(ssl);
  }
  return grpc::CreateCustomChannel(connection.address, credentials, args);
}

void Authorize(grpc::ClientContext& context, const ServerConnection& connection) {
  if (!connection.token.empty()) {
    context.AddMetadata("authorization", absl::StrCat("Bearer ", connection.token));
  }
}

void RouteToJob(grpc::ClientContext& context, const std::string& job_id) {
  const absl::string_view replica = ReplicaOfJobId(job_id);
  if (!replica.empty()) context.AddMetadata(kReplicaHeader, std::string(replica));
}

grpc::Status CancelRemoteJob(const ServerConnection& connection, const std::string& job_id,
                             absl::Duration timeout) {
  auto stub = v1::Reconstruction::NewStub(Connect(connection));
  grpc::ClientContext context;
  Authorize(context, connection);
  RouteToJob(context, job_id);
  context.set_deadline(absl::ToChronoTime(absl::Now() + timeout));
  v1::CancelJobRequest request;
  request.set_job_id(job_id);
  v1::Job job;
  return stub->CancelJob(&context, request, &job);
}

}  // namespace membrane::client
