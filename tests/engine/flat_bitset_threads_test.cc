// FlatBitset's word passes and the state planes on several threads give the bits one thread
// gives: planes of several word blocks and segments, with long runs of set bits across the
// seams between segments, along every axis and sign.
#include <algorithm>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/engine/flat_bitset.h"
#include "core/engine/state_planes.h"
#include "core/engine/word_blocks.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// A 203 x 197 x 211 box: 132k words, so four word blocks, two or more segments of the halo
// and spread passes along x and y.
constexpr int kNx = 203, kNy = 197, kNz = 211;
constexpr int64_t kBits = int64_t{kNx} * kNy * kNz;
constexpr int64_t kStrides[3] = {1, kNx, int64_t{kNx} * kNy};

// Bits set with probability `density`, and all set inside a box of a third of the grid (runs
// that cross segment seams), all clear on the outermost layer when `clear_border`.
FlatBitset MakePlane(double density, uint32_t seed, bool clear_border) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution bit(density);
  FlatBitset b(kBits);
  for (int z = 0; z < kNz; ++z) {
    for (int y = 0; y < kNy; ++y) {
      for (int x = 0; x < kNx; ++x) {
        const bool border = x == 0 || y == 0 || z == 0 || x == kNx - 1 || y == kNy - 1 || z == kNz - 1;
        if (clear_border && border) continue;
        const bool in_box = x > kNx / 3 && x < 2 * kNx / 3 && z > kNz / 4 && z < 3 * kNz / 4;
        if (in_box || bit(rng)) b.set(x + kStrides[1] * y + kStrides[2] * z);
      }
    }
  }
  return b;
}

// MakePlane's plane on `threads` threads, each made once.
FlatBitset Plane(double density, uint32_t seed, bool clear_border, int threads) {
  struct Made {
    double density;
    uint32_t seed;
    bool clear_border;
    FlatBitset plane;
  };
  static std::vector<Made>* made = new std::vector<Made>;
  auto it = std::find_if(made->begin(), made->end(), [&](const Made& m) {
    return m.density == density && m.seed == seed && m.clear_border == clear_border;
  });
  if (it == made->end()) {
    made->push_back({density, seed, clear_border, MakePlane(density, seed, clear_border)});
    it = made->end() - 1;
  }
  FlatBitset b = it->plane;
  b.set_threads(threads);
  return b;
}

bool SameWords(const FlatBitset& a, const FlatBitset& b) {
  return a.bits() == b.bits() &&
         std::equal(a.words(), a.words() + a.word_count(), b.words(), b.words() + b.word_count());
}

// Runs `op` on copies of the same planes with 1, 2 and 3 threads; the results must match.
void ExpectSameForAnyThreadCount(const std::string& what,
                                 const std::function<void(FlatBitset&, FlatBitset&, FlatBitset&,
                                                          FlatBitset&)>& op,
                                 double density = 0.9) {
  std::vector<FlatBitset> results;
  for (int threads : {1, 2, 3}) {
    FlatBitset a = Plane(density, 11, true, threads);
    FlatBitset b = Plane(0.5, 12, true, threads);
    FlatBitset s1(kBits), s2(kBits);
    s1.set_threads(threads);
    s2.set_threads(threads);
    op(a, b, s1, s2);
    results.push_back(a);
  }
  ASSERT_GT(results[0].Count(), 0) << what;
  EXPECT_TRUE(SameWords(results[0], results[1])) << what << ": 2 threads";
  EXPECT_TRUE(SameWords(results[0], results[2])) << what << ": 3 threads";
}

TEST(FlatBitsetThreads, PlanesAreLargeEnoughForSeveralBlocks) {
  EXPECT_GE(WordBlockCount(2, (kBits + 63) / 64), 4);
}

TEST(FlatBitsetThreads, ElementWiseAndShiftedPassesAreTheSameForAnyThreadCount) {
  using B = FlatBitset;
  ExpectSameForAnyThreadCount("And", [](B& a, B& b, B&, B&) { a.And(b); });
  ExpectSameForAnyThreadCount("Or", [](B& a, B& b, B&, B&) { a.Or(b); });
  ExpectSameForAnyThreadCount("AndNot", [](B& a, B& b, B&, B&) { a.AndNot(b); });
  ExpectSameForAnyThreadCount("copy", [](B& a, B& b, B&, B&) { a = b; });
  ExpectSameForAnyThreadCount("AssignOr", [](B& a, B& b, B& s, B&) {
    s.AssignOr(a, b);
    a = s;
  });
  ExpectSameForAnyThreadCount("AssignOrAnd", [](B& a, B& b, B& s, B&) {
    s.AssignOrAnd(b, s, a);
    a = s;
  });
  for (int axis = 0; axis < 3; ++axis) {
    for (int64_t k : {kStrides[axis], -kStrides[axis], 5 * kStrides[axis] + 3}) {
      const std::string at = " by " + std::to_string(k);
      ExpectSameForAnyThreadCount("AssignShifted" + at, [k](B& a, B& b, B&, B&) { a.AssignShifted(b, k); });
      ExpectSameForAnyThreadCount("OrShifted" + at, [k](B& a, B& b, B&, B&) { a.OrShifted(b, k); });
      ExpectSameForAnyThreadCount("AndShifted" + at, [k](B& a, B& b, B&, B&) { a.AndShifted(b, k); });
      ExpectSameForAnyThreadCount("AssignAndShifted" + at, [k](B& a, B& b, B& s, B&) {
        s.AssignAndShifted(a, b, k);
        a = s;
      });
    }
  }
  ExpectSameForAnyThreadCount("Dilate26", [](B& a, B&, B& s, B&) { a.Dilate26(kStrides, s); }, 0.01);
}

