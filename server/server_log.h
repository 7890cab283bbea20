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
// write, so lines of concurrent jobs never interleave. Values with spaces or quotes are
// quoted.
void LogEvent(absl::string_view event,
              std::initializer_list<std::pair<absl::string_view, std::string>> fields);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_SERVER_LOG_H_
