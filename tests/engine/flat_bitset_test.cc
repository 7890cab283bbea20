#include "core/engine/flat_bitset.h"

#include <cstdint>
#include <random>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

FlatBitset RandomBits(int64_t n, double density, uint32_t seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution bit(density);
  FlatBitset b(n);
  for (int64_t i = 0; i < n; ++i)
    if (bit(rng)) b.set(i);
  return b;
}

// The definition: a seed spreads cell by cell along `step` while `run` stays set.
std::vector<bool> NaiveSpread(const FlatBitset& seeds, const FlatBitset& run, int64_t step) {
  const int64_t n = seeds.bits();
  std::vector<bool> out(static_cast<size_t>(n));
  for (int64_t i = 0; i < n; ++i) out[i] = seeds.test(i);
  if (step > 0) {
    for (int64_t i = step; i < n; ++i) out[i] = out[i] || (run.test(i) && out[i - step]);
  } else {
    for (int64_t i = n - 1 + step; i >= 0; --i) out[i] = out[i] || (run.test(i) && out[i - step]);
  }
  return out;
}

TEST(FlatBitsetSpreadAlong, MatchesTheCellByCellDefinitionForEveryStepKind) {
  // |step| 1: carries along x; 3: doubling; 64 and 70: one pass along y or z.
  for (int64_t step : {1, -1, 3, -3, 64, -64, 70, -70}) {
    for (int64_t n : {64, 200, 1000, 4103}) {
      const FlatBitset run = RandomBits(n, 0.85, static_cast<uint32_t>(n + step * 7 + 100));
      FlatBitset seeds = RandomBits(n, 0.05, static_cast<uint32_t>(n - step));
      seeds.And(run);
      FlatBitset spread = seeds, a(n), b(n);
      spread.SpreadAlong(run, step, n, a, b);
      const std::vector<bool> expected = NaiveSpread(seeds, run, step);
      for (int64_t i = 0; i < n; ++i) {
        ASSERT_EQ(spread.test(i), expected[i]) << "step " << step << " bits " << n << " bit " << i;
      }
    }
  }
}

TEST(FlatBitsetSpreadAlong, RunsCrossWordBordersAlongX) {
  FlatBitset run(256), spread(256), a(256), b(256);
  for (int64_t i = 60; i < 200; ++i) run.set(i);
  spread.set(62);
  spread.SpreadAlong(run, 1, 256, a, b);
  EXPECT_FALSE(spread.test(61));
  EXPECT_TRUE(spread.test(62));
  EXPECT_TRUE(spread.test(199));
  EXPECT_FALSE(spread.test(200));
  FlatBitset down(256);
  down.set(130);
  down.SpreadAlong(run, -1, 256, a, b);
  EXPECT_TRUE(down.test(60));
  EXPECT_TRUE(down.test(130));
  EXPECT_FALSE(down.test(131));
  EXPECT_FALSE(down.test(59));
}

TEST(FlatBitsetRuns, ErodeAndDilateMatchTheirDefinitions) {
  // Strides within a word, across words, a multiple of 64, and past the end of the set.
  for (int64_t stride : {1, 5, 64, 70, 300, 5000}) {
    for (int n : {1, 2, 3, 4, 7, 8, 16, 20, 21, 80}) {
      const int64_t bits = 3000;
      // Dense for the erosion, sparse for the dilation, so that both answers vary.
      const FlatBitset a = RandomBits(bits, 0.9, static_cast<uint32_t>(stride * 31 + n));
      const FlatBitset b = RandomBits(bits, 0.08, static_cast<uint32_t>(stride * 17 + n));
      FlatBitset eroded = a, dilated = b;
      eroded.ErodeRun(n, stride);
      dilated.DilateRun(n, stride);
      for (int64_t i = 0; i < bits; ++i) {
        bool all = true, any = false;
        for (int j = 0; j < n; ++j) {
          const int64_t up = i + j * stride, down = i - j * stride;
          all = all && up < bits && a.test(up);
          any = any || (down >= 0 && b.test(down));
        }
        ASSERT_EQ(eroded.test(i), all) << "stride " << stride << " n " << n << " bit " << i;
        ASSERT_EQ(dilated.test(i), any) << "stride " << stride << " n " << n << " bit " << i;
      }
    }
  }
}

bool SameBits(const FlatBitset& a, const FlatBitset& b) {
  if (a.bits() != b.bits()) return false;
  for (int64_t i = 0; i < a.bits(); ++i)
    if (a.test(i) != b.test(i)) return false;
  return true;
}

TEST(FlatBitsetRuns, FromVariantsEqualCopyThenRun) {
  for (int64_t stride : {1, 5, 64, 70, 300, 5000}) {
    for (int n : {1, 2, 3, 4, 7, 8, 16, 20, 21, 80}) {
      const int64_t bits = 3000;
      const FlatBitset a = RandomBits(bits, 0.9, static_cast<uint32_t>(stride * 13 + n));
      const FlatBitset b = RandomBits(bits, 0.08, static_cast<uint32_t>(stride * 7 + n));
      FlatBitset eroded = a, dilated = b;
      eroded.ErodeRun(n, stride);
      dilated.DilateRun(n, stride);
      FlatBitset eroded_from = RandomBits(bits, 0.5, 1), dilated_from = RandomBits(bits, 0.5, 2);
      eroded_from.ErodeRunFrom(a, n, stride);
      dilated_from.DilateRunFrom(b, n, stride);
      EXPECT_TRUE(SameBits(eroded, eroded_from)) << "stride " << stride << " n " << n;
      EXPECT_TRUE(SameBits(dilated, dilated_from)) << "stride " << stride << " n " << n;
    }
  }
}

