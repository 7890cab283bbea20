#include "core/engine/voxel_topology.h"

#include <cmath>
#include <functional>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// A grid of side n whose voxels satisfying `solid` (voxel-centre coordinates) are
// boundary soft, all others outside.
VoxelGrid Solid(int n, const std::function<bool(double, double, double)>& solid) {
  VoxelGrid g({n, n, n}, {0, 0, 0}, 1.0, OutsideState(0));
  for (int z = 1; z < n - 1; ++z)
    for (int y = 1; y < n - 1; ++y)
      for (int x = 1; x < n - 1; ++x)
        if (solid(x + 0.5, y + 0.5, z + 0.5)) g.set(Coord{x, y, z}, kBoundarySoft);
  return g;
}

TEST(VoxelTopology, BallHasOneShellOfGenusZero) {
  auto t = ComputeVoxelTopology(Solid(24, [](double x, double y, double z) {
    return std::hypot(x - 12, y - 12, z - 12) < 8;
  }));
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{0});
  EXPECT_EQ(t.cavities, 0);
}

TEST(VoxelTopology, SolidTorusHasGenusOne) {
  auto t = ComputeVoxelTopology(Solid(32, [](double x, double y, double z) {
    const double r = std::hypot(x - 16, y - 16) - 9;
    return std::hypot(r, z - 16) < 4;
  }));
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{1});
}

TEST(VoxelTopology, TwoBallsAreTwoShells) {
  auto t = ComputeVoxelTopology(Solid(32, [](double x, double y, double z) {
    return std::hypot(x - 9, y - 9, z - 16) < 6 || std::hypot(x - 23, y - 23, z - 16) < 6;
  }));
  EXPECT_EQ(t.shells, 2);
  EXPECT_EQ(t.genus, (std::vector<int>{0, 0}));
}

TEST(VoxelTopology, VoxelsTouchingAlongAnEdgeAreOneShell) {
  VoxelGrid g({6, 6, 6}, {0, 0, 0}, 1.0, OutsideState(0));
  g.set(Coord{2, 2, 2}, kBoundaryHard);
  g.set(Coord{3, 3, 2}, kBoundaryHard);
  auto t = ComputeVoxelTopology(g);
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{0});
}

TEST(VoxelTopology, RingOfVoxelsTouchingAtCornersHasGenusOne) {
  // Four voxels, each touching the next only at an edge, closing a loop around (3,3).
  VoxelGrid g({7, 7, 7}, {0, 0, 0}, 1.0, OutsideState(0));
  g.set(Coord{2, 3, 3}, kBoundaryHard);
  g.set(Coord{3, 2, 3}, kBoundaryHard);
  g.set(Coord{4, 3, 3}, kBoundaryHard);
  g.set(Coord{3, 4, 3}, kBoundaryHard);
  auto t = ComputeVoxelTopology(g);
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.genus, std::vector<int>{1});
}

TEST(VoxelTopology, HollowBallReportsACavity) {
  auto t = ComputeVoxelTopology(Solid(24, [](double x, double y, double z) {
    const double r = std::hypot(x - 12, y - 12, z - 12);
    return r < 8 && r > 5;
  }));
  EXPECT_EQ(t.shells, 1);
  EXPECT_EQ(t.cavities, 1);
}

}  // namespace
}  // namespace membrane
