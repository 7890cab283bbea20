// A spatial hash of the input points, for gathering the points near a surface vertex during the
// fit (membrane-quality.md recipe 3 step 5: "gather points within 2 voxels").
#ifndef MEMBRANE_CORE_MESH_POINT_HASH_GRID_H_
#define MEMBRANE_CORE_MESH_POINT_HASH_GRID_H_

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "core/geometry/point_cloud.h"
#include "core/mesh/vec3.h"

namespace membrane {

// Cubic cells of side `cell` (model units). The points are stored sorted by cell (z, y, x), and
// only occupied cells are kept, in an open-addressing table from cell key to its run of points:
// memory is O(points) whatever the extent, and queries that move along the surface keep
// reading the same few runs and table slots, which stay in cache.
class PointHashGrid {
 public:
  // `cell` > 0 (model units); fewer than 2^32 points. Copies the points.
  PointHashGrid(absl::Span<const Point3f> points, double cell);

  // Calls fn(const Point3f&, double squared_distance) for every point within `radius` of
  // `centre` (model units). Visits every cell the ball's box touches: with `radius` at most
  // half the cell size, that is 8 cells.
  template <typename Fn>
  void ForEachWithin(const Vec3d& centre, double radius, Fn fn) const {
    if (sorted_.empty()) return;
    const double r2 = radius * radius;
    std::array<int64_t, 3> lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = CellOf(centre[k] - radius);
      hi[k] = CellOf(centre[k] + radius);
    }
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
      for (int64_t y = lo[1]; y <= hi[1]; ++y)
        for (int64_t x = lo[0]; x <= hi[0]; ++x) {
          const Slot* slot = Find(Key(x, y, z));
          if (slot == nullptr) continue;
          for (uint32_t i = slot->begin; i < slot->end; ++i) {
            const Point3f& p = sorted_[i];
            const double dx = p[0] - centre[0], dy = p[1] - centre[1], dz = p[2] - centre[2];
            const double d2 = dx * dx + dy * dy + dz * dz;
            if (d2 <= r2) fn(p, d2);
          }
        }
  }

 private:
  struct Slot {
    uint64_t key = kEmpty;
    uint32_t begin = 0, end = 0;
  };
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  static constexpr int64_t kBias = int64_t{1} << 20;  // cell coordinates kept in 21 bits

  int64_t CellOf(double v) const {
    const double c = std::floor(v / cell_);
    return static_cast<int64_t>(std::fmin(std::fmax(c, -double(kBias)), double(kBias - 1)));
  }
  static uint64_t Key(int64_t x, int64_t y, int64_t z) {
    return static_cast<uint64_t>(z + kBias) << 42 | static_cast<uint64_t>(y + kBias) << 21 |
           static_cast<uint64_t>(x + kBias);
  }
  size_t Home(uint64_t key) const {
    return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  const Slot* Find(uint64_t key) const {
    for (size_t i = Home(key);; i = (i + 1) & mask_) {
      if (table_[i].key == key) return &table_[i];
      if (table_[i].key == kEmpty) return nullptr;
    }
  }

  double cell_;
  std::vector<Point3f> sorted_;
  std::vector<Slot> table_;
  size_t mask_ = 0;
  int shift_ = 64;
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_POINT_HASH_GRID_H_
