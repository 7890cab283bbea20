// The input points of the hard voxels, indexed by voxel, for the shrink's tests that read where
// the data lies inside a few voxels (the thin-part exception of the thick-wall incursion test,
// incursion_test.h).
#ifndef MEMBRANE_CORE_ENGINE_HARD_VOXEL_POINTS_H_
#define MEMBRANE_CORE_ENGINE_HARD_VOXEL_POINTS_H_

#include <array>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "core/engine/voxel_grid.h"
#include "core/geometry/point_cloud.h"

namespace membrane {

class HardVoxelPoints {
 public:
  // Indexes `points` by the voxel of `grid` each lies in (voxel floor((p - origin) / l), as
  // Voxelize placed them; a point past the array is clamped into it). The grid's states are
  // not read, and the grid is not kept: queries take it again. Memory: 12 bytes a point and
  // 12 a voxel holding points (16 bytes a point more while it is built); cost: one sort of
  // the points' voxel indices.
  HardVoxelPoints(const VoxelGrid& grid, absl::Span<const Point3f> points);

  // How far the points of the voxels in the box [lo, hi] (voxel coordinates, inclusive,
  // clipped to the grid) lie from their best-fitting plane: the square root of the smallest
  // eigenvalue of their covariance, in voxels. One scanned surface gives its noise (a tenth to
  // a few tenths of a voxel); two surfaces facing away from each other (the two sides of a
  // leg, a horn, a belt, a sheet) give about half their distance. -1 when the box holds fewer
  // than `min_points` points (no evidence).
  double PlaneSpread(const VoxelGrid& grid, const Coord& lo, const Coord& hi,
                     int min_points = 4) const;

  int64_t points() const { return static_cast<int64_t>(positions_.size()); }

 private:
  std::vector<int64_t> voxels_;                 // grid indices holding points, ascending
  std::vector<uint32_t> starts_;                // voxel k's points: [starts_[k], starts_[k+1])
  std::vector<std::array<float, 3>> positions_; // in voxels from the grid's origin
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_HARD_VOXEL_POINTS_H_
