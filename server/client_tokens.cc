#include "server/client_tokens.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "absl/container/flat_hash_set.h"
#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "core/io/file_bytes.h"

namespace membrane::server {
namespace {

bool IsName(absl::string_view name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](char ch) {
    return absl::ascii_isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' ||
           ch == '-';
  });
}

bool IsToken(absl::string_view token) {
  return !token.empty() && std::all_of(token.begin(), token.end(), [](char ch) {
    return ch >= 0x21 && ch <= 0x7e;
  });
}

// The clients of one file; a bare token is the client `default_name`.
absl::Status ReadFile(const std::string& path, const std::string& default_name,
                      std::vector<ClientToken>& out) {
  absl::StatusOr<std::string> bytes = ReadFileBytes(path);
  if (!bytes.ok()) return absl::InvalidArgumentError(bytes.status().message());
  int line_number = 0;
  bool any = false;
  for (absl::string_view line : absl::StrSplit(*bytes, '\n')) {
    ++line_number;
    line = absl::StripAsciiWhitespace(line);
    if (line.empty() || line.front() == '#') continue;
    const std::vector<absl::string_view> fields =
        absl::StrSplit(line, absl::ByAnyChar(" \t"), absl::SkipEmpty());
    const std::string where = absl::StrCat(path, " line ", line_number);
    if (fields.size() == 1 && !any) {
      // The shared-token format: the token alone on the first line.
      if (!IsToken(fields[0])) {
        return absl::InvalidArgumentError(
            absl::StrCat("the token in ", where, " holds a non-printable character"));
      }
      out.push_back({IsName(default_name) ? default_name : "token", std::string(fields[0]),
                     false});
      return absl::OkStatus();
    }
    if (fields.size() < 2 || fields.size() > 3 || (fields.size() == 3 && fields[2] != "operator")) {
      return absl::InvalidArgumentError(
          absl::StrCat(where, " is not \"NAME TOKEN\" or \"NAME TOKEN operator\""));
    }
    if (!IsName(fields[0])) {
      return absl::InvalidArgumentError(absl::StrCat(
          where, ": the client name must be 1-64 letters, digits, '.', '_' or '-'"));
    }
    if (!IsToken(fields[1])) {
      return absl::InvalidArgumentError(
          absl::StrCat("the token in ", where, " holds a non-printable character"));
    }
    out.push_back({std::string(fields[0]), std::string(fields[1]), fields.size() == 3});
    any = true;
  }
  if (!any) return absl::InvalidArgumentError(absl::StrCat(path, " holds no token"));
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<std::vector<ClientToken>> ReadClientTokens(const std::string& path) {
  std::vector<ClientToken> clients;
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    std::vector<std::string> files;
    for (const auto& entry : std::filesystem::directory_iterator(path, error)) {
      const std::string name = entry.path().filename().string();
      // Kubernetes keeps its own ..data links and timestamped directories beside the keys.
      if (name.empty() || name.front() == '.') continue;
      if (!std::filesystem::is_regular_file(entry.path(), error)) continue;
      files.push_back(name);
    }
    if (error) {
      return absl::InvalidArgumentError(
          absl::StrCat("cannot list ", path, ": ", error.message()));
    }
    std::sort(files.begin(), files.end());
    for (const std::string& name : files) {
      if (absl::Status s = ReadFile(absl::StrCat(path, "/", name), name, clients); !s.ok()) {
        return s;
      }
    }
    if (clients.empty()) return absl::InvalidArgumentError(absl::StrCat(path, " holds no token"));
  } else {
    const std::string file_name = std::filesystem::path(path).filename().string();
    if (absl::Status s = ReadFile(path, file_name, clients); !s.ok()) return s;
  }
  absl::flat_hash_set<std::string> names, tokens;
  for (const ClientToken& c : clients) {
    if (!names.insert(c.name).second) {
      return absl::InvalidArgumentError(
          absl::StrCat(path, ": the client name '", c.name, "' is given twice"));
    }
    if (!tokens.insert(c.token).second) {
      return absl::InvalidArgumentError(absl::StrCat(
          path, ": client '", c.name, "' has the token of another (each needs its own)"));
    }
  }
  return clients;
}

}  // namespace membrane::server
