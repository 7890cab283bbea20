#include "tests/mesh/cloud_surface.h"

#include <algorithm>
#include <random>
#include <utility>

#include "core/base/cancel_token.h"
#include "core/mesh/relaxation.h"
#include "gtest/gtest.h"
#include "tests/support/shrink_fixture.h"

namespace membrane::testing {

PointCloud SphereWithHole(int n, double hole, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  PointCloud cloud;
  while (static_cast<int>(cloud.points.size()) < n) {
    const Vec3d p = Normalized(Vec3d{gauss(rng), gauss(rng), gauss(rng)});
    if (SquaredNorm(p - Vec3d{0, 0, 1}) < hole * hole) continue;
    cloud.points.push_back(ToPoint3f(p));
  }
  return cloud;
}

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

CapMeasure MeasureCap(const PointCloud& cloud, const SmoothSurfaceOptions& options,
                      double voxel_size, const std::function<bool(const Vec3d&)>& in_hole,
                      const std::function<double(const Vec3d&)>& error) {
  absl::StatusOr<CloudSurface> surface = SmoothSurfaceOfCloud(cloud, options, voxel_size);
  CapMeasure result;
  EXPECT_TRUE(surface.ok()) << surface.status();
  if (!surface.ok()) return result;
  for (const Point3f& p : surface->mesh.vertices) {
    const Vec3d v = ToVec3d(p);
    if (!in_hole(v)) continue;
    const double e = error(v) / surface->voxel_size;
    result.max_error = std::max(result.max_error, e);
    result.mean_error += e;
    ++result.vertices;
  }
  if (result.vertices > 0) result.mean_error /= result.vertices;
  result.caps = surface->stats.caps;
  result.check = CheckMesh(surface->mesh);
  return result;
}

}  // namespace membrane::testing
