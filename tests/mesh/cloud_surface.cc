#include "tests/mesh/cloud_surface.h"

#include <utility>

#include "core/base/cancel_token.h"
#include "core/mesh/relaxation.h"
#include "tests/support/shrink_fixture.h"

namespace membrane::testing {

absl::StatusOr<CloudSurface> SmoothSurfaceOfCloud(const PointCloud& cloud,
                                                  const SmoothSurfaceOptions& options,
                                                  double voxel_size) {
  absl::StatusOr<ShrinkRun> run = ShrinkCloud(cloud, 1.0, {}, voxel_size);
  if (!run.ok()) return run.status();
  VoxelGrid& grid = run->voxels.grid;
  if (auto relaxed = Relax(grid, CancelToken::Never()); !relaxed.ok()) return relaxed.status();
  CloudSurface surface;
  absl::StatusOr<TriangleMesh> mesh = SmoothSurface(grid, cloud.points, options, &surface.stats);
  if (!mesh.ok()) return mesh.status();
  surface.mesh = *std::move(mesh);
  surface.voxel_size = grid.voxel_size();
  return surface;
}

}  // namespace membrane::testing
