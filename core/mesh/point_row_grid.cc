#include "core/mesh/point_row_grid.h"

#include <algorithm>
#include <numeric>

#include "core/base/bucket_offsets.h"
#include "core/base/parallel_tasks.h"

namespace membrane {
namespace {

// Cells along an axis: their x is a uint32 and a row key z dims_y + y fits in 62 bits.
constexpr int64_t kMaxCellsPerAxis = (int64_t{1} << 31) - 1;
// Points per task of the passes over the input: enough to outweigh handing a task out.
constexpr int64_t kBlockPoints = int64_t{1} << 16;
// Rows per task of the passes over the rows.
constexpr int64_t kBlockRows = int64_t{1} << 12;
// Rows up to which the per-row stable sort by x is an insertion sort.
constexpr uint32_t kInsertionSortRows = 32;

template <typename T>
using Unfilled = std::vector<T, UnfilledAllocator<T>>;

// Sorts the `len` indexes at `o` by x_of, stably: by counting over the row's x range where it is
// at most kCountingRangePerPoint times the points plus 256 (a dense cloud's long rows, where a
// merge sort was a tenth of a 10M-point surface), else by std::stable_sort. `tally` and
// `sorted` are scratch.
constexpr uint32_t kCountingRangePerPoint = 4;
void CountingSortByX(uint32_t* o, uint32_t len, const uint32_t* x_of,
                     std::vector<uint32_t>& tally, std::vector<uint32_t>& sorted) {
  uint32_t lo = x_of[o[0]], hi = lo;
  for (uint32_t i = 1; i < len; ++i) {
    lo = std::min(lo, x_of[o[i]]);
    hi = std::max(hi, x_of[o[i]]);
  }
  const uint64_t range = uint64_t{hi} - lo + 1;
  if (range > uint64_t{kCountingRangePerPoint} * len + 256) {
    std::stable_sort(o, o + len, [&](uint32_t a, uint32_t b) { return x_of[a] < x_of[b]; });
    return;
  }
  tally.assign(range + 1, 0);
  for (uint32_t i = 0; i < len; ++i) ++tally[x_of[o[i]] - lo + 1];
  for (uint64_t k = 1; k <= range; ++k) tally[k] += tally[k - 1];
  sorted.resize(len);
  for (uint32_t i = 0; i < len; ++i) sorted[tally[x_of[o[i]] - lo]++] = o[i];
  std::copy(sorted.begin(), sorted.end(), o);
}

}  // namespace

PointRowGrid::PointRowGrid(absl::Span<const Point3f> points, double cell, int threads,
                           const Limits& limits, absl::Span<const float> weights)
    : cell_(cell) {
  if (points.empty()) return;
  const int64_t n = static_cast<int64_t>(points.size());
  const int64_t point_tasks = (n + kBlockPoints - 1) / kBlockPoints;

  // Bounds: per task, then merged (min and max are exact, so any split gives the same box).
  std::vector<std::array<double, 6>> task_box(point_tasks);
  RunTasks(threads, point_tasks, [&](int, int64_t t) {
    std::array<double, 6>& b = task_box[t];
    const int64_t begin = t * kBlockPoints, end = std::min(n, begin + kBlockPoints);
    for (int k = 0; k < 3; ++k) b[k] = b[k + 3] = points[begin][k];
    for (int64_t i = begin; i < end; ++i)
      for (int k = 0; k < 3; ++k) {
        b[k] = std::min<double>(b[k], points[i][k]);
        b[k + 3] = std::max<double>(b[k + 3], points[i][k]);
      }
  });
  std::array<double, 3> hi;
  for (int k = 0; k < 3; ++k) {
    lo_[k] = task_box[0][k];
    hi[k] = task_box[0][k + 3];
    for (const auto& b : task_box) {
      lo_[k] = std::min(lo_[k], b[k]);
      hi[k] = std::max(hi[k], b[k + 3]);
    }
  }
  // The box holds at most max(16 points, 2^21) cells: a sparse cloud in a large box gets
  // coarser cells (more points scanned per query). The cells then set the order in which the
  // points are listed, and so the bits of the callers' sums; in a large box the index holds
  // the occupied cells alone.
  const double max_cells = std::max(16.0 * static_cast<double>(n), double(1 << 21));
  for (;;) {
    double cells = 1;
    bool fits = true;
    for (int k = 0; k < 3; ++k) {
      const double d = std::floor((hi[k] - lo_[k]) / cell_) + 1;
      fits = fits && d <= double(kMaxCellsPerAxis);
      dims_[k] = static_cast<int64_t>(std::min(d, double(kMaxCellsPerAxis)));
      cells *= d;
    }
    if (fits && cells <= max_cells) break;
    cell_ *= 1.25;
  }
  num_points_ = static_cast<size_t>(n);

  // order[s]: the input index of the point stored at slot s.
  Unfilled<uint32_t> order(n);
  const int64_t rows = dims_[1] * dims_[2];
  const double box_cells = static_cast<double>(rows) * static_cast<double>(dims_[0]);
  const bool dense = box_cells <= static_cast<double>(limits.max_dense_cells);
  // A table over the rows when it is no larger than the points (a surface's cloud: its box's
  // face in cells is a fraction of its points), else the occupied rows alone.
  const int64_t max_rows =
      limits.max_table_rows >= 0 ? limits.max_table_rows : n + (int64_t{1} << 20);
  if (dense || rows <= max_rows) {
    layout_ = dense ? Layout::kDense : Layout::kRowTable;
    // Counting sort by row, stable: per part of the points (one a thread, each with counts for
    // every row) its counts, then running totals in (row, part) order, then each part places
    // its points in input order.
    Unfilled<uint32_t> row_of(n), x_of(n);
    const int64_t parts = std::min<int64_t>(std::max(threads, 1), point_tasks);
    const int64_t part_points = (n + parts - 1) / parts;
    std::vector<std::vector<uint32_t>> next(parts, std::vector<uint32_t>(rows, 0));
    RunTasks(threads, parts, [&](int, int64_t t) {
      const int64_t begin = t * part_points, end = std::min(n, begin + part_points);
      std::vector<uint32_t>& count = next[t];
      for (int64_t i = begin; i < end; ++i) {
        int64_t c[3];
        for (int k = 0; k < 3; ++k)
          c[k] = std::clamp<int64_t>(CellOf(points[i][k], k), 0, dims_[k] - 1);
        row_of[i] = static_cast<uint32_t>(c[1] + dims_[1] * c[2]);
        x_of[i] = static_cast<uint32_t>(c[0]);
        ++count[row_of[i]];
      }
    });
    const std::vector<uint32_t> row_start = PlaceBucketsByPart(next);
    RunTasks(threads, parts, [&](int, int64_t t) {
      const int64_t begin = t * part_points, end = std::min(n, begin + part_points);
      std::vector<uint32_t>& slot = next[t];
      for (int64_t i = begin; i < end; ++i) order[slot[row_of[i]]++] = static_cast<uint32_t>(i);
    });
    next.clear();
    next.shrink_to_fit();
    // Within each row, a stable sort by x; then its cells counted, placed by running totals,
    // and written.
    row_table_.assign(rows + 1, 0);
    const int64_t row_tasks = (rows + kBlockRows - 1) / kBlockRows;
    std::vector<std::vector<uint32_t>> tally(std::max(threads, 1)), sorted(std::max(threads, 1));
    RunTasks(threads, row_tasks, [&](int worker, int64_t t) {
      const int64_t end = std::min(rows, (t + 1) * kBlockRows);
      for (int64_t r = t * kBlockRows; r < end; ++r) {
        uint32_t* o = order.data() + row_start[r];
        const uint32_t len = row_start[r + 1] - row_start[r];
        if (len == 0) continue;
        if (len <= kInsertionSortRows) {
          for (uint32_t i = 1; i < len; ++i) {
            const uint32_t v = o[i];
            uint32_t j = i;
            for (; j > 0 && x_of[o[j - 1]] > x_of[v]; --j) o[j] = o[j - 1];
            o[j] = v;
          }
        } else {
          CountingSortByX(o, len, x_of.data(), tally[worker], sorted[worker]);
        }
        uint32_t distinct = 1;
        for (uint32_t i = 1; i < len; ++i) distinct += x_of[o[i]] != x_of[o[i - 1]];
        row_table_[r] = distinct;
      }
    });
    uint32_t cells = 0;
    for (int64_t r = 0; r < rows; ++r) {
      const uint32_t c = row_table_[r];
      row_table_[r] = cells;
      cells += c;
    }
    row_table_[rows] = cells;
    cells_.resize(cells + 1);
    RunTasks(threads, row_tasks, [&](int, int64_t t) {
      const int64_t end = std::min(rows, (t + 1) * kBlockRows);
      for (int64_t r = t * kBlockRows; r < end; ++r) {
        uint32_t to = row_table_[r];
        for (uint32_t s = row_start[r]; s < row_start[r + 1]; ++s)
          if (s == row_start[r] || x_of[order[s]] != x_of[order[s - 1]])
            cells_[to++] = Cell{x_of[order[s]], s};
      }
    });
  } else {
    layout_ = Layout::kSparseRows;
    BuildSparseRows(points, absl::MakeSpan(order));
  }
  cells_.back() = Cell{~uint32_t{0}, static_cast<uint32_t>(n)};
  if (layout_ == Layout::kDense) {
    // Every cell of the box: an occupied one its first point, an empty one the next occupied
    // cell's (or the next row's first point), so that [start(lo), start(hi + 1)) is a run.
    start_.resize(rows * dims_[0] + 1);
    const int64_t row_tasks = (rows + kBlockRows - 1) / kBlockRows;
    RunTasks(threads, row_tasks, [&](int, int64_t t) {
      const int64_t end = std::min(rows, (t + 1) * kBlockRows);
      for (int64_t r = t * kBlockRows; r < end; ++r) {
        uint32_t* row = start_.data() + dims_[0] * r;
        uint32_t c = row_table_[r];
        for (int64_t x = 0; x < dims_[0]; ++x) {
          if (c < row_table_[r + 1] && cells_[c].x < x) ++c;
          row[x] = cells_[c].start;  // past the row's last cell: the next row's first point
        }
      }
    });
    start_.back() = static_cast<uint32_t>(n);
    cells_ = {};
    row_table_ = {};
  }

  // The coordinates in storage order, then the paddings.
  x_.resize(n + kTail);
  y_.resize(n + kTail);
  z_.resize(n + kTail);
  const bool weighted = !weights.empty();
  if (weighted) w_.resize(n + kTail);
  RunTasks(threads, point_tasks, [&](int, int64_t t) {
    const int64_t end = std::min(n, (t + 1) * kBlockPoints);
    for (int64_t s = t * kBlockPoints; s < end; ++s) {
      const Point3f& p = points[order[s]];
      x_[s] = p[0];
      y_[s] = p[1];
      z_[s] = p[2];
      if (weighted) w_[s] = weights[order[s]];
    }
  });
  // The paddings copy the last point (no weight): finite and within the cloud, so that a
  // masked lane's products stay finite in any frame (a far value such as 1e15, in the frame
  // of a voxel of 1e-7, squares to infinity, and the mask's 0 times infinity is NaN).
  for (size_t s = num_points_; s < num_points_ + kTail; ++s) {
    x_[s] = num_points_ > 0 ? x_[num_points_ - 1] : 0.0f;
    y_[s] = num_points_ > 0 ? y_[num_points_ - 1] : 0.0f;
    z_[s] = num_points_ > 0 ? z_[num_points_ - 1] : 0.0f;
    if (weighted) w_[s] = 0;
  }
}

// A sparse cloud in a large box: the points sorted by (row key, x), stable, on one thread (a
// cloud of this shape is small or rare), and the occupied rows listed.
void PointRowGrid::BuildSparseRows(absl::Span<const Point3f> points,
                                   absl::Span<uint32_t> order) {
  const size_t n = points.size();
  std::vector<uint64_t> key(n);
  std::vector<uint32_t> x_of(n);
  for (size_t i = 0; i < n; ++i) {
    int64_t c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp<int64_t>(CellOf(points[i][k], k), 0, dims_[k] - 1);
    key[i] = static_cast<uint64_t>(c[2]) * static_cast<uint64_t>(dims_[1]) +
             static_cast<uint64_t>(c[1]);
    x_of[i] = static_cast<uint32_t>(c[0]);
  }
  std::iota(order.begin(), order.end(), uint32_t{0});
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return key[a] != key[b] ? key[a] < key[b] : x_of[a] < x_of[b];
  });
  for (size_t s = 0; s < n; ++s) {
    const uint32_t i = order[s];
    const bool new_row = s == 0 || key[i] != key[order[s - 1]];
    if (new_row) {
      row_key_.push_back(key[i]);
      row_first_cell_.push_back(static_cast<uint32_t>(cells_.size()));
    }
    if (new_row || x_of[i] != x_of[order[s - 1]])
      cells_.push_back(Cell{x_of[i], static_cast<uint32_t>(s)});
  }
  row_first_cell_.push_back(static_cast<uint32_t>(cells_.size()));
  cells_.push_back(Cell{});  // the end, set by the caller
  cells_.shrink_to_fit();
  row_key_.shrink_to_fit();
  row_first_cell_.shrink_to_fit();
}

size_t PointRowGrid::bytes() const {
  return cells_.capacity() * sizeof(Cell) + row_table_.capacity() * sizeof(uint32_t) +
         start_.capacity() * sizeof(uint32_t) +
         row_key_.capacity() * sizeof(uint64_t) + row_first_cell_.capacity() * sizeof(uint32_t) +
         3 * x_.capacity() * sizeof(float) + w_.capacity() * sizeof(float);
}

}  // namespace membrane
