#include "core/pipeline/memory_estimate.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_format.h"
#include "core/engine/voxel_grid.h"

namespace membrane {
namespace {

constexpr int64_t kBytesPerVoxel = 6;
// The decoded cloud, the pipeline's copy for the surface fit, and slack for the mesh.
constexpr int64_t kBytesPerPoint = 4 * sizeof(Point3f);
constexpr int64_t kBytesPerBoundaryVoxel = 1000;

}  // namespace

absl::StatusOr<PlannedGrid> PlanGrid(const PointCloud& cloud, const VoxelizeOptions& voxelize) {
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  if (!bounds.ok()) return bounds.status();
  PlannedGrid plan;
  plan.bounds = *bounds;
  plan.voxel_size =
      voxelize.voxel_size > 0 ? voxelize.voxel_size : FormulaVoxelSize(*bounds, cloud.points);
  double voxels = 1;
  for (const double side : bounds->Extent()) {
    voxels *= std::floor(side / plan.voxel_size) + 1 + 2 * VoxelGrid::kPadding;
  }
  plan.voxels = static_cast<int64_t>(std::min(voxels, 9e18));
  plan.bytes = GridBytesEstimate(std::min(plan.voxels, voxelize.voxel_budget),
                                 static_cast<int64_t>(cloud.points.size()));
  return plan;
}

int64_t GridBytesEstimate(int64_t voxels, int64_t points) {
  // In double: a planned grid can hold 9e18 voxels before any budget caps it.
  const double bytes = static_cast<double>(voxels) * kBytesPerVoxel +
                       static_cast<double>(points) * kBytesPerPoint;
  return static_cast<int64_t>(std::min(bytes, 9e18));
}

int64_t SurfaceBytesEstimate(const MembraneCounts& membrane) {
  return kBytesPerBoundaryVoxel * membrane.membrane_voxels();
}

std::string BytesText(int64_t bytes) {
  static constexpr const char* kUnits[] = {"bytes", "KB", "MB", "GB", "TB", "PB", "EB"};
  double value = static_cast<double>(bytes);
  int unit = 0;
  while (std::abs(value) >= 999.5 && unit < 6) {
    value /= 1000;
    ++unit;
  }
  if (unit == 0) return absl::StrFormat("%d bytes", bytes);
  return absl::StrFormat("%.3g %s", value, kUnits[unit]);
}

}  // namespace membrane
