#include "core/mesh/output_grid.h"

#include "gtest/gtest.h"

namespace membrane {
namespace {

// A grid `width` voxels long on its widest axis (thin on the others: only the widest counts).
VoxelGrid GridOfWidth(int width, double voxel_size) {
  return VoxelGrid({width, 3, 3}, {-1.0, 2.0, 0.5}, voxel_size);
}

TEST(OutputBitsForVoxel, RaisesTheBitsUntilTheStepIsWithinItsShareOfTheVoxel) {
  for (const int width : {134, 413, 821, 1295, 2600, 5000}) {
    const VoxelGrid grid = GridOfWidth(width, 0.0016);
    const int bits = OutputBitsForVoxel(grid, 11);
    EXPECT_GE(bits, 11);
    EXPECT_LE(OutputGrid(grid, bits).step(), kMaxOutputStepVoxels * grid.voxel_size())
        << width << " voxels, " << bits << " bits";
    // The fewest such bits: one less would be too coarse, unless that is below the asked 11.
    if (bits > 11) {
      EXPECT_GT(OutputGrid(grid, bits - 1).step(), kMaxOutputStepVoxels * grid.voxel_size())
          << width << " voxels, " << bits << " bits";
    }
  }
  // On the grids of the torus: 100k points (134 voxels) get 13 bits, 1M (413) 14, 10M (1295) 16.
  EXPECT_EQ(OutputBitsForVoxel(GridOfWidth(134, 0.0016), 11), 13);
  EXPECT_EQ(OutputBitsForVoxel(GridOfWidth(413, 0.0016), 11), 14);
  EXPECT_EQ(OutputBitsForVoxel(GridOfWidth(1295, 0.0016), 11), 16);
}

TEST(OutputBitsForVoxel, KeepsLosslessAndStopsAtThirtyBits) {
  EXPECT_EQ(OutputBitsForVoxel(GridOfWidth(5000, 1.0), 0), 0);
  EXPECT_EQ(OutputBitsForVoxel(GridOfWidth(5000, 1.0), 30), 30);
  // Bits asked above what the voxel needs are kept as asked.
  EXPECT_EQ(OutputBitsForVoxel(GridOfWidth(134, 1.0), 20), 20);
}

}  // namespace
}  // namespace membrane
