// Text a client sent (job ids, parameter strings, metadata values), made fit to be written
// into a log line or echoed back in a status message.
#ifndef MEMBRANE_SERVER_CLIENT_TEXT_H_
#define MEMBRANE_SERVER_CLIENT_TEXT_H_

#include <cstddef>
#include <string>

#include "absl/strings/string_view.h"

namespace membrane::server {

// How much of a client's text a status or a log line quotes: enough to recognise a job id or
// a misspelt word, while a status stays far under gRPC's 8 KB metadata limit (its message
// travels percent-encoded in a trailer, so one byte may take three).
inline constexpr size_t kClientTextBytes = 80;

// `text` with every byte outside printable ASCII (control bytes such as ESC and NUL, DEL, and
// bytes of UTF-8 sequences) and the backslash written as \xHH or \\, so that it cannot move a
// terminal's cursor or split a log line; cut after `max_bytes` of `text`, the cut saying how
// long the whole was: "abc...(3145728 bytes)". At most 4 * max_bytes + 24 bytes long.
std::string ClientText(absl::string_view text, size_t max_bytes = kClientTextBytes);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_CLIENT_TEXT_H_
