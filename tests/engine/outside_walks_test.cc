// The walks through the outside in blocks of 8^3 and by runs stop where a walk voxel by voxel
// stops.
#include "core/engine/outside_blocks.h"
#include "core/engine/outside_runs.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <tuple>
#include <vector>

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

// Every voxel, axis and direction of random grids, against a walk voxel by voxel: `walker`
// makes the walk of a grid on so many threads.
using Walk = std::function<int(const Coord&, int d, int sign)>;
void ExpectVoxelWalks(const std::function<Walk(const VoxelGrid&, int threads)>& walker) {
  const std::array<int, 3> sizes[] = {{45, 37, 29}, {64, 16, 24}, {9, 70, 33}, {3, 3, 3},
                                      {8, 5, 7}, {17, 9, 40}};
  uint32_t seed = 1;
  for (const auto& dims : sizes)
    for (int solids : {0, 1, 6}) {
      const VoxelGrid grid = RandomSolids(dims, solids, seed++);
      for (int threads : {1, 2, 3}) {
        const Walk walk = walker(grid, threads);
        Coord c;
        for (c.z = 0; c.z < dims[2]; ++c.z)
          for (c.y = 0; c.y < dims[1]; ++c.y)
            for (c.x = 0; c.x < dims[0]; ++c.x)
              for (int d = 0; d < 3; ++d)
                for (int sign : {-1, 1}) {
                  if ((sign < 0 && c[d] == 0) || (sign > 0 && c[d] == dims[d] - 1)) continue;
                  ASSERT_EQ(walk(c, d, sign), WalkVoxelByVoxel(grid, c, d, sign))
                      << dims[0] << "x" << dims[1] << "x" << dims[2] << " from (" << c.x << ", "
                      << c.y << ", " << c.z << ") axis " << d << " sign " << sign << ", "
                      << threads << " threads";
                }
      }
    }
}

TEST(OutsideBlocks, WalksStopWhereVoxelWalksStop) {
  ExpectVoxelWalks([](const VoxelGrid& grid, int threads) -> Walk {
    auto blocks = std::make_shared<OutsideBlocks>(grid, threads);
    return [blocks, &grid](const Coord& c, int d, int sign) {
      return blocks->WalkOutside(grid, c, d, sign);
    };
  });
}

TEST(OutsideRuns, WalksStopWhereVoxelWalksStop) {
  ExpectVoxelWalks([](const VoxelGrid& grid, int threads) -> Walk {
    auto runs = std::make_shared<OutsideRuns>(*OutsideRuns::Read(grid, threads, int64_t{1} << 30));
    return [runs](const Coord& c, int d, int sign) { return runs->WalkOutside(c, d, sign); };
  });
}

// The runs of a grid of one solid box and one solid voxel: a run per row through each, and
// none from a grid all outside; more runs than the bytes allowed: none read.
TEST(OutsideRuns, OneRunPerRowThroughASolidAndNoneWithoutRoom) {
  VoxelGrid grid({30, 20, 10}, {0, 0, 0}, 1.0, OutsideState(1));
  EXPECT_EQ(OutsideRuns::Read(grid, 2, 1 << 20)->runs(), 0);
  Coord c;
  for (c.z = 2; c.z < 5; ++c.z)
    for (c.y = 3; c.y < 7; ++c.y)
      for (c.x = 10; c.x < 15; ++c.x) grid.set(c, kInsideSoft);
  grid.set(Coord{25, 15, 8}, kBoundaryHard);
  // The box: 4 x 3 rows along x, 5 x 3 along y, 5 x 4 along z; the voxel: one along each.
  const int64_t runs = 12 + 15 + 20 + 3;
  for (int threads : {1, 2, 4}) {
    const std::optional<OutsideRuns> read = OutsideRuns::Read(grid, threads, 8 * runs);
    ASSERT_TRUE(read.has_value());
    EXPECT_EQ(read->runs(), runs);
    EXPECT_FALSE(OutsideRuns::Read(grid, threads, 8 * runs - 1).has_value());
  }
}

// A ray from beside a solid box out into the open reaches the array's border layer.
TEST(OutsideBlocks, AnOpenRayReachesTheBorder) {
  VoxelGrid grid({50, 41, 60}, {0, 0, 0}, 1.0, OutsideState(1));
  grid.set(Coord{20, 20, 20}, kInsideSoft);
  const OutsideBlocks blocks(grid, 1);
  const OutsideRuns runs = *OutsideRuns::Read(grid, 1, 1 << 20);
  for (const auto& [c, d, sign, stop] : std::vector<std::tuple<Coord, int, int, int>>{
           {{20, 20, 21}, 2, 1, 59},
           {{20, 20, 21}, 2, -1, 20},
           {{20, 20, 19}, 2, -1, 0},
           {{25, 20, 20}, 0, -1, 20},
           {{25, 20, 20}, 0, 1, 49}}) {
    EXPECT_EQ(blocks.WalkOutside(grid, c, d, sign), stop);
    EXPECT_EQ(runs.WalkOutside(c, d, sign), stop);
  }
}

}  // namespace
}  // namespace membrane
