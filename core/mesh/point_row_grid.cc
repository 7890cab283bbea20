#include "core/mesh/point_row_grid.h"

namespace membrane {

PointRowGrid::PointRowGrid(absl::Span<const Point3f> points, double cell) : cell_(cell) {
  if (points.empty()) return;
  std::array<double, 3> hi;
  for (int k = 0; k < 3; ++k) lo_[k] = hi[k] = points[0][k];
  for (const Point3f& p : points)
    for (int k = 0; k < 3; ++k) {
      lo_[k] = std::min<double>(lo_[k], p[k]);
      hi[k] = std::max<double>(hi[k], p[k]);
    }
  // A few offsets per point at most: a sparse cloud in a large box gets coarser cells (more
  // points scanned per query) rather than memory out of proportion to the cloud.
  const double max_cells = std::max(16.0 * points.size(), double(1 << 21));
  for (;;) {
    double cells = 1;
    for (int k = 0; k < 3; ++k) {
      dims_[k] = static_cast<int64_t>(std::floor((hi[k] - lo_[k]) / cell_)) + 1;
      cells *= dims_[k];
    }
    if (cells <= max_cells) break;
    cell_ *= 1.25;
  }
  const int64_t n = dims_[0] * dims_[1] * dims_[2];
  std::vector<uint32_t> cell_of(points.size());
  // Counting sort, stable: within a cell the points keep their input order. Counts first, then
  // running totals (start_[c] = end of cell c), then the points from last to first, each one
  // slot before its cell's end: start_[c] ends up as the cell's first point, with no second
  // array of the cells' size.
  start_.assign(n + 1, 0);
  for (size_t i = 0; i < points.size(); ++i) {
    int64_t c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp<int64_t>(CellOf(points[i][k], k), 0, dims_[k] - 1);
    cell_of[i] = static_cast<uint32_t>(c[0] + dims_[0] * (c[1] + dims_[1] * c[2]));
    ++start_[cell_of[i]];
  }
  for (int64_t c = 0; c < n; ++c) start_[c + 1] += start_[c];
  num_points_ = points.size();
  x_.assign(num_points_ + kTail, kPadding);
  y_.assign(num_points_ + kTail, kPadding);
  z_.assign(num_points_ + kTail, kPadding);
  for (size_t i = points.size(); i-- > 0;) {
    const uint32_t to = --start_[cell_of[i]];
    x_[to] = points[i][0];
    y_[to] = points[i][1];
    z_[to] = points[i][2];
  }
}

}  // namespace membrane
