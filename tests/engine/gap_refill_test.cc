// The refill of channels carved through data gaps: an outside channel whose walls hold no data,
// entered through a gap in a scanned skin, returns to the solid; a concavity with scanned walls
// and a hole through the solid keep their shape and their topology.
#include "core/engine/gap_refill.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <utility>
#include <vector>

#include "core/engine/membrane_invariants.h"
#include "core/engine/voxel_topology.h"
#include "tests/engine/final_membrane_states.h"

namespace membrane {
namespace {

constexpr int kN = 30;  // the solid box's side
constexpr int kAt = 4;  // the box's first voxel on each axis (padding and an outside layer)

// A final membrane around the box [kAt, kAt + kN)^3: its skin hard (a scanned surface) except
// where `gap(x, y, z)` (box coordinates) holds, the voxels where `carved` holds outside
// (generation 9), the rest of the grid outside (generation 1). Positions and frozen states as
// the shrink leaves them: a non-outside voxel beside the outside is BOUNDARY, a soft one with
// an outside face neighbour FROZEN.
using BoxPredicate = std::function<bool(int, int, int)>;
VoxelGrid Box(const BoxPredicate& gap, const BoxPredicate& carved) {
  const int dim = kN + 2 * kAt;
  VoxelGrid grid({dim, dim, dim}, {0, 0, 0}, 1.0, OutsideState(1));
  for (int z = 0; z < kN; ++z)
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) {
        const int64_t v = grid.Index(x + kAt, y + kAt, z + kAt);
        const bool skin = std::min({x, y, z, kN - 1 - x, kN - 1 - y, kN - 1 - z}) == 0;
        if (carved(x, y, z)) {
          grid.set(v, OutsideState(9));
        } else {
          grid.set(v, skin && !gap(x, y, z) ? kInsideHard : kInsideSoft);
        }
      }
  SetFinalMembraneStates(grid);
  return grid;
}

bool Never(int, int, int) { return false; }

int64_t OutsideIn(const VoxelGrid& grid, int z_from) {
  int64_t count = 0;
  for (int z = z_from; z < kN; ++z)
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x)
        count += IsOutside(grid.at(grid.Index(x + kAt, y + kAt, z + kAt)));
  return count;
}

// Every voxel of the box where `where` holds that is not outside made hard (a scanned
// surface), its position kept.
void MakeHard(VoxelGrid& grid, const BoxPredicate& where) {
  for (int z = 0; z < kN; ++z)
    for (int y = 0; y < kN; ++y)
      for (int x = 0; x < kN; ++x) {
        const int64_t v = grid.Index(x + kAt, y + kAt, z + kAt);
        if (IsOutside(grid.at(v)) || !where(x, y, z)) continue;
        grid.set(v, IsBoundary(grid.at(v)) ? kBoundaryHard : kInsideHard);
      }
}

// Runs the refill on `grid` with `options` and expects it to leave every voxel as it was;
// returns its statistics.
GapRefillStats ExpectNothingRefilled(VoxelGrid& grid, const GapRefillOptions& options) {
  const VoxelStates before = grid.states();
  absl::StatusOr<GapRefillStats> stats = RefillGapChannels(grid, options, CancelToken::Never());
  EXPECT_TRUE(stats.ok()) << stats.status();
  if (!stats.ok()) return {};
  EXPECT_EQ(stats->refilled_voxels, 0);
  EXPECT_EQ(grid.states(), before);
  return *stats;
}

void ExpectValidMembrane(const VoxelGrid& grid) {
  const absl::Status s = CheckMembraneInvariants(grid, InvariantOptions{});
  EXPECT_TRUE(s.ok()) << s;
}

