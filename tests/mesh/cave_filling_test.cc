#include "core/mesh/cave_filling.h"

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/engine/local_topology.h"
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

// FillCaves' contract done one voxel at a time on byte masks: the box filters by their 27
// voxels, the flood breadth first.
int64_t ReferenceFillCaves(VoxelGrid& g) {
  const std::array<int, 3>& n = g.dims();
  const int64_t count = g.size();
  auto index = [&](int x, int y, int z) { return x + int64_t{n[0]} * (y + int64_t{n[1]} * z); };
  auto inside = [&](int x, int y, int z) {
    return x >= 0 && y >= 0 && z >= 0 && x < n[0] && y < n[1] && z < n[2];
  };
  auto box = [&](const std::vector<char>& m, bool erode) {
    std::vector<char> out(count);
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x) {
          char v = erode ? 1 : 0;
          for (const Coord& d : kBlockSteps) {
            const char b = inside(x + d.x, y + d.y, z + d.z)
                               ? m[index(x + d.x, y + d.y, z + d.z)]
                               : (erode ? 1 : 0);
            v = erode ? (v & b) : (v | b);
          }
          out[index(x, y, z)] = v;
        }
    return out;
  };
  std::vector<char> outside(count);
  for (int64_t i = 0; i < count; ++i) outside[i] = IsOutside(g.at(i)) ? 1 : 0;
  const std::vector<char> deep = box(outside, /*erode=*/true);
  std::vector<char> reached(count, 0);
  std::vector<Coord> queue;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x)
        if (g.OnArrayBorder(Coord{x, y, z}) && deep[index(x, y, z)]) {
          reached[index(x, y, z)] = 1;
          queue.push_back(Coord{x, y, z});
        }
  for (size_t head = 0; head < queue.size(); ++head) {
    const Coord c = queue[head];
    for (int k = 0; k < 27; ++k) {
      if (!IsFaceStep(k)) continue;
      const Coord d = kBlockSteps[k];
      const Coord to{c.x + d.x, c.y + d.y, c.z + d.z};
      if (!inside(to.x, to.y, to.z)) continue;
      const int64_t j = index(to.x, to.y, to.z);
      if (deep[j] && !reached[j]) {
        reached[j] = 1;
        queue.push_back(to);
      }
    }
  }
  const std::vector<char> near = box(reached, /*erode=*/false);
  std::vector<int64_t> caves;
  for (int64_t i = 0; i < count; ++i)
    if (outside[i] && !near[i] && !g.OnArrayBorder(g.CoordOf(i))) caves.push_back(i);
  auto solid = [](VoxelState v) { return !IsOutside(v); };
  int64_t filled = 0;
  for (bool progress = true; progress;) {
    progress = false;
    std::vector<int64_t> left;
    for (int64_t i : caves) {
      if (IsSimple(NeighbourhoodMask(g, i, solid))) {
        g.set(i, kBoundarySoft);
        ++filled;
        progress = true;
      } else {
        left.push_back(i);
      }
    }
    caves.swap(left);
  }
  return filled;
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

// Random solids in grids of random shapes (two outside layers on the border, as the shrink's
// grids have): rows of any length against the words of the bit masks, walls with gaps and
// slots of one to three voxels. The same grid as the contract done voxel by voxel.
TEST(CaveFilling, SameGridAsTheContractVoxelByVoxel) {
  std::mt19937 rng(21);
  int64_t filled_total = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::uniform_int_distribution<int> side(6, trial < 45 ? 24 : 75);
    const std::array<int, 3> n = {side(rng), side(rng), side(rng)};
    VoxelGrid g(n, {0, 0, 0}, 1.0, OutsideState(0));
    const double density = std::uniform_real_distribution<double>(0.3, 0.9)(rng);
    std::bernoulli_distribution solid(density);
    for (int z = 2; z < n[2] - 2; ++z)
      for (int y = 2; y < n[1] - 2; ++y)
        for (int x = 2; x < n[0] - 2; ++x)
          if (solid(rng)) g.set(Coord{x, y, z}, kInsideSoft);
    VoxelGrid want = g;
    const int64_t want_filled = ReferenceFillCaves(want);
    const int64_t filled = FillCaves(g, 1 + trial % 3);
    ASSERT_EQ(filled, want_filled) << "trial " << trial;
    ASSERT_TRUE(g.states() == want.states()) << "trial " << trial;
    filled_total += filled;
  }
  EXPECT_GT(filled_total, 1000);
}

}  // namespace
}  // namespace membrane
