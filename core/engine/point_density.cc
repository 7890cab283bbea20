#include "core/engine/point_density.h"

#include <algorithm>
#include <cmath>

namespace membrane {

std::array<int, 3> DataDims(const Box3d& bounds, double voxel_size) {
  const auto extent = bounds.Extent();
  std::array<int, 3> dims;
  for (int d = 0; d < 3; ++d) dims[d] = static_cast<int>(std::floor(extent[d] / voxel_size)) + 1;
  return dims;
}

std::vector<int64_t> SortedPointVoxels(absl::Span<const Point3f> points, const Box3d& bounds,
                                       double voxel_size, const std::array<int, 3>& dims) {
  std::vector<int64_t> voxel_of(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    int64_t c[3];
    for (int d = 0; d < 3; ++d) {
      const double f = std::floor((points[i][d] - bounds.min[d]) / voxel_size);
      c[d] = std::clamp(static_cast<int64_t>(f), int64_t{0}, int64_t{dims[d]} - 1);
    }
    voxel_of[i] = c[0] + dims[0] * (c[1] + int64_t{dims[1]} * c[2]);
  }
  std::sort(voxel_of.begin(), voxel_of.end());
  return voxel_of;
}

PointDensity MeasurePointDensity(absl::Span<const Point3f> points, const Box3d& bounds,
                                 double voxel_size) {
  return ForEachOccupiedVoxel(
      SortedPointVoxels(points, bounds, voxel_size, DataDims(bounds, voxel_size)),
      [](int64_t, int64_t) {});
}

}  // namespace membrane
