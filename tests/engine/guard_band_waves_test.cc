// The interior guard's band waves on bricks freeze exactly the voxels of two breadth-first
// waves run a voxel at a time (the outside's first at each distance, the core's kept a voxel
// off the hard ones): random grids and coarse classes, every brick size, data regions that
// end partway through a coarse voxel, on 1 and 3 threads.
#include "core/engine/guard_band_waves.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace membrane {
namespace {

constexpr int kPad = VoxelGrid::kPadding;

struct Case {
  VoxelGrid grid;
  std::array<int, 3> coarse_dims{};
  std::vector<uint8_t> classes;
  std::vector<int64_t> band;
};

bool InData(const VoxelGrid& g, const Coord& f) {
  for (int d = 0; d < 3; ++d)
    if (f[d] < kPad || f[d] >= g.dim(d) - kPad) return false;
  return true;
}

int64_t CoarseOf(const Case& c, int k, const Coord& f) {
  const int64_t x = (f.x - kPad) / k + kPad, y = (f.y - kPad) / k + kPad,
                z = (f.z - kPad) / k + kPad;
  return x + c.coarse_dims[0] * (y + c.coarse_dims[1] * z);
}

// A grid as Voxelize leaves it (padding outside, the data region's outer layer boundary,
// hard voxels at `hard` of the data region), coarse classes drawn at random (the coarse
// padding outside), and the core's fine soft voxels frozen.
Case RandomCase(const std::array<int, 3>& data, int k, double hard, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Case c;
  c.grid = VoxelGrid({data[0] + 2 * kPad, data[1] + 2 * kPad, data[2] + 2 * kPad}, {0, 0, 0},
                     1.0, OutsideState(0));
  VoxelGrid& g = c.grid;
  for (int z = kPad; z < g.dim(2) - kPad; ++z)
    for (int y = kPad; y < g.dim(1) - kPad; ++y)
      for (int x = kPad; x < g.dim(0) - kPad; ++x) {
        const bool edge = x == kPad || y == kPad || z == kPad || x == g.dim(0) - kPad - 1 ||
                          y == g.dim(1) - kPad - 1 || z == g.dim(2) - kPad - 1;
        const bool h = u(rng) < hard;
        g.set(g.Index(x, y, z), edge ? (h ? kBoundaryHard : kBoundarySoft)
                                     : (h ? kInsideHard : kInsideSoft));
      }
  for (int d = 0; d < 3; ++d) c.coarse_dims[d] = (data[d] + k - 1) / k + 2 * kPad;
  c.classes.assign(static_cast<size_t>(c.coarse_dims[0]) * c.coarse_dims[1] * c.coarse_dims[2],
                   kCoarseOutside);
  for (int z = kPad; z < c.coarse_dims[2] - kPad; ++z)
    for (int y = kPad; y < c.coarse_dims[1] - kPad; ++y)
      for (int x = kPad; x < c.coarse_dims[0] - kPad; ++x) {
        const double r = u(rng);
        c.classes[x + c.coarse_dims[0] * (y + c.coarse_dims[1] * z)] =
            r < 0.15 ? kCoarseOutside : r < 0.65 ? kCoarseBand : kCoarseCore;
      }
  for (int64_t i = 0; i < static_cast<int64_t>(c.classes.size()); ++i)
    if (c.classes[i] == kCoarseBand) c.band.push_back(i);
  for (int z = kPad; z < g.dim(2) - kPad; ++z)
    for (int y = kPad; y < g.dim(1) - kPad; ++y)
      for (int x = kPad; x < g.dim(0) - kPad; ++x) {
        const int64_t i = g.Index(x, y, z);
        if (c.classes[CoarseOf(c, k, {x, y, z})] == kCoarseCore && g.at(i) == kInsideSoft)
          g.set(i, kInsideFrozen);
      }
  return c;
}

// The two waves a voxel at a time.
int64_t ReferenceWaves(Case& c, int k) {
  VoxelGrid& g = c.grid;
  const auto band_soft = [&](const Coord& f) {
    return InData(g, f) && c.classes[CoarseOf(c, k, f)] == kCoarseBand &&
           g.at(g.Index(f)) == kInsideSoft;
  };
  const auto near_data = [&](int64_t i) {
    for (int64_t off : g.neighbour_offsets())
      if (IsHard(g.at(i + off))) return true;
    return false;
  };
  const Coord steps[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<uint8_t> seen(g.size(), 0);
  std::vector<Coord> outside, core, next;
  for (int z = kPad; z < g.dim(2) - kPad; ++z)
    for (int y = kPad; y < g.dim(1) - kPad; ++y)
      for (int x = kPad; x < g.dim(0) - kPad; ++x) {
        const Coord f{x, y, z};
        if (!band_soft(f)) continue;
        bool out = false, from_core = false;
        for (const Coord& d : steps) {
          const Coord n{x + d.x, y + d.y, z + d.z};
          if (!InData(g, n) || g.at(g.Index(n)) == kBoundarySoft ||
              c.classes[CoarseOf(c, k, n)] == kCoarseOutside) {
            out = true;
          } else {
            from_core = from_core || g.at(g.Index(n)) == kInsideFrozen;
          }
        }
        if (out) {
          seen[g.Index(f)] = 1;
          outside.push_back(f);
        } else if (from_core) {
          core.push_back(f);
        }
      }
  int64_t frozen = 0;
  next.clear();
  for (const Coord& f : core) {
    const int64_t i = g.Index(f);
    if (near_data(i)) continue;
    seen[i] = 1;
    g.set(i, kInsideFrozen);
    ++frozen;
    next.push_back(f);
  }
  core.swap(next);
  const auto advance = [&](std::vector<Coord>& front, bool freeze) {
    next.clear();
    for (const Coord& f : front)
      for (const Coord& d : steps) {
        const Coord n{f.x + d.x, f.y + d.y, f.z + d.z};
        const int64_t j = g.Index(n);
        if (!band_soft(n) || seen[j] || (freeze && near_data(j))) continue;
        seen[j] = 1;
        if (freeze) {
          g.set(j, kInsideFrozen);
          ++frozen;
        }
        next.push_back(n);
      }
    front.swap(next);
  };
  while (!outside.empty() || !core.empty()) {
    advance(outside, false);
    advance(core, true);
  }
  return frozen;
}

TEST(GuardBandWavesTest, FreezeWhatVoxelByVoxelWavesFreeze) {
  int cases = 0;
  for (int k = 2; k <= 4; ++k) {
    for (uint32_t seed = 1; seed <= 6; ++seed) {
      const double hard = seed <= 3 ? 0.01 : 0.06;
      const std::array<int, 3> data = {9 * k + static_cast<int>(seed) % k, 7 * k + 1,
                                       8 * k - 1};
      Case a = RandomCase(data, k, hard, seed * 7 + k);
      const int64_t expected = ReferenceWaves(a, k);
      for (int threads : {1, 3}) {
        Case b = RandomCase(data, k, hard, seed * 7 + k);
        absl::StatusOr<int64_t> frozen = FreezeBandByWaves(b.grid, b.coarse_dims, k, b.classes,
                                                           b.band, CancelToken::Never(), threads);
        ASSERT_TRUE(frozen.ok()) << frozen.status();
        EXPECT_EQ(*frozen, expected) << "k " << k << " seed " << seed << " threads " << threads;
        EXPECT_TRUE(a.grid.states() == b.grid.states())
            << "k " << k << " seed " << seed << " threads " << threads;
      }
      cases += expected > 0;
    }
  }
  // The waves reach into the band in most cases (not an empty comparison).
  EXPECT_GE(cases, 12);
}

// Fronts of thousands of coarse voxels, split between tasks: the same voxels on 1 and 3
// threads as a voxel at a time.
TEST(GuardBandWavesTest, SplitFrontsFreezeTheSameVoxels) {
  const std::array<int, 3> data = {4 * 40 + 1, 4 * 38 + 3, 4 * 36};
  Case a = RandomCase(data, 4, 0.02, 99);
  const int64_t expected = ReferenceWaves(a, 4);
  EXPECT_GT(expected, 0);
  for (int threads : {1, 3}) {
    Case b = RandomCase(data, 4, 0.02, 99);
    absl::StatusOr<int64_t> frozen = FreezeBandByWaves(b.grid, b.coarse_dims, 4, b.classes,
                                                       b.band, CancelToken::Never(), threads);
    ASSERT_TRUE(frozen.ok()) << frozen.status();
    EXPECT_EQ(*frozen, expected) << "threads " << threads;
    EXPECT_TRUE(a.grid.states() == b.grid.states()) << "threads " << threads;
  }
}

}  // namespace
}  // namespace membrane