TEST(FlatBitsetThreads, CountsAndOrChangedAreTheSameForAnyThreadCount) {
  for (int threads : {2, 3}) {
    const FlatBitset one = Plane(0.3, 21, false, 1);
    const FlatBitset many = Plane(0.3, 21, false, threads);
    EXPECT_EQ(many.Count(), one.Count());
    FlatBitset a = Plane(0.3, 22, false, threads);
    FlatBitset b = a;
    EXPECT_FALSE(a.OrChanged(b));
    b.set(kBits - 1);  // in the last block only
    a.AndNot(b);
    EXPECT_TRUE(a.OrChanged(b));
    EXPECT_TRUE(SameWords(a, b));
  }
}

TEST(FlatBitsetThreads, RunsAreTheSameForAnyThreadCount) {
  using B = FlatBitset;
  for (int axis = 0; axis < 3; ++axis) {
    const int64_t s = kStrides[axis];
    // Doubling (in place: the halo of each segment), and the long runs (x from 64, y and z
    // from 17).
    for (int n : {2, 3, 10, 16, 17, 70, 150}) {
      const std::string at = " n " + std::to_string(n) + " stride " + std::to_string(s);
      ExpectSameForAnyThreadCount("ErodeRun" + at, [=](B& a, B&, B&, B&) { a.ErodeRun(n, s); });
      ExpectSameForAnyThreadCount("DilateRun" + at, [=](B& a, B&, B&, B&) { a.DilateRun(n, s); }, 0.02);
      ExpectSameForAnyThreadCount("ErodeRun scratch" + at, [=](B& a, B&, B& t, B&) { a.ErodeRun(n, s, t); });
      ExpectSameForAnyThreadCount("DilateRun scratch" + at, [=](B& a, B&, B& t, B&) { a.DilateRun(n, s, t); }, 0.02);
      ExpectSameForAnyThreadCount("ErodeRunFrom" + at, [=](B& a, B& b, B& t, B&) {
        b.ErodeRunFrom(a, n, s, t);
        a = b;
      });
      ExpectSameForAnyThreadCount("DilateRunFrom" + at, [=](B& a, B& b, B& t, B&) {
        b.DilateRunFrom(a, n, s, t);
        a = b;
      }, 0.02);
    }
  }
}

TEST(FlatBitsetThreads, BitsetsSharingAHaloStoreGiveTheirOwnBits) {
  // Two planes whose in-place passes save their halo in one store, taking turns along every
  // axis (the store grows from x's small halo to z's), give the bits of one thread.
  std::vector<uint64_t> store;
  FlatBitset a = Plane(0.9, 31, true, 2), b = Plane(0.02, 32, true, 2);
  FlatBitset a1 = Plane(0.9, 31, true, 1), b1 = Plane(0.02, 32, true, 1);
  a.set_halo_store(&store);
  b.set_halo_store(&store);
  for (int axis = 0; axis < 3; ++axis) {
    for (FlatBitset* p : {&a, &a1}) p->ErodeRun(3, kStrides[axis]);
    for (FlatBitset* p : {&b, &b1}) p->DilateRun(10, kStrides[axis]);
    EXPECT_TRUE(SameWords(a, a1)) << "axis " << axis;
    EXPECT_TRUE(SameWords(b, b1)) << "axis " << axis;
  }
  EXPECT_FALSE(store.empty());  // the passes used the store
  ASSERT_GT(a.Count(), 0);
  ASSERT_GT(b.Count(), 0);
}

TEST(FlatBitsetThreads, SpreadsAreTheSameForAnyThreadCount) {
  using B = FlatBitset;
  const int64_t dims[3] = {kNx, kNy, kNz};
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {1, -1}) {
      const int64_t step = sign * kStrides[axis];
      const int64_t max_len = dims[axis];
      // Sparse seeds in a run plane of long runs: the spread crosses the segments' seams.
      ExpectSameForAnyThreadCount("SpreadAlong " + std::to_string(step),
                                  [=](B& run, B& seeds, B& t, B& u) {
                                    seeds.ErodeRun(9, 1);
                                    seeds.And(run);
                                    seeds.SpreadAlong(run, step, max_len, t, u);
                                    run = seeds;
                                  });
    }
  }
  // Doubling spreads (a step under 64): element-wise passes.
  ExpectSameForAnyThreadCount("SpreadAlong 3", [](B& run, B& seeds, B& t, B& u) {
    seeds.ErodeRun(9, 1);
    seeds.And(run);
    seeds.SpreadAlong(run, 3, kNx, t, u);
    run = seeds;
  });
}

TEST(FlatBitsetThreads, StatePlanesAndCountsAreTheSameForAnyThreadCount) {
  std::mt19937 rng(5);
  const VoxelState kinds[] = {kInsideSoft, kBoundarySoft, kBoundaryFrozen, kInsideHard,
                              OutsideState(3), static_cast<VoxelState>(0x07)};
  std::vector<VoxelState> states(static_cast<size_t>(kBits));
  for (VoxelState& s : states) s = kinds[rng() % std::size(kinds)];
  const StateCounts one = CountStates(states, 1);
  for (int threads : {2, 3}) {
    const StateCounts many = CountStates(states, threads);
    EXPECT_EQ(many.outside, one.outside);
    EXPECT_EQ(many.boundary, one.boundary);
    EXPECT_EQ(many.boundary_soft, one.boundary_soft);
    for (StatePredicate p : {StatePredicate::kOutside, StatePredicate::kBoundarySoft,
                             StatePredicate::kFree, StatePredicate::kHard}) {
      FlatBitset a(kBits), b(kBits);
      b.set_threads(threads);
      FillStatePlane(states, p, a);
      FillStatePlane(states, p, b);
      EXPECT_TRUE(SameWords(a, b)) << static_cast<int>(p) << " on " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace membrane
