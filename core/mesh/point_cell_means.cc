#include "core/mesh/point_cell_means.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace membrane {

PointCellMeans MeanPerSubCell(const PointRowGrid& grid, int split) {
  PointCellMeans out;
  const float* xs = grid.xs();
  const float* ys = grid.ys();
  const float* zs = grid.zs();
  const std::array<double, 3>& lo = grid.origin();
  const double per_cell = split / grid.cell();
  const int subs = split * split * split;
  std::vector<std::array<double, 3>> sum(subs);
  std::vector<int64_t> count(subs, 0);
  grid.ForEachCell([&](uint32_t begin, uint32_t end) {
    std::fill(sum.begin(), sum.end(), std::array<double, 3>{0, 0, 0});
    std::fill(count.begin(), count.end(), 0);
    const std::array<int64_t, 3> cell = grid.CellCoords({xs[begin], ys[begin], zs[begin]});
    for (uint32_t i = begin; i < end; ++i) {
      const double p[3] = {xs[i], ys[i], zs[i]};
      int sub = 0;
      for (int k = 2; k >= 0; --k) {
        const double t = std::floor((p[k] - lo[k]) * per_cell) - double(split) * double(cell[k]);
        sub = sub * split + static_cast<int>(std::clamp(t, 0.0, double(split - 1)));
      }
      for (int k = 0; k < 3; ++k) sum[sub][k] += p[k];
      ++count[sub];
    }
    for (int sub = 0; sub < subs; ++sub) {
      if (count[sub] == 0) continue;
      const double n = static_cast<double>(count[sub]);
      out.means.push_back(Point3f{static_cast<float>(sum[sub][0] / n),
                                  static_cast<float>(sum[sub][1] / n),
                                  static_cast<float>(sum[sub][2] / n)});
      out.counts.push_back(static_cast<float>(count[sub]));
    }
  });
  return out;
}

}  // namespace membrane
