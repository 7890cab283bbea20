#include "core/pipeline/membrane_counts.h"

#include <array>
#include <cstdint>

#include "core/engine/voxel_state.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// The census a state at a time, as the statistics define it.
MembraneCounts Census(const VoxelGrid& grid) {
  MembraneCounts c;
  for (const VoxelState s : grid.states()) {
    if (IsOutside(s)) continue;
    const bool b = IsBoundary(s);
    if (IsHard(s)) {
      ++(b ? c.hard_voxels : c.inside_hard_voxels);
    } else if (IsFrozen(s)) {
      ++(b ? c.frozen_voxels : c.inside_frozen_voxels);
    } else {
      ++(b ? c.soft_voxels : c.inside_soft_voxels);
    }
  }
  return c;
}

void ExpectSameCounts(const MembraneCounts& a, const MembraneCounts& b) {
  EXPECT_EQ(a.hard_voxels, b.hard_voxels);
  EXPECT_EQ(a.frozen_voxels, b.frozen_voxels);
  EXPECT_EQ(a.soft_voxels, b.soft_voxels);
  EXPECT_EQ(a.inside_hard_voxels, b.inside_hard_voxels);
  EXPECT_EQ(a.inside_frozen_voxels, b.inside_frozen_voxels);
  EXPECT_EQ(a.inside_soft_voxels, b.inside_soft_voxels);
}

// A grid of 13x11x9 voxels (not a whole number of 8-state words, rows starting at every
// phase of a word) with an outside border layer: within it, runs of soft inside voxels and of
// outside voxels (labels 0 and 1, bit 0 set on the second) of every length from 1 to 20,
// broken by each other state in turn.
VoxelGrid MixedGrid() {
  VoxelGrid g({13, 11, 9}, {0, 0, 0}, 1.0);
  constexpr std::array<VoxelState, 8> kOthers = {kBoundarySoft,   kInsideHard,
                                                 kBoundaryHard,   kInsideFrozen,
                                                 kBoundaryFrozen, OutsideState(0),
                                                 OutsideState(1), OutsideState(126)};
  int run = 1, other = 0, left = run;
  bool inside = true;
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 11; ++y)
      for (int x = 0; x < 13; ++x) {
        const bool border = x == 0 || y == 0 || z == 0 || x == 12 || y == 10 || z == 8;
        VoxelState s = inside ? kInsideSoft : OutsideState(run % 2);
        if (left-- == 0) {
          s = kOthers[other++ % kOthers.size()];
          run = run % 20 + 1;
          left = run;
          inside = !inside;
        }
        g.set(Coord{x, y, z}, border ? OutsideState(0) : s);
      }
  return g;
}

TEST(MembraneCounts, CountsEveryStateAsTheCensusDoes) {
  const VoxelGrid g = MixedGrid();
  const MembraneCounts expected = Census(g);
  ASSERT_GT(expected.inside_soft_voxels, 0);
  ASSERT_GT(expected.inside_frozen_voxels, 0);
  ASSERT_GT(expected.soft_voxels, 0);
  ExpectSameCounts(CountMembrane(g), expected);
}

// A solid block (inside soft, its outer layer boundary, every other one hard) in a grid of
// 30^3: the long runs a membrane's grid holds, one shell of genus 0.
TEST(MembraneCounts, CountsASolidBlockAndItsTopology) {
  VoxelGrid g({30, 30, 30}, {0, 0, 0}, 1.0);
  for (int z = 0; z < 30; ++z)
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 30; ++x) {
        const auto in = [](int c, int lo, int hi) { return c >= lo && c < hi; };
        VoxelState s = OutsideState(0);
        if (in(x, 3, 27) && in(y, 5, 25) && in(z, 4, 26)) {
          const bool outer = x == 3 || x == 26 || y == 5 || y == 24 || z == 4 || z == 25;
          s = outer ? ((x + y + z) % 2 ? kBoundaryHard : kBoundarySoft) : kInsideSoft;
        }
        g.set(Coord{x, y, z}, s);
      }
  const MembraneCounts counts = CountMembrane(g);
  ExpectSameCounts(counts, Census(g));
  EXPECT_EQ(counts.inside_soft_voxels, 22 * 18 * 20);
  EXPECT_EQ(counts.shells, 1);
  ASSERT_EQ(counts.genus.size(), 1u);
  EXPECT_EQ(counts.genus[0], 0);
}

// A grid over the split size (2^24 voxels) holding every state, counted on 1 to 3 threads:
// the census and the topology of one thread.
TEST(MembraneCounts, TheSameCountsOnAnyThreadCount) {
  const std::array<int, 3> dims = {260, 258, 256};
  VoxelGrid g(dims, {0, 0, 0}, 1.0, OutsideState(0));
  constexpr std::array<VoxelState, 7> kSolid = {kInsideSoft,    kBoundarySoft,  kInsideHard,
                                                kBoundaryHard,  kInsideFrozen,  kBoundaryFrozen,
                                                kInsideSoft};
  uint32_t h = 12345;
  for (int z = 1; z < dims[2] - 1; ++z)
    for (int y = 1; y < dims[1] - 1; ++y)
      for (int x = 1; x < dims[0] - 1; ++x) {
        h = h * 1664525u + 1013904223u;
        const int dx = x - 130, dy = y - 129, dz = z - 128;
        if (dx * dx + dy * dy + dz * dz < 110 * 110 || (h >> 24) < 8)
          g.set(Coord{x, y, z}, kSolid[(h >> 8) % kSolid.size()]);
      }
  ASSERT_GE(g.size(), int64_t{1} << 24);
  const MembraneCounts one = CountMembrane(g);
  ExpectSameCounts(one, Census(g));
  ASSERT_GT(one.shells, 1);
  for (int threads : {2, 3}) {
    const MembraneCounts split = CountMembrane(g, threads);
    ExpectSameCounts(split, one);
    EXPECT_EQ(split.shells, one.shells) << threads << " threads";
    EXPECT_EQ(split.genus, one.genus) << threads << " threads";
  }
}

}  // namespace
}  // namespace membrane
