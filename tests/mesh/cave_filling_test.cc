#include "core/mesh/cave_filling.h"

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

}  // namespace
}  // namespace membrane
