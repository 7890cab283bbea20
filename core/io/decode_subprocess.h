// Decoding untrusted Draco point clouds in a child process. Debian's Draco 1.5.5 decoder has
// crashes and allocation blowups on crafted input (fuzzing found 30 bytes that make it allocate
// 2.8 GB from a count inside the coded data); in a child with RLIMIT_AS, RLIMIT_CPU and a
// wall-clock timeout, such input costs one refused file instead of the server's memory or the
// user's machine. The child runs RunDecodeHelper (decode_helper.h), and is killed
// (PR_SET_PDEATHSIG) when the thread that started it dies, so that a server killed outright
// leaves no decoder behind.
#ifndef MEMBRANE_CORE_IO_DECODE_SUBPROCESS_H_
#define MEMBRANE_CORE_IO_DECODE_SUBPROCESS_H_

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/base/progress_meter.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/triangle_mesh.h"

namespace membrane {

struct DecodeLimits {
  // The helper's command line before the arguments RunDecodeHelper takes: a membrane-decode
  // binary, or a program that passes its remaining arguments to RunDecodeHelper.
  std::vector<std::string> helper;
  double timeout_seconds = 30;       // wall clock; also RLIMIT_CPU (rounded up)
  int64_t memory_bytes = 4LL << 30;  // RLIMIT_AS of the child
  int64_t max_points = 50'000'000;   // the helper refuses larger clouds before decoding them
  bool accept_mesh = false;          // a Draco mesh gives its vertices instead of an error
  // Threads the child decodes an upload's parts on (RLIMIT_CPU counts them all: the parts'
  // CPU time is about one part's).
  int threads = 1;
  std::string subject = "the data";  // messages say "<subject> could not be decoded: ..."
};

// The point cloud in Draco `bytes`, decoded by `limits.helper` in a child process (bytes on
// its stdin, points on its stdout). A Draco mesh is refused unless limits.accept_mesh.
// `part_bytes`, when not empty, cuts the bytes into Draco point clouds decoded on
// limits.threads in the one child (DecodeDracoPointCloudParts, draco_parts.h: the points part
// after part; the parts' errors name the part), under the same limits as one cloud.
// The child's output is checked as a file's would be (finite coordinates). Errors: InvalidArgument naming the cause for bytes the helper rejects
// (not Draco, a mesh, non-finite coordinates, no points) or output that fails those checks; ResourceExhausted for more than max_points;
// InvalidArgument also for a child that crashes (with the signal), runs out of memory or CPU,
// or exceeds the timeout; Cancelled when `cancel` fires (the child is killed within 50 ms);
// Internal when the helper cannot be started or run (exit status 127). `progress` counts the
// decode as DecodeProgress does (decode_progress.h: the child's CPU time, then its points),
// and ends at its end when the cloud is returned.
absl::StatusOr<PointCloud> DecodeInSubprocess(absl::string_view bytes, const DecodeLimits& limits,
                                              const CancelToken& cancel,
                                              ProgressRange progress = ProgressRange(),
                                              absl::Span<const uint64_t> part_bytes = {});

// The triangle mesh in Draco `bytes` (as DecodeDracoMesh gives it), decoded the same way;
// limits.max_points bounds its vertices and limits.accept_mesh is not used; the output's face
// indices are checked too. Errors as DecodeInSubprocess's, with "a Draco point cloud" among
// the rejected inputs.
absl::StatusOr<TriangleMesh> DecodeMeshInSubprocess(absl::string_view bytes,
                                                    const DecodeLimits& limits,
                                                    const CancelToken& cancel,
                                                    ProgressRange progress = ProgressRange());

}  // namespace membrane

#endif  // MEMBRANE_CORE_IO_DECODE_SUBPROCESS_H_
