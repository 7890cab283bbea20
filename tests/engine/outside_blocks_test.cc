// The walks through the outside in blocks of 8^3 stop where a walk voxel by voxel stops.
#include "core/engine/outside_blocks.h"

#include <gtest/gtest.h>

#include <array>
#include <random>

namespace membrane {
namespace {

// The walk OutsideBlocks::WalkOutside stands for, one voxel a step.
int WalkVoxelByVoxel(const VoxelGrid& grid, const Coord& c, int d, int sign) {
  Coord u = c;
  u[d] += sign;
  while (u[d] > 0 && u[d] < grid.dim(d) - 1 && IsOutside(grid.at(u))) u[d] += sign;
  return u[d];
}

// A grid of `dims` all outside but for `solids` random boxes of solid and a scatter of
// solid voxels: long runs of outside blocks, rows open to the border, blocks cut by the
// solid's faces.
VoxelGrid RandomSolids(std::array<int, 3> dims, int solids, uint32_t seed) {
  std::mt19937 rng(seed);
  VoxelGrid grid(dims, {0, 0, 0}, 1.0, OutsideState(1));
  for (int k = 0; k < solids; ++k) {
    Coord lo, hi;
    for (int d = 0; d < 3; ++d) {
      lo[d] = static_cast<int>(rng() % dims[d]);
      hi[d] = std::min(dims[d] - 1, lo[d] + static_cast<int>(rng() % 12));
    }
    Coord c;
    for (c.z = lo.z; c.z <= hi.z; ++c.z)
      for (c.y = lo.y; c.y <= hi.y; ++c.y)
        for (c.x = lo.x; c.x <= hi.x; ++c.x) grid.set(c, rng() % 5 == 0 ? kInsideHard : kInsideSoft);
  }
  for (int k = 0; k < 40; ++k)
    grid.set(static_cast<int64_t>(rng() % grid.size()), kBoundarySoft);
  return grid;
}

TEST(OutsideBlocks, WalksStopWhereVoxelWalksStop) {
  const std::array<int, 3> sizes[] = {{45, 37, 29}, {64, 16, 24}, {9, 70, 33}, {3, 3, 3}};
  uint32_t seed = 1;
  for (const auto& dims : sizes)
    for (int solids : {0, 1, 6}) {
      const VoxelGrid grid = RandomSolids(dims, solids, seed++);
      for (int threads : {1, 2}) {
        const OutsideBlocks blocks(grid, threads);
        Coord c;
        for (c.z = 0; c.z < dims[2]; ++c.z)
          for (c.y = 0; c.y < dims[1]; ++c.y)
            for (c.x = 0; c.x < dims[0]; ++c.x)
              for (int d = 0; d < 3; ++d)
                for (int sign : {-1, 1}) {
                  if ((sign < 0 && c[d] == 0) || (sign > 0 && c[d] == dims[d] - 1)) continue;
                  ASSERT_EQ(blocks.WalkOutside(grid, c, d, sign), WalkVoxelByVoxel(grid, c, d, sign))
                      << dims[0] << "x" << dims[1] << "x" << dims[2] << " from (" << c.x << ", "
                      << c.y << ", " << c.z << ") axis " << d << " sign " << sign << ", "
                      << threads << " threads";
                }
      }
    }
}

// A ray from beside a solid box out into the open reaches the array's border layer.
TEST(OutsideBlocks, AnOpenRayReachesTheBorder) {
  VoxelGrid grid({50, 41, 60}, {0, 0, 0}, 1.0, OutsideState(1));
  grid.set(Coord{20, 20, 20}, kInsideSoft);
  const OutsideBlocks blocks(grid, 1);
  EXPECT_EQ(blocks.WalkOutside(grid, Coord{20, 20, 21}, 2, 1), 59);
  EXPECT_EQ(blocks.WalkOutside(grid, Coord{20, 20, 21}, 2, -1), 20);
  EXPECT_EQ(blocks.WalkOutside(grid, Coord{20, 20, 19}, 2, -1), 0);
  EXPECT_EQ(blocks.WalkOutside(grid, Coord{25, 20, 20}, 0, -1), 20);
  EXPECT_EQ(blocks.WalkOutside(grid, Coord{25, 20, 20}, 0, 1), 49);
}

}  // namespace
}  // namespace membrane
