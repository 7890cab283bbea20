#include "core/synth/synth_options.h"

#include "absl/strings/str_format.h"

namespace membrane {
namespace {

// Every comparison with NaN is false, so NaN is out of every range.
bool InRange(double v, double lo, double hi) { return v >= lo && v <= hi; }

}  // namespace

absl::Status ValidateSynthOptions(const SynthOptions& o) {
  if (o.points < kMinSynthPoints || o.points > kMaxSynthPoints) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "points = %d is out of range: must be in [%d, %d]", o.points, kMinSynthPoints,
        kMaxSynthPoints));
  }
  if (!InRange(o.density_ratio, 1.0, kMaxDensityRatio)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "density_ratio = %g is out of range: must be in [1, %g]", o.density_ratio,
        kMaxDensityRatio));
  }
  if (o.holes < 0 || o.holes > kMaxHoles) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "holes = %d is out of range: must be in [0, %d]", o.holes, kMaxHoles));
  }
  if (!InRange(o.noise, 0.0, kMaxNoise)) {
    return absl::InvalidArgumentError(
        absl::StrFormat("noise = %g is out of range: must be in [0, %g]", o.noise, kMaxNoise));
  }
  if (o.voxel_size != 0.0 && !InRange(o.voxel_size, kMinCubeVoxelSize, kMaxCubeVoxelSize)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "voxel_size = %g is out of range: must be 0 (automatic) or in [%g, %g]", o.voxel_size,
        kMinCubeVoxelSize, kMaxCubeVoxelSize));
  }
  if (o.hole_size < 1 || o.hole_size > kMaxCubeHoleSize) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "hole_size = %d is out of range: must be in [1, %d]", o.hole_size, kMaxCubeHoleSize));
  }
  return absl::OkStatus();
}

}  // namespace membrane
