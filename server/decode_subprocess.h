// Decoding untrusted Draco uploads in a child process. Debian's Draco 1.5.5 decoder has known
// crashes and allocation blowups on crafted input; in a child with RLIMIT_AS, RLIMIT_CPU and
// a wall-clock timeout, such input costs one failed job instead of the server.
#ifndef MEMBRANE_SERVER_DECODE_SUBPROCESS_H_
#define MEMBRANE_SERVER_DECODE_SUBPROCESS_H_

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "core/engine/cancel_token.h"
#include "core/geometry/point_cloud.h"

namespace membrane::server {

struct DecodeLimits {
  std::string helper_path;           // the membrane-decode binary
  double timeout_seconds = 30;       // wall clock; also RLIMIT_CPU (rounded up)
  int64_t memory_bytes = 4LL << 30;  // RLIMIT_AS of the child
  int64_t max_points = 50'000'000;   // the helper refuses larger clouds before decoding them
};

// The point cloud in Draco `bytes`, decoded by `limits.helper_path` in a child process (bytes
// on its stdin, points on its stdout). A Draco mesh is refused (a cloud is expected).
// Errors: InvalidArgument naming the cause for bytes the helper rejects (not Draco, a mesh,
// non-finite coordinates, no points); ResourceExhausted for more than max_points; InvalidArgument
// also for a child that crashes (with
// the signal), runs out of memory or CPU, or exceeds the timeout; Cancelled when `cancel`
// fires (the child is killed within 50 ms); Internal when the helper cannot be started.
absl::StatusOr<PointCloud> DecodeInSubprocess(absl::string_view bytes, const DecodeLimits& limits,
                                              const CancelToken& cancel);

}  // namespace membrane::server

#endif  // MEMBRANE_SERVER_DECODE_SUBPROCESS_H_
