// The hole opening's wall-core test: a plug in the core of a thin wall, whose faces have the
// outside right behind them, is told from a plug in a hole through a thick slab or a thin
// sheet, whose walls have the solid behind them.
#include "core/engine/plug_wall_core.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

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

}  // namespace
}  // namespace membrane
