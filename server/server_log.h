// Structured log lines on stderr: one line per job lifecycle event, key=value pairs, so that
// `grep job=ab12` or a log shipper can follow a job.
#ifndef MEMBRANE_SERVER_SERVER_LOG_H_
#define MEMBRANE_SERVER_SERVER_LOG_H_

#include <initializer_list>
#include <string>
#include <utility>

#include "absl/strings/string_view.h"

namespace membrane::server {

// Writes "ts=<unix seconds> event=<event> k1=v1 k2=v2 ..." and a newline to stderr in one
// write, so lines of concurrent jobs never interleave. A value is cut after 2 KiB (saying its
// length), its control bytes are written as \xHH, and it is quoted ("...", with \" and \\) when
// it holds a space, a quote, a backslash or such a byte, or is empty.
void LogEvent(absl::string_view event,
              std::initializer_list<std::pair<absl::string_view, std::string>> fields);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_SERVER_LOG_H_
