#include "core/mesh/cave_filling.h"

#include <cmath>
#include <vector>

#include "core/engine/voxel_topology.h"
#include "gtest/gtest.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

using namespace membrane::testing;

int64_t SolidCount(const VoxelGrid& g) {
  int64_t n = 0;
  for (int64_t i = 0; i < g.size(); ++i) n += !IsOutside(g.at(i));
  return n;
}

TEST(CaveFilling, FillsTheHollowBehindAPinhole) {
  VoxelGrid g = PinholeBoxGrid(20, 3);
  const VoxelTopology before = ComputeVoxelTopology(g);
  const int64_t filled = FillCaves(g);
  // The solid spans voxels 2..17 with 3-voxel walls: a 10^3 hollow plus the 3-voxel pinhole.
  EXPECT_EQ(filled, 10 * 10 * 10 + 3);
  const VoxelTopology after = ComputeVoxelTopology(g);
  EXPECT_EQ(after.shells, before.shells);
  EXPECT_EQ(after.genus, before.genus);
}

TEST(CaveFilling, KeepsTheHoleOfAThinTorus) {
  // The hole is narrower than 3 voxels in places, so it is a cave, but filling it would close
  // the handle: homotopic filling stops short.
  VoxelGrid g = SolidTorusGrid(32, 5, 3.5);
  FillCaves(g);
  EXPECT_EQ(ComputeVoxelTopology(g).genus, std::vector<int>{1});
}

TEST(CaveFilling, LeavesAConvexSolidAlone) {
  VoxelGrid g = BallGrid(30, 10.5);
  const int64_t before = SolidCount(g);
  EXPECT_EQ(FillCaves(g), 0);
  EXPECT_EQ(SolidCount(g), before);
}

TEST(CaveFilling, FillsANarrowCrevice) {
  // A 2-voxel-wide slot cut 6 deep into a block: reached from outside only through a passage
  // narrower than 3 voxels.
  VoxelGrid g = OutsideGrid(20);
  MarkSolid(g, [](int x, int y, int z) {
    const bool block = x >= 3 && x < 17 && y >= 3 && y < 17 && z >= 3 && z < 17;
    const bool slot = x >= 9 && x < 11 && y >= 5 && y < 15 && z >= 11;
    return block && !slot;
  });
  const VoxelTopology before = ComputeVoxelTopology(g);
  EXPECT_GT(FillCaves(g), 0);
  const VoxelTopology after = ComputeVoxelTopology(g);
  EXPECT_EQ(after.shells, before.shells);
  EXPECT_EQ(after.genus, before.genus);
}

// A 64^3 block with 2-voxel slots 6 deep every 8 voxels across its top, a hollow behind a
// pinhole and a thin torus beside it: caves on many planes of the filters' and the scan's
// tasks, filled to the same bytes on 1, 2 and 3 threads.
TEST(CaveFilling, SameGridForAnyThreadCount) {
  VoxelGrid shape = OutsideGrid(64);
  MarkSolid(shape, [](int x, int y, int z) {
    const bool block = x >= 3 && x < 61 && y >= 3 && y < 40 && z >= 3 && z < 61;
    const bool slot = x % 8 >= 4 && x % 8 < 6 && y >= 30 && z % 8 < 6 && x > 3 && x < 60 &&
                      z > 3 && z < 60;
    const bool hollow = x >= 10 && x < 30 && y >= 10 && y < 25 && z >= 10 && z < 30;
    const bool pinhole = x == 20 && z == 20 && y < 10;
    const double r = std::hypot(x - 32.0, z - 32.0);
    const bool torus = y >= 46 && y < 60 && std::hypot(r - 12.0, y - 53.0) < 3.5;
    return (block && !slot && !hollow && !pinhole) || torus;
  });
  std::vector<VoxelGrid> filled;
  std::vector<int64_t> counts;
  for (int threads : {1, 2, 3}) {
    VoxelGrid g = shape;
    counts.push_back(FillCaves(g, threads));
    filled.push_back(std::move(g));
  }
  EXPECT_GT(counts[0], 1000);
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(counts[k], counts[0]) << "threads " << k + 1;
    EXPECT_TRUE(filled[k].states() == filled[0].states()) << "threads " << k + 1;
  }
}

}  // namespace
}  // namespace membrane
