// Options of the synthetic point-cloud generators (`membrane synth`).
#ifndef MEMBRANE_CORE_SYNTH_SYNTH_OPTIONS_H_
#define MEMBRANE_CORE_SYNTH_SYNTH_OPTIONS_H_

#include <cstdint>
#include <string>

#include "absl/status/status.h"

namespace membrane {

// Allowed ranges, inclusive. Shared by validation and by the messages that quote them.
inline constexpr int64_t kMinSynthPoints = 1;
inline constexpr int64_t kMaxSynthPoints = 50'000'000;
inline constexpr double kMaxDensityRatio = 1000.0;
inline constexpr int kMaxHoles = 100;
inline constexpr double kMaxNoise = 0.1;
inline constexpr double kMinCubeVoxelSize = 0.001;
inline constexpr double kMaxCubeVoxelSize = 1.0;
inline constexpr int kMaxCubeHoleSize = 1000;

struct SynthOptions {
  // One of SynthShapeNames().
  std::string shape;
  // Number of points of the cloud, exactly; [1, 50,000,000].
  int64_t points = 100000;
  // Densest : sparsest surface density along a random direction (SynthLayout; the exact
  // profile is DensityRamp's); [1, 1000]. 1 = uniform.
  double density_ratio = 1.0;
  // Number of circular patches (radius kHoleRadius = 0.15) left unsampled, at random places
  // (SynthLayout); [0, 100]. Smooth shapes only.
  int holes = 0;
  // Standard deviation of a Gaussian displacement along the surface normal, model units;
  // [0, 0.1]. Smooth shapes only.
  double noise = 0.0;
  // Seed of every random choice: the same options give the same cloud.
  uint64_t seed = 1;
  // cube-pinholes only: the voxel edge the cloud is built for, model units; 0 picks the size
  // that gives about 4 points per wall voxel for `points`, else [0.001, 1].
  double voxel_size = 0.0;
  // cube-pinholes only: each of the two holes is hole_size x hole_size voxels; >= 1 and at most
  // the cube's side in voxels minus 2 (checked by CubePinholesGridFor).
  int hole_size = 1;
};

// Checks the shape-independent ranges above (the shape name and the shape-specific rules are
// checked by SynthesizeShape). Returns InvalidArgument naming the first bad field, its value
// and its allowed range; NaN is out of every range.
absl::Status ValidateSynthOptions(const SynthOptions& options);

}  // namespace membrane

#endif  // MEMBRANE_CORE_SYNTH_SYNTH_OPTIONS_H_
