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
  // Indexes `points` by the voxel of `grid` each lies in: when the grid was voxelized from
  // these points (its origin is their least coordinate less the padding), the voxel Voxelize
  // made hard for each (DataVoxelAlong past the padding); for another grid, voxel
  // floor((p - origin) / l), a point past the array clamped into it. The grid's states are
  // not read, and the grid is not kept: queries take it again. Memory: 12 bytes a point and
  // 12 a voxel holding points (16 bytes a point more while it is built, 32 while its two
  // halves merge); cost: one sort of the points' voxel indices, its halves on two of
  // `threads` (>= 1) when there are more than one: the same object for any count.
  HardVoxelPoints(const VoxelGrid& grid, absl::Span<const Point3f> points, int threads = 1);

  // How far the points of the voxels in the box [lo, hi] (voxel coordinates, inclusive,
  // clipped to the grid) lie from their best-fitting plane: the square root of the smallest
  // eigenvalue of their covariance, in voxels. One scanned surface gives its noise (a tenth to
  // a few tenths of a voxel); two surfaces facing away from each other (the two sides of a
  // leg, a horn, a belt, a sheet) give about half their distance. -1 when the box holds fewer
  // than `min_points` points (no evidence).
  double PlaneSpread(const VoxelGrid& grid, const Coord& lo, const Coord& hi,
                     int min_points = 4) const;

  // The unit normal of the points' best-fitting plane in the box [lo, hi] (as PlaneSpread):
  // the eigenvector of the smallest eigenvalue of their covariance, its sign arbitrary. False
  // when the box holds fewer than `min_points` points, or that eigenvector is not a line
  // (the two smallest spreads equal).
  bool PlaneNormal(const VoxelGrid& grid, const Coord& lo, const Coord& hi,
                   std::array<double, 3>& normal, int min_points = 4) const;

  // The distance, in voxels, from the centre of voxel `c` to the nearest point of the voxels
  // within Chebyshev distance `radius` of it; radius + 1 when they hold none (every point
  // farther than `radius` voxels from the centre lies outside them).
  double NearestDistance(const VoxelGrid& grid, const Coord& c, int radius) const;

  // The distance, in voxels, from each spot of voxel `c` to the nearest point of the voxels
  // within Chebyshev distance `radius` of it, into `distances` (resized): the spots are the
  // centres of a `samples`^3 subdivision of the voxel, x fastest (samples 1: its centre, as
  // NearestDistance). Exact up to `radius` (a point outside the voxels read lies farther from
  // every spot); a spot with no point read within radius + 1 gets radius + 1. Where a passage
  // narrower than two voxels runs off the voxel centres (a hole 2.4 voxels wide whose axis
  // crosses a voxel 0.55 voxel from its centre), its free line passes spots, not centres.
  void SpotDistances(const VoxelGrid& grid, const Coord& c, int radius, int samples,
                     std::vector<double>& distances) const;

  // The patch of data seen from voxel `c`: the points, among those of the voxels within
  // Chebyshev distance `radius` of it, that lie within `band` voxels more than the nearest of
  // them from its centre, or, when fewer than `min_count` (at most 8) lie there, within as
  // far as the min_count-th nearest, up to `max_band` more than the nearest. Seen from an
  // outside voxel beside the data, that is the surface it faces: its foot on one sheet, not a
  // mean over a wall's two faces; on a face sampled at a point a voxel the band alone holds a
  // point or two, too few for the face's plane.
  struct Patch {
    double count = 0;
    std::array<double, 3> mean{};  // voxels from the grid's origin
    std::array<double, 6> scatter{};  // sums of (p - mean)(p - mean)^T: xx, xy, xz, yy, yz, zz
  };
  // False when those voxels hold no point.
  bool FacingPatch(const VoxelGrid& grid, const Coord& c, int radius, double band,
                   int min_count, double max_band, Patch& patch) const;

  // The grid indices of the voxels holding points, ascending: a voxel's rank is its position.
  absl::Span<const int64_t> voxels() const { return voxels_; }

  // Whether a point of the voxel of rank `a` and a point of the voxel of rank `b` lie within
  // `reach` voxels of each other. Costs at most the product of their point counts, stopping at
  // the first pair within reach.
  bool PointsWithin(size_t a, size_t b, double reach) const;

  int64_t points() const { return static_cast<int64_t>(positions_.size()); }

 private:
  // The count and covariance (xx, xy, xz, yy, yz, zz; voxels squared) of the points in the box
  // [lo, hi] (clipped to the grid); false when the box is empty after clipping.
  struct Moments {
    double n = 0;
    std::array<double, 6> cov{};
  };
  bool BoxMoments(const VoxelGrid& grid, const Coord& lo, const Coord& hi, Moments& m) const;
  // Calls f(position) for every point of the voxels of the box [a, b] (already clipped).
  template <typename F>
  void ForEachPoint(const VoxelGrid& grid, const Coord& a, const Coord& b, F f) const;

  // Sized unset: the constructor writes every element on the run's threads.
  template <typename T>
  using Array = std::vector<T, UnsetAllocator<T>>;
  Array<int64_t> voxels_;                 // grid indices holding points, ascending
  Array<uint32_t> starts_;                // voxel k's points: [starts_[k], starts_[k+1])
  Array<std::array<float, 3>> positions_; // in voxels from the grid's origin
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_ENGINE_HARD_VOXEL_POINTS_H_
