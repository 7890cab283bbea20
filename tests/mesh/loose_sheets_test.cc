#include "core/mesh/loose_sheets.h"

#include "core/engine/voxel_topology.h"
#include "gtest/gtest.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

using namespace membrane::testing;

TEST(LooseSheets, RemovesAComponentWithoutInsideVoxels) {
  VoxelGrid g = BallGrid(30, 7.5);
  // A frozen plate far from the ball: all boundary, no inside.
  for (int y = 4; y < 12; ++y)
    for (int x = 4; x < 12; ++x) g.set(Coord{x, y, 25}, kBoundaryFrozen);
  ASSERT_EQ(ComputeVoxelTopology(g).shells, 2);
  EXPECT_EQ(RemoveLooseSheets(g), 64);
  EXPECT_EQ(ComputeVoxelTopology(g).shells, 1);
}

TEST(LooseSheets, KeepsASheetAttachedToASolid) {
  VoxelGrid g = BallGrid(30, 7.5);
  const int64_t solid_before = [&] {
    int64_t n = 0;
    for (int64_t i = 0; i < g.size(); ++i) n += !IsOutside(g.at(i));
    return n;
  }();
  // A fin touching the ball: same 26-component, which has inside voxels.
  for (int z = 15; z < 26; ++z) g.set(Coord{15, 15, z}, kBoundaryFrozen);
  EXPECT_EQ(RemoveLooseSheets(g), 0);
  int64_t solid_after = 0;
  for (int64_t i = 0; i < g.size(); ++i) solid_after += !IsOutside(g.at(i));
  EXPECT_GT(solid_after, solid_before);
}

TEST(LooseSheets, KeepsEverySolidWithInsideVoxels) {
  VoxelGrid g = TwoBallsGrid(32, 6, 3);
  EXPECT_EQ(RemoveLooseSheets(g), 0);
  EXPECT_EQ(ComputeVoxelTopology(g).shells, 2);
}

}  // namespace
}  // namespace membrane
