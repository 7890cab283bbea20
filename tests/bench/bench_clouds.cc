#include "tests/bench/bench_clouds.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/voxelization.h"
#include "core/synth/synthesize.h"

namespace membrane::bench {
namespace {

absl::StatusOr<PointCloud> Synth(const std::string& shape, int64_t points, uint64_t seed) {
  SynthOptions o;
  o.shape = shape;
  o.points = points;
  o.seed = seed;
  return SynthesizeShape(o);
}

// Half the surface of a box: lx ly + ly lz + lz lx.
double HalfSurface(const Box3d& b) {
  const auto e = b.Extent();
  return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}

}  // namespace

int64_t PointsForGridSide(const Box3d& bounds, int axis, int target_side) {
  const double data_side = target_side - 2.0 * VoxelGrid::kPadding - 0.5;
  const double l = bounds.Extent()[axis] / std::max(1.0, data_side);
  return static_cast<int64_t>(std::ceil(2.0 * HalfSurface(bounds) / (l * l)));
}

absl::StatusOr<PointCloud> SynthForGridSide(const std::string& shape, int target_side) {
  // The bounds of a sampled sphere approach the true ones as points grow: probe, then refine.
  int64_t points = 20000;
  for (int round = 0; round < 2; ++round) {
    absl::StatusOr<PointCloud> probe = Synth(shape, points, 1);
    if (!probe.ok()) return probe.status();
    absl::StatusOr<Box3d> bounds = CheckedBounds(probe->points);
    if (!bounds.ok()) return bounds.status();
    const auto e = bounds->Extent();
    const int axis = static_cast<int>(std::max_element(e.begin(), e.end()) - e.begin());
    points = PointsForGridSide(*bounds, axis, target_side);
  }
  return Synth(shape, points, 1);
}

absl::StatusOr<PointCloud> SubsampleForGridSide(const PointCloud& cloud, int axis,
                                                int target_side) {
  absl::StatusOr<Box3d> bounds = CheckedBounds(cloud.points);
  if (!bounds.ok()) return bounds.status();
  const int64_t total = static_cast<int64_t>(cloud.points.size());
  const int64_t keep = PointsForGridSide(*bounds, axis, target_side);
  if (keep > total) {
    return absl::InvalidArgumentError(absl::StrCat("a grid side of ", target_side, " needs ",
                                                   keep, " points, the cloud has ", total));
  }
  PointCloud out;
  out.points.reserve(static_cast<size_t>(keep));
  for (int64_t i = 0; i < total; ++i) {
    if ((i + 1) * keep / total > i * keep / total) out.points.push_back(cloud.points[i]);
  }
  return out;
}

absl::StatusOr<PointCloud> StackedSpheres(int64_t points, int count, double spacing) {
  if (count < 1 || !(spacing > 0.0) || spacing >= 2.0 || points < count) {
    return absl::InvalidArgumentError(absl::StrCat("stacked spheres: count ", count, " spacing ",
                                                   spacing, " points ", points));
  }
  // Each overlap hides a cap of height h = 1 - spacing / 2, a fraction h / 2 of a sphere's
  // area, from both spheres: raw points per sphere so that about `points` remain.
  const double h = 1.0 - spacing / 2.0;
  const double kept_spheres = count - (count - 1) * h;
  const int64_t per_sphere = static_cast<int64_t>(std::ceil(points / kept_spheres));
  const double y0 = -0.5 * spacing * (count - 1);
  PointCloud out;
  out.points.reserve(static_cast<size_t>(points + count));
  for (int i = 0; i < count; ++i) {
    absl::StatusOr<PointCloud> sphere = Synth("sphere", per_sphere, 1 + i);
    if (!sphere.ok()) return sphere.status();
    const double yi = y0 + i * spacing;
    for (const Point3f& p : sphere->points) {
      const double y = p[1] + yi;
      bool covered = false;
      for (int j = 0; j < count && !covered; ++j) {
        if (j == i) continue;
        const double dy = y - (y0 + j * spacing);
        covered = p[0] * p[0] + dy * dy + p[2] * p[2] < 1.0;
      }
      if (!covered) out.points.push_back({p[0], static_cast<float>(y), p[2]});
    }
  }
  return out;
}

absl::StatusOr<PointCloud> StackedSpheresForHeight(int target_height, int count, double spacing) {
  // Bounding box of the union: 2 x (2 + (count - 1) spacing) x 2.
  Box3d box;
  box.min = {-1.0, -1.0 - 0.5 * spacing * (count - 1), -1.0};
  box.max = {1.0, 1.0 + 0.5 * spacing * (count - 1), 1.0};
  return StackedSpheres(PointsForGridSide(box, 1, target_height), count, spacing);
}

}  // namespace membrane::bench
