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
#include "core/pipeline/grid_box.h"
#include "core/pipeline/reconstruction_options.h"

namespace membrane::client {

// The upload's grid step is at most 1/kStepsPerVoxel of the voxel: each coordinate moves by at
// most a step (SnapKeepingVoxels), what the server allows between the points and the box the
// client sends (grid_box.h).
inline constexpr int kStepsPerVoxel = kGridBoxStepsPerVoxel;
// The default bits (contracts.md's --quantization), kept wherever they are fine enough.
inline constexpr int kDefaultUploadBits = 11;

struct UploadPlan {
  double voxel_size = 0;  // 0: the cloud is degenerate, and the server will say so
  int bits = kDefaultUploadBits;
  // NoiseVoxelNote of the plan: the server gets the size as given and says nothing of it.
  std::optional<std::string> noise_note;
  // The box the voxel was planned on (CheckedBounds of the cloud as read), for the server to
  // plan its grid on (Parameters.grid_box); none when voxel_size is 0.
  std::optional<Box3d> box;
  // When the voxel was the default: formula (1)'s size and the points' noise it was planned
  // from, for the server to report and treat the voxel as --local does (Parameters.voxel_plan).
  std::optional<VoxelPlanNote> voxel_plan;
};

// For `cloud` and the voxel size asked for (0: the default, as PlanGrid plans Voxelize's):
// that voxel size, its box, and the fewest bits from kDefaultUploadBits up (at most 30) whose
// step over the cloud's largest side is at most voxel / kStepsPerVoxel. A degenerate cloud (no
// points, coplanar, ...) gives voxel_size 0, no box and the default bits. Formula (1)'s
// distinct count runs on `threads`; the plan is the same for any number.
UploadPlan PlanUpload(const PointCloud& cloud, double requested_voxel_size, int threads = 1);

}  // namespace membrane::client

#endif  // MEMBRANE_CLIENT_UPLOAD_PLAN_H_
