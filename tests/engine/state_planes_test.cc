#include "core/engine/state_planes.h"

#include <algorithm>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// Every state a voxel can hold, outside labels included.
std::vector<VoxelState> AllStates() {
  std::vector<VoxelState> s = {kInsideSoft,   kBoundarySoft,  kInsideHard,
                               kBoundaryHard, kInsideFrozen, kBoundaryFrozen};
  for (int label = 0; label <= kMaxGenerationLabel; ++label) s.push_back(OutsideState(label));
  return s;
}

std::vector<VoxelState> RandomStates(int64_t n, uint32_t seed) {
  const std::vector<VoxelState> all = AllStates();
  std::mt19937 rng(seed);
  std::vector<VoxelState> s(static_cast<size_t>(n));
  for (VoxelState& v : s) v = all[rng() % all.size()];
  return s;
}

bool Expected(StatePredicate p, VoxelState s) {
  switch (p) {
    case StatePredicate::kOutside: return IsOutside(s);
    case StatePredicate::kBoundarySoft: return IsBoundarySoft(s);
    case StatePredicate::kFree: return !IsHardOrFrozen(s);
    case StatePredicate::kHard: return IsHard(s);
  }
  return false;
}

constexpr StatePredicate kPredicates[] = {StatePredicate::kOutside, StatePredicate::kBoundarySoft,
                                          StatePredicate::kFree, StatePredicate::kHard};

TEST(StatePlanes, EveryBitMatchesTheScalarPredicate) {
  for (int64_t n : {1, 63, 64, 65, 1000, 4099}) {
    const std::vector<VoxelState> s = RandomStates(n, static_cast<uint32_t>(n));
    for (StatePredicate p : kPredicates) {
      FlatBitset plane(n);
      FillStatePlane(s, p, plane);
      for (int64_t i = 0; i < n; ++i) {
        ASSERT_EQ(plane.test(i), Expected(p, s[i])) << "n " << n << " voxel " << i
                                                    << " state " << int(s[i]);
      }
    }
  }
}

bool SameBits(const FlatBitset& a, const FlatBitset& b) {
  return a.word_count() == b.word_count() &&
         std::equal(a.words(), a.words() + a.word_count(), b.words());
}

// Planes of 3M voxels span several blocks of words, which the threads share.
TEST(StatePlanes, FreeAndOutsidePlanesInOnePassAreTheTwoFills) {
  for (int64_t n : {1, 63, 64, 65, 1000, 4099, 3000017}) {
    const std::vector<VoxelState> s = RandomStates(n, static_cast<uint32_t>(n) + 5);
    for (int threads : {1, 3}) {
      FlatBitset free_cells(n), outside(n), soft(n), expected_out(n);
      free_cells.set_threads(threads);
      FillFreeAndOutsidePlanes(s, free_cells, outside);
      FillStatePlane(s, StatePredicate::kBoundarySoft, soft);
      FillStatePlane(s, StatePredicate::kOutside, expected_out);
      soft.Or(expected_out);
      EXPECT_TRUE(SameBits(outside, expected_out)) << "n " << n << ", " << threads << " thread(s)";
      EXPECT_TRUE(SameBits(free_cells, soft)) << "n " << n << ", " << threads << " thread(s)";
    }
  }
}

TEST(StatePlanes, WordRangeLeavesOtherWordsAlone) {
  const int64_t n = 640;
  const std::vector<VoxelState> s = RandomStates(n, 7);
  FlatBitset plane(n);
  for (size_t w = 0; w < plane.word_count(); ++w) plane.words()[w] = 0xabcdull;
  FillStatePlane(s, StatePredicate::kOutside, plane, 3, 6);
  for (int64_t w = 0; w < static_cast<int64_t>(plane.word_count()); ++w) {
    if (w >= 3 && w < 6) {
      for (int64_t i = w * 64; i < w * 64 + 64; ++i) ASSERT_EQ(plane.test(i), IsOutside(s[i]));
    } else {
      EXPECT_EQ(plane.words()[w], 0xabcdull) << "word " << w;
    }
  }
}

