// What a reconstruction will need in memory, estimated before it allocates: the grid and the
// cloud before voxelizing, the surface once the membrane is known. The server's memory budget
// and `membrane reconstruct --local`'s memory limit refuse a job on these numbers, before the
// kernel's OOM killer would end it.
#ifndef MEMBRANE_CORE_PIPELINE_MEMORY_ESTIMATE_H_
#define MEMBRANE_CORE_PIPELINE_MEMORY_ESTIMATE_H_

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "core/engine/voxelization.h"
#include "core/geometry/point_cloud.h"
#include "core/pipeline/membrane_counts.h"

namespace membrane {

// The grid Voxelize will allocate for `cloud` with `voxelize`, computed the same way before
// anything is allocated.
struct PlannedGrid {
  Box3d bounds;           // CheckedBounds of the points
  double voxel_size = 0;  // voxelize.voxel_size when > 0, else formula (1)'s (model units)
  int64_t voxels = 0;     // padding included
  // GridBytesEstimate of the grid and the points; a grid over voxelize.voxel_budget counts at
  // the budget (Voxelize refuses it, with the grid in its message, before allocating).
  int64_t bytes = 0;
};
// InvalidArgument for a degenerate cloud (CheckedBounds' message). Callers that then voxelize
// pass the planned voxel_size on, so that formula (1) does not count the points again.
absl::StatusOr<PlannedGrid> PlanGrid(const PointCloud& cloud, const VoxelizeOptions& voxelize);

// The bytes of a reconstruction before its surface: the grid and the shrink's working sets
// (under 6 bytes per voxel on the bench clouds) plus the cloud and its copies (48 per point).
int64_t GridBytesEstimate(int64_t voxels, int64_t points);

// The bytes BuildSurface and the mesh check may take beyond the grid and the cloud, for a
// membrane with these counts (CountMembrane): its boundary voxels times 1000. Measured on the
// ten real clouds and on uniform noise (whose membrane is a foam: its surface takes 28 times
// what the grid does), both surfaces: 1.8-2.7 faces per boundary voxel. Each run's peak RSS
// stayed within GridBytesEstimate plus 800 bytes per boundary voxel, but for cuberille on 20k
// noise points (1.2 times that); 1000 leaves a margin.
int64_t SurfaceBytesEstimate(const MembraneCounts& membrane);

// `bytes` for a person: "512 KB", "38.1 MB", "2.61 GB" (powers of 1000, 3 significant digits).
std::string BytesText(int64_t bytes);

}  // namespace membrane

#endif  // MEMBRANE_CORE_PIPELINE_MEMORY_ESTIMATE_H_
