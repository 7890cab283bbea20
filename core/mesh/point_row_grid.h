// An index of the input points by cell, for gathering the points near a surface vertex during
// the fit (membrane-quality.md recipe 3 step 5: "gather points within 2 voxels") and the hole
// caps' gap search. Its memory follows the occupied cells, not the points' bounding box.
#ifndef MEMBRANE_CORE_MESH_POINT_ROW_GRID_H_
#define MEMBRANE_CORE_MESH_POINT_ROW_GRID_H_

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "absl/types/span.h"
#include "core/engine/arena_allocator.h"
#include "core/geometry/point_cloud.h"
#include "core/geometry/vec3.h"

namespace membrane {

// Where PointRowGrid's layouts change (see below).
struct PointRowGridLimits {
  // The largest box (in cells) kept as kDense: 64 MB of offsets. The box is at most
  // max(16 points, 2^21) cells, so every cloud up to a million points is kDense.
  int64_t max_dense_cells = int64_t{1} << 24;
  // The most rows of a kRowTable; < 0: the points plus 2^20.
  int64_t max_table_rows = -1;
};

// Cubic cells over the points' bounding box, the points stored cell by cell in (z, y, x) order,
// stable within a cell: the cells of one row along x are one contiguous run, so a query reads
// one run per (y, z) row of its box. A small box keeps an offset per cell (the fastest query);
// a large one keeps the occupied cells alone: per row, its occupied cells' x and first point,
// sorted by x, found by a short search from the row's first cell, the rows a table over (y, z)
// when they are at most about one a point (a surface's cloud), else the occupied rows sorted by
// (z, y) and found by binary search (a sparse cloud in a large box). The coordinates are stored
// as three arrays (x, y, z), so that a caller can weigh a run several points at a time
// (near_point_sums.h). Memory: a copy of the points and, beyond a dense box of at most 64 MB,
// at most 12 bytes a point more (and 4 MB).
class PointRowGrid {
 public:
  // Extra entries after the last point in each coordinate array, copies of the last point
  // with weight 0: a reader of SIMD width up to kTail + 1 may load past a run's end (and mask
  // the extra lanes).
  static constexpr size_t kTail = 7;

  // How the cells are found: kDense, an offset per cell of the box; kRowTable, per row of
  // the box its occupied cells; kSparseRows, the occupied rows and their occupied cells.
  enum class Layout { kDense, kRowTable, kSparseRows };
  using Limits = PointRowGridLimits;

  // `cell` > 0 (model units): the finest cell size, grown x1.25 until the box holds at most
  // max(16 points, 2^21) cells (and 2^31 - 1 along each axis); fewer than 2^32 points. The
  // layout is the first of kDense, kRowTable, kSparseRows within `limits`. The build runs on
  // `threads` (<= 1: the calling thread); the index is the same for any thread count, and the
  // points' order and a query's runs are the same in every layout. `weights`, empty or one per
  // point, are stored beside the points (ws()).
  PointRowGrid(absl::Span<const Point3f> points, double cell, int threads = 1,
               const Limits& limits = Limits(), absl::Span<const float> weights = {});

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
  // near it (the cells of the ball's bounding box), in storage order, one run per (y, z) row
  // of the box holding a point: the caller filters.
  template <typename Fn>
  void ForEachRun(const Vec3d& centre, double radius, Fn fn) const {
    if (num_points_ == 0) return;
    std::array<int64_t, 3> lo, hi;
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::max<int64_t>(CellOf(centre[k] - radius, k), 0);
      hi[k] = std::min<int64_t>(CellOf(centre[k] + radius, k), dims_[k] - 1);
      if (lo[k] > hi[k]) return;
    }
    const uint32_t xlo = static_cast<uint32_t>(lo[0]), xhi = static_cast<uint32_t>(hi[0]);
    uint32_t begin, end;
    const int64_t nx = dims_[0], ny_cells = dims_[1];
    if (layout_ == Layout::kDense) {
      const uint32_t* start = start_.data();
      for (int64_t z = lo[2]; z <= hi[2]; ++z)
        for (int64_t y = lo[1]; y <= hi[1]; ++y) {
          const uint32_t* row = start + nx * (y + ny_cells * z);
          begin = row[xlo];
          end = row[xhi + 1];
          if (begin < end) fn(begin, end);
        }
      return;
    }
    if (layout_ == Layout::kRowTable) {
      const uint32_t* table = row_table_.data();
      for (int64_t z = lo[2]; z <= hi[2]; ++z)
        for (int64_t y = lo[1]; y <= hi[1]; ++y) {
          const int64_t row = y + ny_cells * z;
          if (RunInRow(table[row], table[row + 1], xlo, xhi, begin, end)) fn(begin, end);
        }
      return;
    }
    // Sparse rows: from each occupied row in the box's (z, y) range to the next, skipping the
    // keys between by binary search.
    const uint64_t ny = static_cast<uint64_t>(dims_[1]);
    const uint64_t ylo = static_cast<uint64_t>(lo[1]), yhi = static_cast<uint64_t>(hi[1]);
    const uint64_t last = static_cast<uint64_t>(hi[2]) * ny + yhi;
    size_t r = LowerRow(static_cast<uint64_t>(lo[2]) * ny + ylo);
    while (r < row_key_.size() && row_key_[r] <= last) {
      const uint64_t key = row_key_[r], y = key % ny;
      if (y < ylo) {
        r = LowerRow(key - y + ylo);
      } else if (y > yhi) {
        r = LowerRow(key - y + ny + ylo);
      } else {
        if (RunInRow(row_first_cell_[r], row_first_cell_[r + 1], xlo, xhi, begin, end))
          fn(begin, end);
        ++r;
      }
    }
  }

