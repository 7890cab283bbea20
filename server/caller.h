// Who made a call (gRPC or HTTP), as --token-file names it, and which jobs that caller sees:
// its own, or every job for an operator and on a server without tokens.
#ifndef MEMBRANE_SERVER_CALLER_H_
#define MEMBRANE_SERVER_CALLER_H_

#include <string>

#include "server/client_tokens.h"
#include "server/job.h"

namespace membrane::server {

struct Caller {
  std::string name;        // the token's client; empty on a server without tokens
  bool sees_all = false;   // an operator, or a server without tokens
  // Whether `job` is this caller's to see, watch, fetch and cancel.
  bool Sees(const Job& job) const { return sees_all || job.client() == name; }
  // For the log: the name, never the token; "-" without tokens.
  std::string LogName() const { return name.empty() ? "-" : name; }
  // The reason a cancel by this caller gives `job`: the job's own client is "the client"; an
  // operator says who stopped it.
  std::string CancelReason(const Job& job) const {
    return name == job.client() ? std::string("cancelled by the client")
                                : "cancelled by operator '" + name + "'";
  }
};

// The caller a matched token names (CheckBearerToken, CheckAuthorization); null, from a server
// without tokens, is one anonymous client who sees every job.
inline Caller CallerOf(const ClientToken* client) {
  if (client == nullptr) return Caller{"", true};
  return Caller{client->name, client->is_operator};
}

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_CALLER_H_
