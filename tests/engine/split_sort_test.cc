#include "core/base/split_sort.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/engine/arena_allocator.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// Keys that put the halves' items in every kind of interleaving: random, the first half all
// below the second, all above it, and alternating runs of a few hundred.
std::vector<uint64_t> Keys(size_t n, int kind, std::mt19937_64& rng) {
  std::vector<uint64_t> keys(n);
  for (size_t i = 0; i < n; ++i) {
    switch (kind) {
      case 0: keys[i] = rng() >> 8; break;
      case 1: keys[i] = i; break;
      case 2: keys[i] = n - i; break;
      default: keys[i] = (i / 300 % 2 == 0 ? i : n + i) * 3 + (i >= n / 2 ? 1 : 0); break;
    }
  }
  return keys;
}

TEST(SplitSort, MergedHalvesGiveTheOneSortsOrderOnAnyThreadCount) {
  std::mt19937_64 rng(11);
  for (size_t n : {size_t{5}, kMinSplitItems - 1, kMinSplitItems, kMinSplitItems + 7,
                   size_t{300001}})
    for (int kind = 0; kind < 4; ++kind) {
      const std::vector<uint64_t> keys = Keys(n, kind, rng);
      // (key, index): unique items, as the callers make them.
      std::vector<std::pair<uint64_t, int32_t>> expected(n);
      for (size_t i = 0; i < n; ++i) expected[i] = {keys[i], static_cast<int32_t>(i)};
      std::sort(expected.begin(), expected.end());
      auto make = [&](size_t i) {
        return std::pair<uint64_t, int32_t>{keys[i], static_cast<int32_t>(i)};
      };
      for (int threads : {1, 2, 3}) {
        std::vector<std::pair<uint64_t, int32_t>> items(n);
        MakeAndSortUnique(items, threads, make);
        ASSERT_EQ(items, expected) << n << " items, kind " << kind << ", " << threads << " threads";
        // The same in an array left unfilled when made (the merge's buffer too).
        std::vector<std::pair<uint64_t, int32_t>, UnfilledAllocator<std::pair<uint64_t, int32_t>>>
            unfilled(n);
        MakeAndSortUnique(unfilled, threads, make);
        ASSERT_TRUE(std::equal(unfilled.begin(), unfilled.end(), expected.begin(), expected.end()))
            << n << " items, kind " << kind << ", " << threads << " threads, unfilled";
      }
    }
}

}  // namespace
}  // namespace membrane
