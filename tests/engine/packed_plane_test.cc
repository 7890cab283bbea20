#include "core/engine/packed_plane.h"

#include <cstdint>
#include <random>

#include "core/engine/flat_bitset.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// A plane of runs of zero words, all-ones words and random words (every kind of word, in runs
// that cross the 64-word groups), of a size that ends inside a word.
FlatBitset RunsPlane(int64_t bits, uint32_t seed) {
  std::mt19937_64 rng(seed);
  FlatBitset plane(bits);
  uint64_t* w = plane.words();
  const int64_t words = static_cast<int64_t>(plane.word_count());
  for (int64_t k = 0; k < words;) {
    const int kind = static_cast<int>(rng() % 3);
    const int64_t run = 1 + static_cast<int64_t>(rng() % 150);
    for (int64_t j = 0; j < run && k < words; ++j, ++k) {
      w[k] = kind == 0 ? 0 : kind == 1 ? ~uint64_t{0} : rng();
    }
  }
  return plane;
}

TEST(PackedPlane, EveryBitIsThePlanes) {
  for (const int64_t bits : {int64_t{1}, int64_t{64}, int64_t{4097}, int64_t{300001}}) {
    for (uint32_t seed = 1; seed <= 3; ++seed) {
      const FlatBitset plane = RunsPlane(bits, seed);
      PackedPlane packed;
      packed.Assign(plane);
      for (int64_t i = 0; i < bits; ++i) {
        ASSERT_EQ(packed.test(i), plane.test(i)) << bits << " " << i;
      }
    }
  }
}

TEST(PackedPlane, AssignedAgainHoldsTheNewPlane) {
  const FlatBitset first = RunsPlane(200000, 7), second = RunsPlane(200000, 8);
  PackedPlane packed;
  packed.Assign(first);
  packed.Assign(second);
  for (int64_t i = 0; i < second.bits(); ++i) ASSERT_EQ(packed.test(i), second.test(i)) << i;
}

TEST(PackedPlane, AGrowingCopyHoldsLittleMoreThanItsWords) {
  // A plane of mixed words, then one with a few more: the second copy's bytes stay near its
  // own words' (a buffer grown by doubling would hold twice them).
  FlatBitset first(int64_t{64} * 100000), second(int64_t{64} * 100000);
  for (int64_t w = 0; w < 100000; ++w) {
    if (w < 90000) first.words()[w] = 0x5;
    if (w < 90100) second.words()[w] = 0x5;
  }
  PackedPlane packed;
  packed.Assign(first);
  packed.Assign(second);
  const int64_t flags = (100000 + 63) / 64 * 24;  // two flags and a rank per 64 words
  EXPECT_LE(packed.bytes(), flags + 90100 * 8 * 17 / 16 + 64);
  for (int64_t i = 0; i < second.bits(); i += 61) ASSERT_EQ(packed.test(i), second.test(i)) << i;
}

TEST(PackedPlane, SameCopyOnAnyThreadCount) {
  // Five blocks of words and a part (ForWordBlocks' 32k words), so that the ranks of every
  // block but the first are offset by the mixed words of the blocks before it.
  const int64_t bits = int64_t{64} * ((int64_t{5} << 15) + 1000) - 17;
  const FlatBitset plane = RunsPlane(bits, 11);
  int64_t one_thread_bytes = 0;
  for (const int threads : {1, 2, 3}) {
    FlatBitset threaded = plane;
    threaded.set_threads(threads);
    PackedPlane packed;
    packed.Assign(threaded);
    for (int64_t i = 0; i < bits; ++i) {
      ASSERT_EQ(packed.test(i), plane.test(i)) << threads << " threads, bit " << i;
    }
    if (threads == 1) one_thread_bytes = packed.bytes();
    EXPECT_EQ(packed.bytes(), one_thread_bytes) << threads << " threads";
  }
}

TEST(PackedPlane, UniformWordsTakeTwoBitsEach) {
  // 2^20 voxels of zeros then ones: no mixed word, so only the flags and the ranks are held
  // (two flag bits a word and a 64-bit rank per 64 words: 3/64 of the plane's 128 KB).
  FlatBitset plane(int64_t{1} << 20);
  for (int64_t i = plane.bits() / 2; i < plane.bits(); ++i) plane.set(i);
  PackedPlane packed;
  packed.Assign(plane);
  EXPECT_FALSE(packed.test(0));
  EXPECT_TRUE(packed.test(plane.bits() - 1));
  EXPECT_LE(packed.bytes(), static_cast<int64_t>(plane.word_count() * 8 / 16 + 256));
}

}  // namespace
}  // namespace membrane