  // Calls fn(uint32_t begin, uint32_t end) for the run of stored points of every occupied
  // cell, in storage order.
  template <typename Fn>
  void ForEachCell(Fn fn) const {
    if (num_points_ == 0) return;
    if (layout_ == Layout::kDense) {
      // An empty cell's offset is the next occupied cell's, so the runs of empty cells are empty.
      for (size_t c = 0; c + 1 < start_.size(); ++c)
        if (start_[c] < start_[c + 1]) fn(start_[c], start_[c + 1]);
      return;
    }
    for (size_t c = 0; c + 1 < cells_.size(); ++c) fn(cells_[c].start, cells_[c + 1].start);
  }

  // The stored coordinates, num_points() + kTail entries each.
  const float* xs() const { return x_.data(); }
  const float* ys() const { return y_.data(); }
  const float* zs() const { return z_.data(); }
  // The stored weights in the same order, then kTail zeros; null when none were given.
  const float* ws() const { return w_.empty() ? nullptr : w_.data(); }
  size_t num_points() const { return num_points_; }
  // The cell size used.
  double cell() const { return cell_; }
  // The low corner of cell (0, 0, 0): the points' box's.
  const std::array<double, 3>& origin() const { return lo_; }
  // The cell the build filed `p` in (its coordinates clamped to the box).
  std::array<int64_t, 3> CellCoords(const Point3f& p) const {
    std::array<int64_t, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = std::clamp<int64_t>(CellOf(p[k], k), 0, dims_[k] - 1);
    return c;
  }
  // The memory the index holds, in bytes.
  size_t bytes() const;

  // The layout chosen within the limits.
  Layout layout() const { return layout_; }

 private:
  // An occupied cell: its x along its row and its first stored point (the next cell's first
  // point ends it).
  struct Cell {
    uint32_t x;
    uint32_t start;
  };

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

  // The run of stored points [begin, end) of a row's cells [a, b) (indices into cells_) whose
  // x lies in [xlo, xhi]; false when there is none. A row of a surface holds a few cells: a
  // forward scan, with a binary search for long rows (a surface lying along x). The caller's
  // fn is called in ForEachRun's loop, not in here: a RunInRow that called it was not inlined,
  // and the fit's sums then lived in memory across its calls (the weighing +43% instructions).
  [[gnu::always_inline]] bool RunInRow(uint32_t a, uint32_t b, uint32_t xlo, uint32_t xhi,
                                       uint32_t& begin, uint32_t& end) const {
    if (a == b) return false;
    const Cell* c = cells_.data();
    if (b - a > 16) {
      a = static_cast<uint32_t>(
          std::partition_point(c + a, c + b, [xlo](const Cell& e) { return e.x < xlo; }) - c);
    } else {
      while (a < b && c[a].x < xlo) ++a;
    }
    uint32_t e = a;
    while (e < b && c[e].x <= xhi) ++e;
    begin = c[a].start;
    end = c[e].start;
    return a < e;
  }

  // The first occupied row whose key is not below `key`.
  size_t LowerRow(uint64_t key) const {
    return static_cast<size_t>(std::lower_bound(row_key_.begin(), row_key_.end(), key) -
                               row_key_.begin());
  }

  // Sorts `order` (the input indexes) into storage order and lists the occupied rows and cells,
  // for a box whose rows are too many for a table.
  void BuildSparseRows(absl::Span<const Point3f> points, absl::Span<uint32_t> order);

  double cell_;
  std::array<double, 3> lo_{0, 0, 0};
  std::array<int64_t, 3> dims_{0, 0, 0};
  // The occupied cells in storage order, then one {~0, num_points} that ends the last.
  std::vector<Cell> cells_;
  Layout layout_ = Layout::kDense;
  // kDense: per cell x + dims_x (y + dims_y z) of the box, its first point (an empty cell:
  // the next occupied cell's); one more at the end. cells_ and row_table_ are then empty.
  std::vector<uint32_t, UnfilledAllocator<uint32_t>> start_;
  // kRowTable: per row y + dims_y z, its first cell in cells_; one more at the end.
  std::vector<uint32_t> row_table_;
  // Sparse rows (without the table): the occupied rows' keys z dims_y + y, increasing, and each
  // one's first cell; one more first cell at the end.
  std::vector<uint64_t> row_key_;
  std::vector<uint32_t> row_first_cell_;
  size_t num_points_ = 0;
  // Large and touched once: 2 MB pages where the kernel gives them (4 KB page faults would
  // be about a tenth of the surface's time on the shared virtual machine), first written on the
  // build's threads.
  template <typename T>
  using BigVector = std::vector<T, UnfilledAllocator<T>>;
  BigVector<float> x_, y_, z_;  // the points in cell order, then kTail paddings
  BigVector<float> w_;          // their weights, then kTail zeros (empty: none given)
};

}  // namespace membrane

#endif  // MEMBRANE_CORE_MESH_POINT_ROW_GRID_H_
