// The optional shared-secret check of membraned --token-file: every membrane.v1 call must
// carry "authorization: Bearer <token>". Health and reflection stay open, so that container
// probes and grpcurl's listing need no secret.
#ifndef MEMBRANE_SERVER_BEARER_TOKEN_H_
#define MEMBRANE_SERVER_BEARER_TOKEN_H_

#include "absl/strings/string_view.h"

#include <grpcpp/server_context.h>
#include <grpcpp/support/status.h>

namespace membrane::server {

// OK when `expected` is empty (no token configured) or the call's "authorization" metadata is
// exactly "Bearer <expected>"; UNAUTHENTICATED saying what is missing or wrong otherwise. The
// comparison takes the same time wherever the first difference is, so that timing does not
// reveal a prefix of the token.
grpc::Status CheckBearerToken(const grpc::ServerContext& context, absl::string_view expected);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_BEARER_TOKEN_H_
