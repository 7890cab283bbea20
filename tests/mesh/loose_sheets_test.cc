#include "core/mesh/loose_sheets.h"

#include <array>
#include <cstdint>
#include <random>
#include <vector>

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

// Plates on many planes, loose and attached, beside two balls: the scan's planes on 1, 2 and
// 3 threads remove the same voxels.
TEST(LooseSheets, SameGridForAnyThreadCount) {
  VoxelGrid shape = TwoBallsGrid(48, 9, 3);
  for (int z = 4; z < 44; z += 6)
    for (int y = 3; y < 10; ++y)
      for (int x = 3; x < 45; ++x) shape.set(Coord{x, y, z}, kBoundaryFrozen);
  for (int z = 3; z < 45; ++z) shape.set(Coord{24, 24, z}, kBoundaryFrozen);  // through a ball
  std::vector<VoxelGrid> cleaned;
  std::vector<int64_t> removed;
  for (int threads : {1, 2, 3}) {
    VoxelGrid g = shape;
    removed.push_back(RemoveLooseSheets(g, threads));
    cleaned.push_back(std::move(g));
  }
  EXPECT_GE(removed[0], 7 * 7 * 42);
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(removed[k], removed[0]) << "threads " << k + 1;
    EXPECT_TRUE(cleaned[k].states() == cleaned[0].states()) << "threads " << k + 1;
  }
}

// Random boundary voxels (sheets and strands that cross many planes, some touching a random
// inside voxel) in grids down to 3 voxels a side: the slabs' flood on 1 and 3 threads, for one
// slab, a few and one a plane, gives the one-thread flood's grid; and RemoveLooseSheets' own
// threaded path on a grid large enough to take it.
TEST(LooseSheets, SlabsGiveTheOneThreadFloodsGrid) {
  std::mt19937 rng(23);
  auto random_grid = [&](const std::array<int, 3>& n) {
    VoxelGrid g(n, {0, 0, 0}, 1.0, OutsideState(0));
    const double boundary = std::uniform_real_distribution<double>(0.03, 0.3)(rng);
    const double inside = std::uniform_real_distribution<double>(0.0, 0.01)(rng);
    std::uniform_real_distribution<double> u(0, 1);
    for (int z = 1; z < n[2] - 1; ++z)
      for (int y = 1; y < n[1] - 1; ++y)
        for (int x = 1; x < n[0] - 1; ++x) {
          const double r = u(rng);
          if (r < inside) g.set(Coord{x, y, z}, kInsideSoft);
          else if (r < inside + boundary) g.set(Coord{x, y, z}, kBoundaryFrozen);
        }
    return g;
  };
  int64_t removed_total = 0, kept_total = 0;
  for (int trial = 0; trial < 150; ++trial) {
    std::uniform_int_distribution<int> side(3, trial < 120 ? 20 : 60);
    const std::array<int, 3> n = {side(rng), side(rng), side(rng)};
    const VoxelGrid shape = random_grid(n);
    VoxelGrid serial = shape;
    const int64_t removed = RemoveLooseSheets(serial, 1);
    removed_total += removed;
    for (int64_t i = 0; i < serial.size(); ++i) kept_total += IsBoundary(serial.at(i));
    for (int threads : {1, 3})
      for (int slabs : {1, 2, 5, n[2]}) {
        VoxelGrid g = shape;
        ASSERT_EQ(RemoveLooseSheetsOnSlabs(g, threads, slabs), removed)
            << "trial " << trial << " threads " << threads << " slabs " << slabs;
        ASSERT_TRUE(g.states() == serial.states())
            << "trial " << trial << " threads " << threads << " slabs " << slabs;
      }
  }
  EXPECT_GT(removed_total, 1000);
  EXPECT_GT(kept_total, 1000);

  const std::array<int, 3> n = {256, 256, 257};
  const VoxelGrid shape = random_grid(n);
  ASSERT_GE(shape.size(), int64_t{1} << 24);
  VoxelGrid serial = shape, threaded = shape;
  const int64_t removed = RemoveLooseSheets(serial, 1);
  EXPECT_EQ(RemoveLooseSheets(threaded, 3), removed);
  EXPECT_TRUE(threaded.states() == serial.states());
}

}  // namespace
}  // namespace membrane
