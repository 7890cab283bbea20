#include "tests/support/random_membrane.h"

#include <algorithm>
#include <vector>

#include "core/engine/voxel_state.h"

namespace membrane::testing {

void MarkRandomMembrane(VoxelGrid& grid, std::mt19937& rng, int64_t scatter_divisor) {
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  std::vector<int64_t> boundary;
  for (int64_t i = 0; i < grid.size(); ++i) {
    if (IsOutside(grid.at(i)) || grid.OnArrayBorder(grid.CoordOf(i))) continue;
    for (int64_t offset : grid.neighbour_offsets()) {
      if (IsOutside(grid.at(i + offset))) {
        boundary.push_back(i);
        break;
      }
    }
  }
  for (int64_t i : boundary) {
    const int roll = uniform(0, 99);
    grid.set(i, roll < 4 ? kBoundaryHard : roll < 7 ? kBoundaryFrozen : kBoundarySoft);
  }
  const auto& dims = grid.dims();
  for (int64_t k = 0; k < grid.size() / scatter_divisor; ++k) {
    const int64_t i = std::uniform_int_distribution<int64_t>(0, grid.size() - 1)(rng);
    const Coord c = grid.CoordOf(i);
    if (std::min({c.x, c.y, c.z, dims[0] - 1 - c.x, dims[1] - 1 - c.y, dims[2] - 1 - c.z}) <
        VoxelGrid::kPadding) {
      continue;
    }
    grid.set(i, uniform(0, 1) == 0 ? OutsideState(1) : kBoundarySoft);
  }
}

}  // namespace membrane::testing
