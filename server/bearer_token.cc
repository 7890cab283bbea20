#include "server/bearer_token.h"

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"

namespace membrane::server {
namespace {

// Equal length and bytes, in time that depends on the lengths only.
bool ConstantTimeEqual(absl::string_view a, absl::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  }
  return diff == 0;
}

}  // namespace

absl::StatusOr<const ClientToken*> CheckBearerToken(const grpc::ServerContext& context,
                                                    const std::vector<ClientToken>& clients) {
  const auto& metadata = context.client_metadata();
  const auto found = metadata.find("authorization");
  if (found == metadata.end()) return CheckAuthorization(std::nullopt, clients);
  return CheckAuthorization(absl::string_view(found->second.data(), found->second.size()),
                            clients);
}

absl::StatusOr<const ClientToken*> CheckAuthorization(
    std::optional<absl::string_view> authorization, const std::vector<ClientToken>& clients) {
  if (clients.empty()) return nullptr;
  if (!authorization.has_value()) {
    return absl::UnauthenticatedError(
        "this server needs a bearer token (\"authorization: Bearer <token>\"; "
        "membrane --token-file FILE)");
  }
  absl::string_view given = *authorization;
  // RFC 7235 auth schemes are case-insensitive: "bearer", "BEARER" and "Bearer" are one scheme.
  constexpr absl::string_view kScheme = "bearer ";
  const bool bearer = absl::StartsWithIgnoreCase(given, kScheme);
  if (bearer) given.remove_prefix(kScheme.size());
  const ClientToken* match = nullptr;
  for (const ClientToken& client : clients) {
    if (ConstantTimeEqual(given, client.token)) match = &client;
  }
  if (!bearer || match == nullptr) {
    return absl::UnauthenticatedError("the bearer token is not this server's");
  }
  return match;
}

}  // namespace membrane::server
