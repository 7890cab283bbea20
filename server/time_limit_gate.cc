#include "server/time_limit_gate.h"

#include <string>

#include "absl/strings/str_format.h"
#include "core/pipeline/time_estimate.h"

namespace membrane::server {

absl::Status CheckEncodeTime(const v1::Parameters& parameters, double max_job_seconds) {
  const double encode = EncodeSecondsFloor(parameters.quantization());
  if (max_job_seconds <= 0 || encode <= max_job_seconds) return absl::OkStatus();
  return absl::ResourceExhaustedError(absl::StrFormat(
      "quantization %d takes at least %.1f s to encode (Draco's tables grow as 2^bits), over "
      "the server's --max-job-seconds of %g s; use fewer bits",
      parameters.quantization(), encode, max_job_seconds));
}

absl::Status TimeLimitGate::AdmitGrid(const PlannedGrid& grid, int64_t points,
                                      const CancelToken& cancel) {
  const double floor = GridSecondsFloor(grid.voxels, threads_) + EncodeSecondsFloor(quantization_bits_);
  if (max_seconds_ > 0 && floor > max_seconds_) {
    const std::string encoding =
        quantization_bits_ > 0 ? absl::StrFormat(", encoded at %d bits", quantization_bits_) : "";
    return absl::ResourceExhaustedError(absl::StrFormat(
        "the job takes at least %.1f s by the estimate (a grid of %d voxels at voxel size "
        "%g%s), over the server's --max-job-seconds of %g s; use a larger voxel_size",
        floor, grid.voxels, grid.voxel_size, encoding, max_seconds_));
  }
  return inner_.AdmitGrid(grid, points, cancel);
}

}  // namespace membrane::server
