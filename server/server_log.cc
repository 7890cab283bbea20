#include "server/server_log.h"

#include <unistd.h>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_replace.h"
#include "absl/time/clock.h"

namespace membrane::server {
namespace {

std::string Quoted(const std::string& value) {
  if (!value.empty() && !absl::StrContains(value, ' ') && !absl::StrContains(value, '"') &&
      !absl::StrContains(value, '\n')) {
    return value;
  }
  return absl::StrCat("\"",
                      absl::StrReplaceAll(value, {{"\\", "\\\\"}, {"\"", "\\\""}, {"\n", " "}}),
                      "\"");
}

}  // namespace

void LogEvent(absl::string_view event,
              std::initializer_list<std::pair<absl::string_view, std::string>> fields) {
  std::string line =
      absl::StrFormat("ts=%.3f event=%s", absl::ToUnixMicros(absl::Now()) / 1e6, event);
  for (const auto& [key, value] : fields) absl::StrAppend(&line, " ", key, "=", Quoted(value));
  line += '\n';
  // One write(2): atomic for lines of this size on a pipe or terminal.
  (void)!write(STDERR_FILENO, line.data(), line.size());
}

}  // namespace membrane::server
