#include "core/engine/local_topology.h"

#include "gtest/gtest.h"

namespace membrane {
namespace {

uint32_t Bit(int dx, int dy, int dz) { return 1u << NeighbourBit(dx, dy, dz); }

// All 27 voxels of the block with z <= 0 are object: a half space.
uint32_t HalfSpace() {
  uint32_t m = 0;
  for (int dz = -1; dz <= 0; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) m |= Bit(dx, dy, dz);
  return m;
}

TEST(LocalTopology, VoxelOnAFlatSurfaceIsSimple) { EXPECT_TRUE(IsSimple(HalfSpace())); }

TEST(LocalTopology, VoxelOfAOneVoxelWallIsNotSimple) {
  // The plane z = 0 only: removing the centre pierces the wall (T6 = 2).
  uint32_t wall = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) wall |= Bit(dx, dy, 0);
  EXPECT_EQ(CountT6(~wall & kAll27), 2);
  EXPECT_FALSE(IsSimple(wall));
}

TEST(LocalTopology, VoxelJoiningTwoPartsIsNotSimple) {
  const uint32_t bridge = Bit(-1, 0, 0) | Bit(1, 0, 0);
  EXPECT_EQ(CountT26(bridge), 2);
  EXPECT_FALSE(IsSimple(bridge));
}

TEST(LocalTopology, IsolatedVoxelIsNotSimple) { EXPECT_FALSE(IsSimple(0)); }

TEST(LocalTopology, CornerContactCountsAsOneObjectComponent) {
  EXPECT_EQ(CountT26(Bit(-1, -1, -1) | Bit(0, 0, -1)), 1);
}

TEST(LocalTopology, Flood6DoesNotCrossEdges) {
  const uint32_t diagonal = Bit(-1, 0, 0) | Bit(0, -1, 0);
  EXPECT_EQ(Flood6(Bit(-1, 0, 0), diagonal), Bit(-1, 0, 0));
  EXPECT_EQ(Flood26(Bit(-1, 0, 0), diagonal), diagonal);
}

}  // namespace
}  // namespace membrane
