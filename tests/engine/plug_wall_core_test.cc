// The hole opening's wall-core tests: a plug in the core of a thin wall, whose faces have the
// outside right behind them, is told from a plug in a hole through a thick slab or a thin
// sheet, whose walls have the solid behind them; a plug through a wall thinner than a plane
// fit's block, between its two faces' data, from a hole lined with one surface.
#include "core/engine/plug_wall_core.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/engine/hard_voxel_points.h"
#include "core/engine/voxel_grid.h"
#include "core/engine/voxel_state.h"
#include "tests/engine/final_membrane_states.h"

namespace membrane {
namespace {

constexpr int kDim = 32;

// `state(x, y, z)` (outside, kInsideSoft or kInsideHard) for every voxel but the array border
// (outside), with the states of a final membrane (boundary beside the outside).
VoxelGrid Grid(const std::function<VoxelState(int, int, int)>& state) {
  VoxelGrid grid({kDim, kDim, kDim}, {0, 0, 0}, 1.0, OutsideState(1));
  for (int z = 1; z + 1 < kDim; ++z)
    for (int y = 1; y + 1 < kDim; ++y)
      for (int x = 1; x + 1 < kDim; ++x) grid.set(grid.Index(x, y, z), state(x, y, z));
  SetFinalMembraneStates(grid);
  return grid;
}

// A wall z in [13, 18): hard faces at z = 13 and 17, soft core, outside on both sides; a dig
// along x through the core at y = 16, z = 15, left closed by a plug at x = 16.
VoxelState WallWithDig(int x, int y, int z) {
  if (z < 13 || z > 17) return OutsideState(2);
  if (z == 13 || z == 17) return kInsideHard;
  if (y == 16 && z == 15 && x != 16) return OutsideState(3);
  return kInsideSoft;
}

TEST(PlugWallCoreTest, APlugBetweenDigsInAThinWallIsInItsCore) {
  const VoxelGrid grid = Grid(WallWithDig);
  const int64_t mid = grid.Index(16, 16, 15);
  EXPECT_TRUE(PlugInsideWallCore(grid, mid, {1, 0, 0}, 5, 3));
  // The faces' outside lies 1 voxel past them: a depth of 0 finds nothing behind them.
  EXPECT_FALSE(PlugInsideWallCore(grid, mid, {1, 0, 0}, 5, 0));
}

// A slab z in [6, 26) pierced along z by a hole of radius 3 around (16, 16), whose wall is hard
// and whose waist, z in [15, 17), is a soft plug.
VoxelState PiercedSlab(int x, int y, int z) {
  if (z < 6 || z >= 26) return OutsideState(2);
  const double r = std::hypot(x + 0.5 - 16, y + 0.5 - 16);
  if (r < 3) return z >= 15 && z < 17 ? kInsideSoft : OutsideState(2);
  if (r < 4 || z == 6 || z == 25) return kInsideHard;
  return kInsideSoft;
}

TEST(PlugWallCoreTest, AHolesPlugHasTheSolidBehindItsWall) {
  const VoxelGrid grid = Grid(PiercedSlab);
  EXPECT_FALSE(PlugInsideWallCore(grid, grid.Index(16, 16, 16), {0, 0, 1}, 5, 3));
}

// A sheet 3 voxels thick, z in [14, 17), with the same hole plugged at z = 15: across the plug
// the sheet's core lies behind the hole's wall, not the outside.
VoxelState PiercedSheet(int x, int y, int z) {
  if (z < 14 || z >= 17) return OutsideState(2);
  const double r = std::hypot(x + 0.5 - 16, y + 0.5 - 16);
  if (r < 3) return z == 15 ? kInsideSoft : OutsideState(2);
  if (r < 4 || z == 14 || z == 16) return kInsideHard;
  return kInsideSoft;
}

TEST(PlugWallCoreTest, AThinSheetsHoleIsNoWallCore) {
  const VoxelGrid grid = Grid(PiercedSheet);
  EXPECT_FALSE(PlugInsideWallCore(grid, grid.Index(16, 16, 15), {0, 0, 1}, 5, 3));
}

// Rays that meet no data (a plug in open soft space) say nothing.
TEST(PlugWallCoreTest, NoDataMetIsNoWallCore) {
  const VoxelGrid grid = Grid([](int, int, int) { return kInsideSoft; });
  EXPECT_FALSE(PlugInsideWallCore(grid, grid.Index(16, 16, 16), {0, 0, 1}, 5, 3));
}

// A wall 2 voxels thick, z in [15, 17), hard, the outside on both sides, whose two faces
// (z = 15.05 and 16.95, every 0.25 voxel) both miss the disc of radius `gap` around
// (16.5, 16.5): the voxels whose centre lies in it are soft, a plug through the wall along z.
VoxelState GappedWall(double gap, int x, int y, int z) {
  if (z < 15 || z >= 17) return OutsideState(2);
  return std::hypot(x + 0.5 - 16.5, y + 0.5 - 16.5) < gap ? kInsideSoft : kInsideHard;
}
std::vector<Point3f> GappedWallPoints(double gap) {
  std::vector<Point3f> points;
  for (double x = 1.125; x < kDim - 1; x += 0.25)
    for (double y = 1.125; y < kDim - 1; y += 0.25) {
      if (std::hypot(x - 16.5, y - 16.5) < gap) continue;
      for (float z : {15.05f, 16.95f})
        points.push_back({static_cast<float>(x), static_cast<float>(y), z});
    }
  return points;
}

// Across a plug through both faces' gaps (2 voxels wide), the rays meet the wall 2 voxels out,
// and every 3x3x3 block there holds both faces: two surfaces, no hole's wall.
TEST(PlugWallCoreTest, APlugThroughAThinWallsFacesIsBetweenThem) {
  const VoxelGrid grid = Grid([](int x, int y, int z) { return GappedWall(2.0, x, y, z); });
  const HardVoxelPoints points(grid, GappedWallPoints(2.0));
  const int64_t mid = grid.Index(16, 16, 15);
  ASSERT_FALSE(IsHard(grid.at(mid)));
  EXPECT_TRUE(PlugBetweenWallFaces(grid, points, mid, {0, 0, 1}, 5, 1, 0.25));
  // Faces 1.9 voxels apart spread about 0.95 from their plane: not for a spread of 1.
  EXPECT_FALSE(PlugBetweenWallFaces(grid, points, mid, {0, 0, 1}, 5, 1, 1.0));
  // Read as a narrow waist (rays meeting data within 2 steps), it is not read.
  EXPECT_FALSE(PlugBetweenWallFaces(grid, points, mid, {0, 0, 1}, 5, 2, 0.25));
}

// The pierced slab's hole with its wall scanned (the cylinder of radius 3, every 0.25 voxel
// along z and a 64th of a turn): the blocks the rays meet hold that one surface.
TEST(PlugWallCoreTest, AHolesWallIsOneSurface) {
  const VoxelGrid grid = Grid(PiercedSlab);
  std::vector<Point3f> wall;
  for (double z = 6.125; z < 26; z += 0.25)
    for (int k = 0; k < 64; ++k) {
      const double a = 2 * M_PI * k / 64;
      wall.push_back({static_cast<float>(16 + 3.05 * std::cos(a)),
                      static_cast<float>(16 + 3.05 * std::sin(a)), static_cast<float>(z)});
    }
  const HardVoxelPoints points(grid, wall);
  EXPECT_FALSE(PlugBetweenWallFaces(grid, points, grid.Index(16, 16, 16), {0, 0, 1}, 5, 1, 0.25));
}

}  // namespace
}  // namespace membrane
