#include "client/upload_plan.h"

#include <algorithm>
#include <cmath>

#include "absl/status/statusor.h"
#include "core/pipeline/memory_estimate.h"
#include "core/pipeline/noise_voxel_note.h"

namespace membrane::client {

UploadPlan PlanUpload(const PointCloud& cloud, double requested_voxel_size) {
  UploadPlan plan;
  absl::StatusOr<PlannedGrid> grid =
      PlanGrid(cloud, VoxelizeOptions{.voxel_size = requested_voxel_size});
  if (!grid.ok()) return plan;
  plan.voxel_size = grid->voxel_size;
  plan.noise_note = NoiseVoxelNote(*grid);
  plan.box = grid->bounds;
  const auto extent = grid->bounds.Extent();
  const double range = std::max({extent[0], extent[1], extent[2]});
  // Draco's step is range / (2^bits - 1).
  const double steps = range / plan.voxel_size * kStepsPerVoxel;
  while (plan.bits < 30 && std::ldexp(1.0, plan.bits) - 1 < steps) ++plan.bits;
  return plan;
}

}  // namespace membrane::client
