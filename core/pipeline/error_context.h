// How the pipeline's own errors name what its caller can change. The core's messages say what
// is wrong with the cloud or the grid; which file it came from and which flag or job field
// changes the grid are the caller's words.
#ifndef MEMBRANE_CORE_PIPELINE_ERROR_CONTEXT_H_
#define MEMBRANE_CORE_PIPELINE_ERROR_CONTEXT_H_

#include <string>

#include "absl/status/status.h"

namespace membrane {

struct ErrorContext {
  // Put before the message of an InvalidArgument (a degenerate cloud, options out of range,
  // no surface): "scan.ply: " names the input of `membrane reconstruct --local`.
  std::string invalid_argument_prefix;
  // Put after the message of a ResourceExhausted (a grid over a voxel budget or the machine's
  // memory): which flags or job fields give a smaller grid.
  std::string resource_exhausted_advice;
};

// `status` with `context` added by its code as above; other codes (Cancelled, Internal, ...)
// and OK unchanged.
absl::Status WithErrorContext(const absl::Status& status, const ErrorContext& context);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_ERROR_CONTEXT_H_
