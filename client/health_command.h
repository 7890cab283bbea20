// `membrane health --server HOST:PORT`: the grpc.health.v1 check, for container probes.
#ifndef MEMBRANE_CLIENT_HEALTH_COMMAND_H_
#define MEMBRANE_CLIENT_HEALTH_COMMAND_H_

#include "client/command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace membrane::client {

// Adds `health` to `parent`. Its action asks the server's health service (overall status,
// within --timeout seconds, default 5) and prints SERVING, NOT_SERVING, ... on stdout. OK
// only when SERVING; Unavailable "server HOST:PORT is NOT_SERVING" otherwise, or the call's
// status (Unavailable, DeadlineExceeded) when the server cannot be reached.
Command AddHealthCommand(CLI::App& parent);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_HEALTH_COMMAND_H_