// A 10 x 10 gap in the bottom skin and a channel 8 x 8 wide carved from it 20 voxels up into
// the solid: the channel's walls hold no data, and from inside it every ray but the way out
// enters such a wall. It is refilled up to gap_radius voxels from the skin's data; the outside
// below the gap (rays into the solid only upwards) stays.
TEST(RefillGapChannels, AChannelThroughAGapIsRefilled) {
  auto gap = [](int x, int y, int z) { return z == 0 && x >= 10 && x < 20 && y >= 10 && y < 20; };
  auto channel = [](int x, int y, int z) {
    return z < 20 && x >= 11 && x < 19 && y >= 11 && y < 19;
  };
  VoxelGrid grid = Box(gap, channel);
  ExpectValidMembrane(grid);
  ASSERT_EQ(OutsideIn(grid, 3), 8 * 8 * 17);
  const VoxelTopology before = ComputeVoxelTopology(grid);
  absl::StatusOr<GapRefillStats> stats =
      RefillGapChannels(grid, GapRefillOptions{}, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(OutsideIn(grid, 3), 0);
  EXPECT_GE(stats->refilled_voxels, 8 * 8 * 17);
  for (int y = 0; y < kAt; ++y)  // below the box
    EXPECT_TRUE(IsOutside(grid.at(grid.Index(kAt + 15, y, kAt + 15))));
  EXPECT_TRUE(IsOutside(grid.at(grid.Index(kAt + 15, kAt + 15, kAt - 1))));
  ExpectValidMembrane(grid);
  const VoxelTopology after = ComputeVoxelTopology(grid);
  EXPECT_EQ(after.shells, before.shells);
  EXPECT_EQ(after.genus, before.genus);
}

// The rows and the seeds read on several threads (a slab of z planes each): the channel,
// the hollow behind a slot and the handle through a hollow come out as on one thread, voxel
// for voxel, with the same counts.
TEST(RefillGapChannels, TheSameGridOnAnyThreadCount) {
  auto gap = [](int x, int y, int z) { return z == 0 && x >= 10 && x < 20 && y >= 10 && y < 20; };
  auto channel = [](int x, int y, int z) {
    return z < 20 && x >= 11 && x < 19 && y >= 11 && y < 19;
  };
  auto slots = [](int x, int y, int z) {
    return z == 0 && y >= 11 && y < 19 && ((x >= 5 && x < 8) || (x >= 22 && x < 25));
  };
  auto hollow = [](int x, int y, int z) {
    return (z >= 1 && z < 12 && x >= 1 && x < kN - 1 && y >= 1 && y < kN - 1) ||
           (z == 0 && (x == 6 || x == 23) && y >= 12 && y < 18);
  };
  const std::pair<BoxPredicate, BoxPredicate> cases[] = {{gap, channel}, {slots, hollow}};
  for (const auto& [skin_gap, carved] : cases) {
    VoxelGrid one = Box(skin_gap, carved);
    absl::StatusOr<GapRefillStats> a = RefillGapChannels(one, GapRefillOptions{},
                                                         CancelToken::Never(), /*threads=*/1);
    ASSERT_TRUE(a.ok()) << a.status();
    ASSERT_GT(a->refilled_voxels, 0);
    for (int threads : {2, 3, 16}) {
      VoxelGrid many = Box(skin_gap, carved);
      absl::StatusOr<GapRefillStats> b =
          RefillGapChannels(many, GapRefillOptions{}, CancelToken::Never(), threads);
      ASSERT_TRUE(b.ok()) << b.status();
      EXPECT_EQ(b->refilled_voxels, a->refilled_voxels) << threads << " threads";
      EXPECT_EQ(b->pocket_voxels, a->pocket_voxels) << threads << " threads";
      EXPECT_EQ(b->loops_closed, a->loops_closed) << threads << " threads";
      EXPECT_TRUE(many.states() == one.states()) << threads << " threads";
    }
  }
}

// The same channel where the scanner saw its walls (hard voxels around it): a concavity seen
// from outside, left as it is.
TEST(RefillGapChannels, AChannelWithScannedWallsStays) {
  auto gap = [](int x, int y, int z) { return z == 0 && x >= 10 && x < 20 && y >= 10 && y < 20; };
  auto channel = [](int x, int y, int z) {
    return z < 20 && x >= 11 && x < 19 && y >= 11 && y < 19;
  };
  VoxelGrid grid = Box(gap, channel);
  MakeHard(grid, [](int x, int y, int z) {
    return z <= 20 && x >= 10 && x < 20 && y >= 10 && y < 20;
  });
  ExpectValidMembrane(grid);
  ExpectNothingRefilled(grid, GapRefillOptions{});
}

// A hole 8 x 8 wide through the box between two gaps, its walls without data: the fill may
// narrow it, but never closes it (each added voxel is simple): one shell of genus 1.
TEST(RefillGapChannels, AHoleThroughGapWallsStaysOpen) {
  auto gap = [](int x, int y, int) { return x >= 10 && x < 20 && y >= 10 && y < 20; };
  auto hole = [](int x, int y, int) { return x >= 11 && x < 19 && y >= 11 && y < 19; };
  VoxelGrid grid = Box(gap, hole);
  ExpectValidMembrane(grid);
  ASSERT_EQ(ComputeVoxelTopology(grid).genus, std::vector<int>{1});
  absl::StatusOr<GapRefillStats> stats =
      RefillGapChannels(grid, GapRefillOptions{}, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  ExpectValidMembrane(grid);
  const VoxelTopology after = ComputeVoxelTopology(grid);
  EXPECT_EQ(after.shells, 1);
  EXPECT_EQ(after.genus, std::vector<int>{1});
}

// A channel has one way out: with none allowed (max_open_rays 0) its voxels, whose rays leave
// downwards through the gap, are not refilled.
TEST(RefillGapChannels, RaysOpenToTheBorderAreCounted) {
  auto gap = [](int x, int y, int z) { return z == 0 && x >= 10 && x < 20 && y >= 10 && y < 20; };
  auto channel = [](int x, int y, int z) {
    return z < 20 && x >= 11 && x < 19 && y >= 11 && y < 19;
  };
  VoxelGrid grid = Box(gap, channel);
  GapRefillOptions options;
  options.max_open_rays = 0;
  ExpectNothingRefilled(grid, options);
}

// A hollow carved behind the scanned skin through a narrow slot (3 x 8 voxels in the bottom
// skin): the chamber's walls are the skin's data seen from inside, with the outside right
// behind them, so it is a pocket of the solid's interior, refilled whole although it touches
// the data; the slot and the outside below it stay, the topology is unchanged.
TEST(RefillGapChannels, AHollowBehindTheSkinThroughASlotIsRefilled) {
  auto slot = [](int x, int y, int z) { return z == 0 && x >= 14 && x < 17 && y >= 11 && y < 19; };
  auto carved = [](int x, int y, int z) {
    return (z >= 1 && z < 12 && x >= 1 && x < kN - 1 && y >= 1 && y < kN - 1) ||
           (z == 0 && x == 15 && y >= 12 && y < 18);
  };
  VoxelGrid grid = Box(slot, carved);
  ExpectValidMembrane(grid);
  ASSERT_GT(OutsideIn(grid, 1), 10 * 28 * 28);
  const VoxelTopology before = ComputeVoxelTopology(grid);
  absl::StatusOr<GapRefillStats> stats =
      RefillGapChannels(grid, GapRefillOptions{}, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(OutsideIn(grid, 1), 0);
  EXPECT_GT(stats->pocket_voxels, 0);
  EXPECT_EQ(stats->loops_closed, 0);
  EXPECT_TRUE(IsOutside(grid.at(grid.Index(kAt + 15, kAt + 15, kAt - 1))));
  ExpectValidMembrane(grid);
  const VoxelTopology after = ComputeVoxelTopology(grid);
  EXPECT_EQ(after.shells, before.shells);
  EXPECT_EQ(after.genus, before.genus);
  // Without pockets only the voxels far from the data could return: the chamber stays open.
  VoxelGrid plain = Box(slot, carved);
  GapRefillOptions options;
  options.pocket_backed_rays = 0;
  ASSERT_TRUE(RefillGapChannels(plain, options, CancelToken::Never()).ok());
  EXPECT_GT(OutsideIn(plain, 1), 0);
}

// The same hollow entered through two slots: the outside runs in through one and out through
// the other, a handle of the solid around the solid's own interior. Refilled with the
// additions that close such a loop, the box is genus 0 again; with simple additions only
// (max_pocket_loops 0) the handle stays.
TEST(RefillGapChannels, AHandleThroughAHollowIsClosed) {
  auto slots = [](int x, int y, int z) {
    return z == 0 && y >= 11 && y < 19 && ((x >= 5 && x < 8) || (x >= 22 && x < 25));
  };
  auto carved = [](int x, int y, int z) {
    return (z >= 1 && z < 12 && x >= 1 && x < kN - 1 && y >= 1 && y < kN - 1) ||
           (z == 0 && (x == 6 || x == 23) && y >= 12 && y < 18);
  };
  VoxelGrid grid = Box(slots, carved);
  ExpectValidMembrane(grid);
  ASSERT_EQ(ComputeVoxelTopology(grid).genus, std::vector<int>{1});
  VoxelGrid simple_only = grid;
  absl::StatusOr<GapRefillStats> stats =
      RefillGapChannels(grid, GapRefillOptions{}, CancelToken::Never());
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->loops_closed, 1);
  ExpectValidMembrane(grid);
  const VoxelTopology after = ComputeVoxelTopology(grid);
  EXPECT_EQ(after.shells, 1);
  EXPECT_EQ(after.cavities, 0);
  EXPECT_EQ(after.genus, std::vector<int>{0});
  GapRefillOptions options;
  options.max_pocket_loops = 0;
  ASSERT_TRUE(RefillGapChannels(simple_only, options, CancelToken::Never()).ok());
  EXPECT_EQ(ComputeVoxelTopology(simple_only).genus, std::vector<int>{1});
}

// A hole through the box whose walls the scanner saw (hard voxels around it, the solid's
// interior behind them): a real tunnel, whose rays leave on both sides. Nothing changes.
TEST(RefillGapChannels, AScannedHoleThroughTheBoxStays) {
  auto gap = [](int x, int y, int) { return x >= 10 && x < 20 && y >= 10 && y < 20; };
  auto hole = [](int x, int y, int) { return x >= 11 && x < 19 && y >= 11 && y < 19; };
  VoxelGrid grid = Box(gap, hole);
  MakeHard(grid, gap);
  ExpectValidMembrane(grid);
  ExpectNothingRefilled(grid, GapRefillOptions{});
  EXPECT_EQ(ComputeVoxelTopology(grid).genus, std::vector<int>{1});
}

// An open container: a cup whose walls and bottom are 2 voxels thick with data on both
// sides (a scanned mug), its inside outside up to the open top. From inside it, 5 of the 6
// rays meet a data wall with the outside right behind it, as in a hollow behind a skin; but
// the cup is open on its whole top, not through a slot, and its inside is a concavity the
// membrane reached from above. Nothing is refilled.
TEST(RefillGapChannels, AnOpenContainerKeepsItsInside) {
  auto inside = [](int x, int y, int z) {
    return z >= 2 && x >= 2 && x < kN - 2 && y >= 2 && y < kN - 2;
  };
  VoxelGrid grid = Box(Never, inside);
  // The inner faces of the walls and the bottom hold data too: the voxels beside the inside.
  MakeHard(grid, [&](int x, int y, int z) {
    const int64_t v = grid.Index(x + kAt, y + kAt, z + kAt);
    for (int64_t off : grid.neighbour_offsets())
      if (IsOutside(grid.at(v + off)) && GenerationLabel(grid.at(v + off)) == 9) return true;
    return false;
  });
  SetFinalMembraneStates(grid);
  ExpectValidMembrane(grid);
  EXPECT_EQ(ExpectNothingRefilled(grid, GapRefillOptions{}).pocket_voxels, 0);
}

// A random final membrane for the refill: a solid box at a random place in a grid of random
// size (no side a multiple of 8), its skin hard but for random gaps, from each gap a channel
// carved into the solid, behind some of them a hollow under the skin, and random notches in
// the skin. Draws from std::mt19937 alone (its output is fixed by the standard), so a seed
// gives the same grid everywhere.
VoxelGrid RandomCarvedBox(uint32_t seed) {
  std::mt19937 rng(seed);
  auto pick = [&](int lo, int hi) { return lo + static_cast<int>(rng() % (hi - lo + 1)); };
  std::array<int, 3> dims, at, side;
  for (int d = 0; d < 3; ++d) {
    side[d] = pick(18, 34);
    do dims[d] = side[d] + pick(8, 40);
    while (dims[d] % 8 == 0);
    at[d] = pick(3, dims[d] - side[d] - 3);
  }
  struct Box3 {
    std::array<int, 3> lo, hi;  // box coordinates, inclusive
    bool Holds(const std::array<int, 3>& p) const {
      for (int d = 0; d < 3; ++d)
        if (p[d] < lo[d] || p[d] > hi[d]) return false;
      return true;
    }
  };
  std::vector<Box3> gaps, carved;
  const int channels = pick(2, 5);
  for (int k = 0; k < channels; ++k) {
    const int a = pick(0, 2), far = pick(0, 1);
    Box3 gap, channel;
    for (int d = 0; d < 3; ++d) {
      if (d == a) continue;
      const int width = pick(2, side[d] / 2);
      gap.lo[d] = pick(1, side[d] - width - 2);
      gap.hi[d] = gap.lo[d] + width + 1;
      channel.lo[d] = gap.lo[d] + 1;
      channel.hi[d] = gap.hi[d] - 1;
    }
    const int depth = pick(2, side[a] - 4);
    gap.lo[a] = gap.hi[a] = far ? side[a] - 1 : 0;
    channel.lo[a] = far ? side[a] - depth : 0;
    channel.hi[a] = far ? side[a] - 1 : depth - 1;
    gaps.push_back(gap);
    carved.push_back(channel);
    if (pick(0, 2) == 0) {  // a hollow under the skin, entered through the channel
      Box3 hollow = channel;
      for (int d = 0; d < 3; ++d) {
        if (d == a) continue;
        hollow.lo[d] = std::max(1, channel.lo[d] - pick(1, 6));
        hollow.hi[d] = std::min(side[d] - 2, channel.hi[d] + pick(1, 6));
      }
      hollow.lo[a] = far ? side[a] - 1 - pick(2, 6) : 1;
      hollow.hi[a] = far ? side[a] - 2 : pick(2, 6);
      carved.push_back(hollow);
    }
  }
  const int notches = pick(0, 12);
  for (int k = 0; k < notches; ++k) {
    const int a = pick(0, 2), far = pick(0, 1);
    Box3 notch;
    for (int d = 0; d < 3; ++d) notch.lo[d] = notch.hi[d] = pick(1, side[d] - 2);
    notch.lo[a] = notch.hi[a] = far ? side[a] - 1 : 0;
    carved.push_back(notch);
  }
  VoxelGrid grid(dims, {0, 0, 0}, 1.0, OutsideState(1));
  std::array<int, 3> p;
  for (p[2] = 0; p[2] < side[2]; ++p[2])
    for (p[1] = 0; p[1] < side[1]; ++p[1])
      for (p[0] = 0; p[0] < side[0]; ++p[0]) {
        const int64_t v = grid.Index(p[0] + at[0], p[1] + at[1], p[2] + at[2]);
        const bool skin = std::min({p[0], p[1], p[2], side[0] - 1 - p[0], side[1] - 1 - p[1],
                                    side[2] - 1 - p[2]}) == 0;
        auto in = [&](const std::vector<Box3>& boxes) {
          return std::any_of(boxes.begin(), boxes.end(), [&](const Box3& b) { return b.Holds(p); });
        };
        if (in(carved)) {
          grid.set(v, OutsideState(9));
        } else {
          grid.set(v, skin && !in(gaps) ? kInsideHard : kInsideSoft);
        }
      }
  SetFinalMembraneStates(grid);
  return grid;
}

// FNV-1a of the grid's states: the refill's result in one number.
uint64_t StatesHash(const VoxelGrid& grid) {
  uint64_t h = 14695981039346656037ull;
  for (VoxelState s : grid.states()) h = (h ^ s) * 1099511628211ull;
  return h;
}

// On random carved boxes the refill gives, on 1 and 2 threads, the grids and counts that
// main 4639d03's refill gave (hash sets for the region, a voxel walk for each ray, each byte
// of the scans tested): the bitsets, the block walks and the word scans change no voxel.
TEST(RefillGapChannels, RandomCarvedBoxesAsBefore) {
  struct Expected {
    uint32_t seed;
    int64_t refilled, pockets;
    int loops;
    uint64_t hash;
  };
  const Expected expected[] = {
      {1, 1748, 0, 0, 12164513874134307355ull}, {2, 1143, 0, 0, 11187835269516572331ull},
      {3, 480, 56, 0, 14898563732693365589ull},  {4, 623, 0, 0, 15395231593075902084ull},
      {5, 5, 0, 0, 2664934846284182520ull},      {6, 583, 0, 0, 6079270907103977274ull},
      {7, 704, 0, 0, 13301417748171562950ull},   {8, 3149, 212, 0, 6463489895353110560ull},
  };
  for (const Expected& e : expected)
    for (int threads : {1, 2}) {
      VoxelGrid grid = RandomCarvedBox(e.seed);
      ExpectValidMembrane(grid);
      absl::StatusOr<GapRefillStats> stats =
          RefillGapChannels(grid, GapRefillOptions{}, CancelToken::Never(), threads);
      ASSERT_TRUE(stats.ok()) << stats.status();
      EXPECT_EQ(stats->refilled_voxels, e.refilled) << "seed " << e.seed << ", " << threads;
      EXPECT_EQ(stats->pocket_voxels, e.pockets) << "seed " << e.seed << ", " << threads;
      EXPECT_EQ(stats->loops_closed, e.loops) << "seed " << e.seed << ", " << threads;
      EXPECT_EQ(StatesHash(grid), e.hash) << "seed " << e.seed << ", " << threads;
      ExpectValidMembrane(grid);
    }
}

TEST(RefillGapChannels, DisabledChangesNothing) {
  auto gap = [](int x, int y, int z) { return z == 0 && x >= 10 && x < 20 && y >= 10 && y < 20; };
  auto channel = [](int x, int y, int z) {
    return z < 20 && x >= 11 && x < 19 && y >= 11 && y < 19;
  };
  VoxelGrid grid = Box(gap, channel);
  GapRefillOptions options;
  options.enabled = false;
  ExpectNothingRefilled(grid, options);
}

TEST(RefillGapChannels, OptionsOutOfRangeAreRefused) {
  VoxelGrid grid = Box(Never, Never);
  GapRefillOptions options;
  options.gap_radius = 0;
  EXPECT_EQ(RefillGapChannels(grid, options, CancelToken::Never()).status().code(),
            absl::StatusCode::kInvalidArgument);
  options = GapRefillOptions{};
  options.min_enclosed_rays = 7;
  const absl::Status s = RefillGapChannels(grid, options, CancelToken::Never()).status();
  EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("min_enclosed_rays 7"), absl::string_view::npos) << s;
  options = GapRefillOptions{};
  options.max_open_rays = -1;
  EXPECT_EQ(RefillGapChannels(grid, options, CancelToken::Never()).status().code(),
            absl::StatusCode::kInvalidArgument);
  options = GapRefillOptions{};
  options.pocket_backed_rays = 7;
  EXPECT_EQ(RefillGapChannels(grid, options, CancelToken::Never()).status().code(),
            absl::StatusCode::kInvalidArgument);
  options = GapRefillOptions{};
  options.pocket_wall_depth = 0;
  EXPECT_EQ(RefillGapChannels(grid, options, CancelToken::Never()).status().code(),
            absl::StatusCode::kInvalidArgument);
  options = GapRefillOptions{};
  options.max_open_pocket_share = 1.5;
  EXPECT_EQ(RefillGapChannels(grid, options, CancelToken::Never()).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace membrane
