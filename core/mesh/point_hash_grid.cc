#include "core/mesh/point_hash_grid.h"

#include <algorithm>
#include <bit>
#include <numeric>

namespace membrane {

PointHashGrid::PointHashGrid(absl::Span<const Point3f> points, double cell) : cell_(cell) {
  std::vector<uint64_t> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    keys[i] = Key(CellOf(points[i][0]), CellOf(points[i][1]), CellOf(points[i][2]));
  std::vector<uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  sorted_.reserve(points.size());
  size_t cells = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    sorted_.push_back(points[order[i]]);
    if (i == 0 || keys[order[i]] != keys[order[i - 1]]) ++cells;
  }
  // Load factor at most 1/2.
  const int bits = std::max(4, static_cast<int>(std::bit_width(2 * cells)));
  table_.assign(size_t{1} << bits, Slot{});
  mask_ = table_.size() - 1;
  shift_ = 64 - bits;
  for (size_t i = 0; i < order.size();) {
    const uint64_t key = keys[order[i]];
    size_t j = i;
    while (j < order.size() && keys[order[j]] == key) ++j;
    size_t slot = Home(key);
    while (table_[slot].key != kEmpty) slot = (slot + 1) & mask_;
    table_[slot] = Slot{key, static_cast<uint32_t>(i), static_cast<uint32_t>(j)};
    i = j;
  }
}

}  // namespace membrane