TEST(StatePlanes, CountsOutsideAndBoundarySoft) {
  const std::vector<VoxelState> s = RandomStates(1003, 3);
  int64_t outside = 0, boundary = 0, boundary_soft = 0;
  for (VoxelState v : s) {
    outside += IsOutside(v);
    boundary += IsBoundary(v);
    boundary_soft += IsBoundarySoft(v);
  }
  const StateCounts c = CountStates(s);
  EXPECT_EQ(c.outside, outside);
  EXPECT_EQ(c.boundary, boundary);
  EXPECT_EQ(c.boundary_soft, boundary_soft);
}

TEST(StatePlanes, CountsDoNotWrapOnLongRunsOfOneState) {
  // Long enough for byte-wide counters to wrap many times if they were never summed.
  const std::vector<VoxelState> outside(100003, OutsideState(5));
  EXPECT_EQ(CountStates(outside).outside, 100003);
  const std::vector<VoxelState> soft(100003, kBoundarySoft);
  EXPECT_EQ(CountStates(soft).boundary_soft, 100003);
  EXPECT_EQ(CountStates(soft).boundary, 100003);
}

TEST(StatePlanes, FirstBoundaryOfEightFindsTheFirstBoundaryState) {
  const std::vector<VoxelState> all = AllStates();
  for (VoxelState b : {kBoundarySoft, kBoundaryHard, kBoundaryFrozen}) {
    for (int at = 0; at < 8; ++at) {
      // Every non-boundary state before `at`, a boundary state at `at`, anything after.
      VoxelState eight[8];
      for (int k = 0; k < 8; ++k) eight[k] = k == at ? b : k > at ? kBoundarySoft : kInsideHard;
      EXPECT_EQ(FirstBoundaryOfEight(eight), at);
    }
  }
  for (VoxelState v : all) {
    if (IsBoundary(v)) continue;
    VoxelState eight[8] = {v, v, v, v, v, v, v, v};
    EXPECT_EQ(FirstBoundaryOfEight(eight), 8) << "state " << int(v);
  }
}

// Random states with rare hard ones (the grid's few data voxels among outside and soft ones),
// searched from every start for every count across the 64- and 8-state steps.
TEST(StatePlanes, FirstHardOfFindsTheFirstHardState) {
  std::mt19937 rng(11);
  const std::vector<VoxelState> all = AllStates();
  std::vector<VoxelState> s(700);
  for (VoxelState& v : s) {
    v = all[rng() % all.size()];
    if (IsHard(v) && rng() % 20 != 0) v = kInsideSoft;
  }
  for (int64_t begin = 0; begin < 80; ++begin)
    for (int64_t count = 0; begin + count <= static_cast<int64_t>(s.size()); count += 1 + count / 8) {
      int64_t expected = 0;
      while (expected < count && !IsHard(s[static_cast<size_t>(begin + expected)])) ++expected;
      EXPECT_EQ(FirstHardOf(s.data() + begin, count), expected) << begin << " " << count;
    }
}

// On a random grid whose states are mostly outside, the eight bits are, voxel by voxel,
// "outside with a face neighbour that is not".
TEST(StatePlanes, OutsideBesideSolidOfEightIsTheFaceNeighbourTest) {
  const int nx = 21, ny = 6, nz = 5;
  std::mt19937 rng(5);
  const std::vector<VoxelState> all = AllStates();
  std::vector<VoxelState> s(static_cast<size_t>(nx * ny * nz));
  for (VoxelState& v : s) v = rng() % 4 == 0 ? all[rng() % all.size()] : OutsideState(2);
  const int64_t strides[3] = {1, nx, nx * ny};
  for (int z = 1; z < nz - 1; ++z)
    for (int y = 1; y < ny - 1; ++y)
      for (int x = 1; x + 8 <= nx - 1; ++x) {
        const int64_t v = x + strides[1] * y + strides[2] * z;
        const uint64_t bits = OutsideBesideSolidOfEight(s.data() + v, strides);
        for (int k = 0; k < 8; ++k) {
          bool beside = false;
          for (int64_t step : strides)
            beside = beside || !IsOutside(s[static_cast<size_t>(v + k - step)]) ||
                     !IsOutside(s[static_cast<size_t>(v + k + step)]);
          const bool expected = IsOutside(s[static_cast<size_t>(v + k)]) && beside;
          EXPECT_EQ(((bits >> (8 * k + 7)) & 1) != 0, expected) << x + k << " " << y << " " << z;
          EXPECT_EQ(bits & ~0x8080808080808080ull, 0u);
        }
      }
}

}  // namespace
}  // namespace membrane
