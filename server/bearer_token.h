// The bearer-token check of membraned --token-file: every membrane.v1 call must carry
// "authorization: Bearer <token>" of one of the server's clients. Health and reflection stay
// open, so that container probes and grpcurl's listing need no secret.
#ifndef MEMBRANE_SERVER_BEARER_TOKEN_H_
#define MEMBRANE_SERVER_BEARER_TOKEN_H_

#include <optional>
#include <vector>

#include <grpcpp/server_context.h>
#include <grpcpp/support/status.h>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "server/client_tokens.h"

namespace membrane::server {

// The client whose token the call's "authorization" metadata carries ("Bearer <token>", the
// scheme in any case, RFC 7235); null when `clients` is empty (no tokens configured: every
// call is let in). UNAUTHENTICATED saying what is missing or wrong otherwise. Every token is
// compared, each in the same time wherever the first difference is, so that timing reveals
// neither a prefix of a token nor which client it nearly matched.
absl::StatusOr<const ClientToken*> CheckBearerToken(const grpc::ServerContext& context,
                                                    const std::vector<ClientToken>& clients);

// The same check of an "Authorization" header's value (nullopt: the header is absent), for
// the HTTP API (membraned --http-listen).
absl::StatusOr<const ClientToken*> CheckAuthorization(
    std::optional<absl::string_view> authorization, const std::vector<ClientToken>& clients);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_BEARER_TOKEN_H_
