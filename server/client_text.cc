#include "server/client_text.h"

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace membrane::server {

std::string ClientText(absl::string_view text, size_t max_bytes) {
  const absl::string_view kept = text.substr(0, max_bytes);
  std::string out;
  out.reserve(kept.size() + 24);
  for (const char ch : kept) {
    const auto byte = static_cast<unsigned char>(ch);
    if (byte == '\\') {
      out += "\\\\";
    } else if (byte < 0x20 || byte > 0x7e) {
      absl::StrAppendFormat(&out, "\\x%02x", byte);
    } else {
      out += ch;
    }
  }
  if (kept.size() < text.size()) absl::StrAppend(&out, "...(", text.size(), " bytes)");
  return out;
}

}  // namespace membrane::server
