// How the client reaches a membraned: its address, and optionally TLS (the server's CA) and
// a bearer token, as set by --server, --tls-ca and --token-file on every subcommand that
// talks to a server (reconstruct, jobs, health).
#ifndef MEMBRANE_CLIENT_SERVER_CONNECTION_H_
#define MEMBRANE_CLIENT_SERVER_CONNECTION_H_

#include <memory>
#include <string>

#include <grpcpp/channel.h>
#include <grpcpp/client_context.h>
#include <grpcpp/support/status.h>

#include "absl/status/statusor.h"
#include "absl/time/time.h"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace membrane::client {

// The flags as typed.
struct ConnectionFlags {
  std::string server = "127.0.0.1:50051";
  std::string token_file;  // empty: no token
  std::string tls_ca;      // empty: plaintext
};

// The flags with the files read.
struct ServerConnection {
  std::string address;     // HOST:PORT, also the name in error lines
  std::string token;       // sent as "authorization: Bearer <token>"; empty: nothing sent
  std::string tls_ca_pem;  // root certificates the server's must chain to; empty: plaintext
};

// Adds --server, --token-file and --tls-ca to `app`, parsed into `flags` (which must outlive
// the parse). Returns the --server option, for a caller that makes it exclusive with another.
CLI::Option* AddConnectionFlags(CLI::App& app, ConnectionFlags& flags);

// Reads the files `flags` names. The token file holds the token on its first line (surrounding
// whitespace dropped). InvalidArgument naming the flag and file when a file cannot be read,
// the token is empty or holds characters a header cannot carry, or the CA file holds no PEM
// certificate.
absl::StatusOr<ServerConnection> LoadServerConnection(const ConnectionFlags& flags);

// A channel to `connection.address`: TLS verified against `tls_ca_pem` when set, plaintext
// otherwise (loopback, or a network the operator trusts). It reconnects at most a second
// after losing its server.
std::shared_ptr<grpc::Channel> Connect(const ServerConnection& connection);

// Adds the bearer token, when there is one, to a call's metadata. Every call of the
// membrane.v1 API needs it on a server started with --token-file; health checks do not.
void Authorize(grpc::ClientContext& context, const ServerConnection& connection);

// Adds the replica `job_id` names (proto/job_routing.h), when it names one, to a call's
// metadata, so that a balancer sends the call to the replica holding the job. For every call
// that names a job: GetJob, WatchJob (re-attach too), CancelJob.
void RouteToJob(grpc::ClientContext& context, const std::string& job_id);

// Cancels job `job_id` on `connection`'s server (CancelJob, authorized and routed to the job's
// replica), waiting at most `timeout` for the answer; the call's status.
grpc::Status CancelRemoteJob(const ServerConnection& connection, const std::string& job_id,
                             absl::Duration timeout);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_SERVER_CONNECTION_H_
