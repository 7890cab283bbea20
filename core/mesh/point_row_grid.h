// A dense grid of the input points, for gathering the points near a surface vertex during the
// fit (membrane-quality.md recipe 3 step 5: "gather points within 2 voxels").
#ifndef MEMBRANE_CORE_MESH_POINT_ROW_GRID_H_
#define MEMBRANE_CORE_MESH_POINT_ROW_GRID_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "core/engine/huge_page_allocator.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/vec3.h"

namespace membrane {

// Cubic cells over the points' bounding box, the points stored cell by cell in (z, y, x) order:
// the cells of one row along x are one contiguous run, so a query reads one run per (y, z) row
// of its box, with no hashing, and cells small enough that the box holds little more than the
// ball. The coordinates are stored as three arrays (x, y, z), so that a caller can weigh a run
// several points at a time (near_point_sums.h). Memory: one offset per cell (their count is
// capped at a few times the points, the cells growing when the box is large and sparse) and a
// copy of the points.
class PointRowGrid {
 public:
  // Extra entries after the last point in each coordinate array, holding kPadding: a reader
  // of SIMD width up to kTail + 1 may load past a run's end (and mask the extra lanes).
  static constexpr size_t kTail = 7;
  static constexpr float kPadding = 1e15f;

  // `cell` > 0 (model units): the finest cell size; fewer than 2^32 points.
  PointRowGrid(absl::Span<const Point3f> points, double cell);

  // Calls fn(const Point3f&, double squared_distance) for every point within `radius` of
  // `centre` (model units), in storage order.
  template <typename Fn>
  void ForEachWithin(const Vec3d& centre, double radius, Fn fn) const {
    const double r2 = radius * radius;
    ForEachRun(centre, radius, [&](uint32_t begin, uint32_t end) {
      for (uint32_t i = begin; i < end; ++i) {
        const Point3f p{x_[i], y_[i], z_[i]};
        const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
        const double d2 = dx * dx + dy * dy + dz * dz;
        if (d2 <= r2) fn(p, d2);
      }
    });
  }

  // Calls fn(uint32_t begin, uint32_t end) for runs [begin, end) of stored points (indices into
  // xs(), ys(), zs()) that together hold every point within `radius` of `centre`, and others
  // near it (the cells of the ball's bounding box), in storage order: the caller filters.
  template <typename Fn>
  void ForEachRun(const Vec3d& centre, double radius, Fn fn) const {
    if (num_points_ == 0) return;
    std::array<int64_t, 3> lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max<int64_t>(CellOf(centre[k] - radius, k), 0);
      hi[k] = std::min<int64_t>(CellOf(centre[k] + radius, k), dims_[k] - 1);
      if (lo[k] > hi[k]) return;
    }
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y) {
        const int64_t row = dims_[0] * (y + dims_[1] * z);
        const uint32_t begin = start_[row + lo[0]], end = start_[row + hi[0] + 1];
        if (begin < end) fn(begin, end);
      }
  }

  // The stored coordinates, num_points() + kTail entries each.
  const float* xs() const { return x_.data(); }
  const float* ys() const { return y_.data(); }
  const float* zs() const { return z_.data(); }
  size_t num_points() const { return num_points_; }

 private:
  int64_t CellOf(double v, int axis) const {
    // Clamped to [-1, dims] before the conversion: far-away queries must not overflow, and NaN
    // goes to -1. Plain comparisons and an inline floor: std::fmin, std::fmax and std::floor
    // are library calls here, and a query makes dozens.
    double c = (v - lo_[axis]) / cell_;
    if (!(c >= -1.0)) c = -1.0;
    if (c > double(dims_[axis])) c = double(dims_[axis]);
    const int64_t t = static_cast<int64_t>(c);
    return t - (static_cast<double>(t) > c);
  }

  double cell_;
  std::array<double, 3> lo_{0, 0, 0};
  std::array<int64_t, 3> dims_{0, 0, 0};
  // Large and touched once: 2 MB pages where the kernel gives them (4 KB page faults would
  // be about a tenth of the surface's time on the shared virtual machine).
  template <typename T>
  using BigVector = std::vector<T, HugePageAllocator<T>>;
  BigVector<uint32_t> start_;  // per cell, its first point; one more at the end
  size_t num_points_ = 0;
  BigVector<float> x_, y_, z_;  // the points in cell order, then kTail paddings
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_POINT_ROW_GRID_H_
