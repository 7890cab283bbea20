// The clients a membraned knows (--token-file): each a name, the bearer token it sends, and
// whether it is an operator, who sees every client's jobs.
#ifndef MEMBRANE_SERVER_CLIENT_TOKENS_H_
#define MEMBRANE_SERVER_CLIENT_TOKENS_H_

#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace membrane::server {

struct ClientToken {
  std::string name;   // in the log and in Job.client; never the token
  std::string token;  // sent as "authorization: Bearer <token>"
  bool is_operator = false;  // sees, cancels and fetches every client's jobs
};

// The clients of `path`, a file or a directory of files. A file holds either one bare token
// on its first line (the shared-token format; the rest of the file is ignored), which is the
// client named after the file (or "token" when the file's name is no client name), or lines "NAME TOKEN" and "NAME TOKEN operator" (blank lines
// and lines starting with '#' skipped). A directory (a Kubernetes secret mounted as one) is
// read file by file, following symbolic links and skipping names that start with '.'.
// Names are 1-64 of [A-Za-z0-9._-]; tokens visible ASCII without spaces. InvalidArgument
// naming the file (and line) for an unreadable file, a malformed line, a name or a token given
// twice, or no client at all.
absl::StatusOr<std::vector<ClientToken>> ReadClientTokens(const std::string& path);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_CLIENT_TOKENS_H_