TEST(FlatBitsetRuns, LongRunVariantsGiveTheDoublingBits) {
  // One pass along x, blocks along strides of 64 and more (a multiple of 64 or not, rows
  // shorter and longer than the run, blocks cut by the end of the set), the doubling between.
  for (int64_t bits : {3000, 20011}) {
    for (int64_t stride : {1, 5, 64, 70, 129, 200, 300, 5000}) {
      for (int n : {2, 3, 9, 16, 17, 20, 63, 64, 65, 80, 200, 1000}) {
        const uint32_t seed = static_cast<uint32_t>(bits + stride * 13 + n);
        // Dense runs of ones for the erosion, sparse ones for the dilation, with long
        // stretches of each so that runs longer than a word occur.
        FlatBitset a = RandomBits(bits, 0.97, seed), b = RandomBits(bits, 0.02, seed + 1);
        for (int64_t i = bits / 3; i < bits / 3 + 700; ++i) a.set(i);
        FlatBitset eroded = a, dilated = b;
        eroded.ErodeRun(n, stride);
        dilated.DilateRun(n, stride);
        FlatBitset scratch = RandomBits(bits, 0.5, 3);
        FlatBitset eroded_long = a, dilated_long = b;
        eroded_long.ErodeRun(n, stride, scratch);
        dilated_long.DilateRun(n, stride, scratch);
        FlatBitset eroded_from = RandomBits(bits, 0.5, 4), dilated_from = RandomBits(bits, 0.5, 5);
        eroded_from.ErodeRunFrom(a, n, stride, scratch);
        dilated_from.DilateRunFrom(b, n, stride, scratch);
        for (int64_t w = 0; w < static_cast<int64_t>(a.word_count()); ++w) {
          ASSERT_EQ(eroded_long.words()[w], eroded.words()[w])
              << "erode bits " << bits << " stride " << stride << " n " << n << " word " << w;
          ASSERT_EQ(eroded_from.words()[w], eroded.words()[w])
              << "erode from, bits " << bits << " stride " << stride << " n " << n;
          ASSERT_EQ(dilated_long.words()[w], dilated.words()[w])
              << "dilate bits " << bits << " stride " << stride << " n " << n << " word " << w;
          ASSERT_EQ(dilated_from.words()[w], dilated.words()[w])
              << "dilate from, bits " << bits << " stride " << stride << " n " << n;
        }
      }
    }
  }
}

TEST(FlatBitsetAssign, AndShiftedOrAndOrAndMatchTheirDefinitions) {
  const int64_t bits = 1000;
  const FlatBitset a = RandomBits(bits, 0.5, 11);
  const FlatBitset b = RandomBits(bits, 0.5, 12);
  const FlatBitset c = RandomBits(bits, 0.5, 13);
  for (int64_t k : {0, 1, -1, 63, -64, 65, -200, 999, -999}) {
    FlatBitset r = RandomBits(bits, 0.5, 14);  // old contents must not matter
    r.AssignAndShifted(a, b, k);
    for (int64_t i = 0; i < bits; ++i) {
      const int64_t j = i - k;
      const bool want = a.test(i) && j >= 0 && j < bits && b.test(j);
      ASSERT_EQ(r.test(i), want) << "k " << k << " bit " << i;
    }
  }
  FlatBitset o = RandomBits(bits, 0.5, 15), oa = RandomBits(bits, 0.5, 16);
  o.AssignOr(a, b);
  oa.AssignOrAnd(a, b, c);
  for (int64_t i = 0; i < bits; ++i) {
    ASSERT_EQ(o.test(i), a.test(i) || b.test(i)) << i;
    ASSERT_EQ(oa.test(i), (a.test(i) || b.test(i)) && c.test(i)) << i;
  }
}

TEST(FlatBitsetOrChanged, ReportsOnlyNewBits) {
  FlatBitset a(300), b(300);
  a.set(5);
  a.set(250);
  b.set(250);
  EXPECT_FALSE(a.OrChanged(b));
  b.set(299);
  EXPECT_TRUE(a.OrChanged(b));
  EXPECT_TRUE(a.test(299));
  EXPECT_TRUE(a.test(5));
  EXPECT_EQ(a.Count(), 3);
}

TEST(FlatBitsetVisit, WordRangesVisitTheirBitsInOrderAndStopWhenAsked) {
  const FlatBitset bits = RandomBits(64 * 9 + 5, 0.3, 17);
  std::vector<int64_t> all;
  bits.ForEach([&](int64_t i) { all.push_back(i); });
  for (int64_t i = 1; i < static_cast<int64_t>(all.size()); ++i) ASSERT_LT(all[i - 1], all[i]);
  // Three word ranges side by side visit what ForEach visits.
  std::vector<int64_t> ranges;
  for (int64_t begin : {0, 4, 7}) {
    const int64_t end = begin == 0 ? 4 : (begin == 4 ? 7 : 10);
    EXPECT_TRUE(bits.ForEachInWords(begin, end, [&](int64_t i) {
      EXPECT_GE(i, begin * 64);
      EXPECT_LT(i, end * 64);
      ranges.push_back(i);
      return true;
    }));
  }
  EXPECT_EQ(ranges, all);
  // Stopped at the fifth bit: five visits, and the walk says it stopped.
  ASSERT_GE(all.size(), 6u);
  int visits = 0;
  EXPECT_FALSE(bits.ForEachInWords(0, 10, [&](int64_t) { return ++visits < 5; }));
  EXPECT_EQ(visits, 5);
}

}  // namespace
}  // namespace membrane
