#include "client/upload_plan.h"

#include <algorithm>
#include <cmath>

#include "absl/status/statusor.h"
#include "core/pipeline/memory_estimate.h"
#include "core/pipeline/noise_voxel_note.h"
#include "core/geometry/position_grid.h"

namespace membrane::client {

UploadPlan PlanUpload(const PointCloud& cloud, double requested_voxel_size, int threads) {
  UploadPlan plan;
  absl::StatusOr<PlannedGrid> grid =
      PlanGrid(cloud, VoxelizeOptions{.voxel_size = requested_voxel_size, .threads = threads});
  if (!grid.ok()) return plan;
  plan.voxel_size = grid->voxel_size;
  plan.noise_note = NoiseVoxelNote(*grid);
  plan.box = grid->bounds;
  if (grid->formula_voxel_size > 0) {
    plan.voxel_plan = VoxelPlanNote{grid->formula_voxel_size, grid->noise.sigma};
  }
  // Draco's step is range / (2^bits - 1), over the box the upload is quantized in: the
  // cloud's, widened for Draco's option text (GridOverBox, as SnapKeepingVoxels takes it).
  const double range =
      GridOverBox(plan.bits, grid->bounds.min, grid->bounds.max, 0.0).box.range;
  const double steps = range / plan.voxel_size * kStepsPerVoxel;
  while (plan.bits < 30 && std::ldexp(1.0, plan.bits) - 1 < steps) ++plan.bits;
  return plan;
}

}  // namespace membrane::client
