#include "core/mesh/point_cell_means.h"

#include <array>
#include <cstdint>

#include "core/mesh/point_row_grid.h"

namespace membrane {

PointCellMeans MeanPerCell(absl::Span<const Point3f> points, double cell, int threads) {
  PointCellMeans out;
  if (points.empty()) return out;
  const PointRowGrid grid(points, cell, threads);
  const float* xs = grid.xs();
  const float* ys = grid.ys();
  const float* zs = grid.zs();
  grid.ForEachCell([&](uint32_t begin, uint32_t end) {
    std::array<double, 3> sum{0, 0, 0};
    for (uint32_t i = begin; i < end; ++i) {
      sum[0] += xs[i];
      sum[1] += ys[i];
      sum[2] += zs[i];
    }
    const double n = static_cast<double>(end - begin);
    out.means.push_back(Point3f{static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n),
                                static_cast<float>(sum[2] / n)});
    out.counts.push_back(static_cast<float>(end - begin));
  });
  return out;
}

}  // namespace membrane
