// What `membrane reconstruct --server` sends besides the Draco bytes, decided on the cloud as
// read, so that the server's mesh is --local's: the default voxel size (a quantized upload
// merges close points, and formula (1) counts distinct points, so the server would otherwise
// pick a coarser grid: 3M points, 693^3 instead of 712^3; and the noise is read before the
// quantization moves the points) and enough position bits for that voxel.
#ifndef MEMBRANE_CLIENT_UPLOAD_PLAN_H_
#define MEMBRANE_CLIENT_UPLOAD_PLAN_H_

#include <optional>
#include <string>

#include "core/geometry/point_cloud.h"

namespace membrane::client {

// The upload's grid step is at most 1/kStepsPerVoxel of the voxel: each coordinate moves by at
// most 1/16 of a voxel.
inline constexpr int kStepsPerVoxel = 8;
// The default bits (contracts.md's --quantization), kept wherever they are fine enough.
inline constexpr int kDefaultUploadBits = 11;

struct UploadPlan {
  double voxel_size = 0;  // 0: the cloud is degenerate, and the server will say so
  int bits = kDefaultUploadBits;
  // NoiseVoxelNote of the plan: the server gets the size as given and says nothing of it.
  std::optional<std::string> noise_note;
};

// For `cloud` and the voxel size asked for (0: the default, as PlanGrid plans Voxelize's):
// that voxel size, and the fewest bits from kDefaultUploadBits up (at most 30) whose step over
// the cloud's largest side is at most voxel / kStepsPerVoxel. A degenerate cloud (no points,
// coplanar, ...) gives voxel_size 0 and the default bits.
UploadPlan PlanUpload(const PointCloud& cloud, double requested_voxel_size);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_UPLOAD_PLAN_H_
