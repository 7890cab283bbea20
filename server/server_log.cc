#include "server/server_log.h"

#include <unistd.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/time/clock.h"

namespace membrane::server {
namespace {

// A value longer than this is cut: a log line stays one write, and one call cannot fill the
// disk with what it sent (values quoting a client are bounded before, see client_text.h).
constexpr size_t kMaxValueBytes = 2048;

// `value` as one token of the line: cut at kMaxValueBytes, control bytes written as \xHH
// (a newline as a space), quotes and backslashes escaped; quoted when it is empty or any of
// that happened, or it holds a space, so that an unquoted value is always the bytes as they
// are.
std::string Quoted(absl::string_view value) {
  const absl::string_view kept = value.substr(0, kMaxValueBytes);
  std::string text;
  text.reserve(kept.size());
  bool quote = kept.empty();
  for (const char ch : kept) {
    const auto byte = static_cast<unsigned char>(ch);
    if (ch == '\n') {
      text += ' ';
      quote = true;
    } else if (byte < 0x20 || byte == 0x7f) {
      absl::StrAppendFormat(&text, "\\x%02x", byte);
      quote = true;
    } else if (ch == '"' || ch == '\\') {
      text += '\\';
      text += ch;
      quote = true;
    } else {
      text += ch;
      quote = quote || ch == ' ';
    }
  }
  if (kept.size() < value.size()) {
    absl::StrAppend(&text, "...(", value.size(), " bytes)");
    quote = true;
  }
  return quote ? absl::StrCat("\"", text, "\"") : text;
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
