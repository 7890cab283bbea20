// How points fill the voxels of a grid: which voxels hold points, and the paper's density
// ratio (section 4.3), voxels holding two points or more over voxels holding one. Voxelize
// marks its hard voxels from it; the pipeline's scatter warning measures the ratio at other
// voxel sizes without building a grid.
#ifndef MEMBRANE_CORE_ENGINE_POINT_DENSITY_H_
#define MEMBRANE_CORE_ENGINE_POINT_DENSITY_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "core/base/cancel_token.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

// Voxels per axis covering `bounds` with edge `voxel_size` (model units, > 0): floor(L / l) + 1,
// so the largest coordinate falls inside (Voxelize's data region, without its padding).
std::array<int, 3> DataDims(const Box3d& bounds, double voxel_size);

// The data-region voxel of coordinate `p` along one axis: floor((p - min) / voxel_size), clamped
// into [0, cells - 1], `min` the bounds' least coordinate on that axis and `cells` its DataDims.
// Voxelize's rule: whoever reads a point in the voxel Voxelize made hard for it computes the
// same expression (a division, not a multiplication by 1 / voxel_size, which rounds
// differently on voxel faces).
inline int64_t DataVoxelAlong(double p, double min, double voxel_size, int cells) {
  const double f = std::floor((p - min) / voxel_size);
  return std::clamp(static_cast<int64_t>(f), int64_t{0}, int64_t{cells} - 1);
}

// The data-region voxel of each point, x + nx (y + ny z) with (nx, ny, nz) = `dims` (DataDims
// of the same bounds and size), sorted so that a voxel's points are adjacent. Voxel x of a
// point is floor((p - bounds.min) / voxel_size), clamped into the region. On `threads`
// threads (RunTasks): the points are dealt into slabs of z planes in fixed blocks and each
// slab sorted apart; the result is the one sorted list, whatever the count. Memory: the list
// and a count per block and slab. Each block of points and each slab's sort asks `cancel`
// first; once it has fired, the rest are skipped and the list is meaningless (the caller, who
// holds the token, knows it).
std::vector<int64_t> SortedPointVoxels(absl::Span<const Point3f> points, const Box3d& bounds,
                                       double voxel_size, const std::array<int, 3>& dims,
                                       int threads = 1,
                                       const CancelToken& cancel = CancelToken::Never());

struct PointDensity {
  int64_t voxels_with_one_point = 0;
  int64_t voxels_with_more_points = 0;
  // more / one; 0 when no voxel holds exactly one point.
  double ratio() const {
    return voxels_with_one_point > 0
               ? static_cast<double>(voxels_with_more_points) / voxels_with_one_point
               : 0.0;
  }
};

// Calls visit(voxel, points_in_it) once per occupied voxel of `sorted` (SortedPointVoxels, or a
// part of it that splits no voxel's run), in order, and returns the counts.
template <typename Visit>
PointDensity ForEachOccupiedVoxel(absl::Span<const int64_t> sorted, Visit visit) {
  PointDensity d;
  for (size_t i = 0; i < sorted.size();) {
    size_t j = i;
    while (j < sorted.size() && sorted[j] == sorted[i]) ++j;
    (j - i == 1 ? d.voxels_with_one_point : d.voxels_with_more_points)++;
    visit(sorted[i], static_cast<int64_t>(j - i));
    i = j;
  }
  return d;
}

// The counts for `points` in voxels of edge `voxel_size` laid from bounds.min (`bounds` must
// hold every point, as CheckedBounds' does). Cost: one sort of the points' voxel indices, on
// `threads` threads (SortedPointVoxels).
PointDensity MeasurePointDensity(absl::Span<const Point3f> points, const Box3d& bounds,
                                 double voxel_size, int threads = 1);

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_POINT_DENSITY_H_
