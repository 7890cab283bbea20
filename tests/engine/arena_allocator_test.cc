#include "core/engine/arena_allocator.h"

#include <cstdint>
#include <vector>

#include "core/engine/flat_bitset.h"
#include "core/engine/plane_arena.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

TEST(ArenaAllocator, LargeBlocksAreAlignedToACacheLine) {
  std::vector<uint64_t, ArenaAllocator<uint64_t>> plane(3 * kAlignedBlockBytes / 8 + 5, 0);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(plane.data()) % PlaneArena::kBlockAlignment, 0u);
  plane.back() = 7;
  EXPECT_EQ(plane.back(), 7u);
  EXPECT_EQ(plane.front(), 0u);
}

TEST(ArenaAllocator, SmallBlocksWorkLikeOrdinaryOnes) {
  std::vector<uint64_t, ArenaAllocator<uint64_t>> small(10, 3);
  small.push_back(4);
  EXPECT_EQ(small.size(), 11u);
  EXPECT_EQ(small[0] + small[10], 7u);
}

TEST(PlaneArena, TakesAlignedBlocksInOrderUntilFull) {
  PlaneArena arena(1000);
  EXPECT_EQ(arena.capacity(), 1024u);  // rounded up to a cache line
  void* a = arena.Take(100);
  void* b = arena.Take(1);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(a) % PlaneArena::kBlockAlignment, 0u);
  EXPECT_EQ(static_cast<char*>(b) - static_cast<char*>(a), 128);  // 100 rounded to 64s
  EXPECT_TRUE(arena.Owns(a));
  EXPECT_TRUE(arena.Owns(b));
  int outside = 0;
  EXPECT_FALSE(arena.Owns(&outside));
  EXPECT_EQ(arena.Take(1000), nullptr);  // no room: the caller goes elsewhere
  EXPECT_EQ(arena.used(), 192u);
}

TEST(PlaneArena, BitsetsTakeTheirWordsFromItAndFallBackWhenFull) {
  const int64_t bits = 64 * 1000;  // 8000 bytes a plane
  PlaneArena arena(20 * 8000);     // 20 planes fit
  std::vector<FlatBitset> planes;
  planes.reserve(30);
  for (int i = 0; i < 30; ++i) planes.emplace_back(bits, &arena);
  EXPECT_TRUE(arena.Owns(planes[0].words()));
  EXPECT_TRUE(arena.Owns(planes[19].words()));
  EXPECT_FALSE(arena.Owns(planes[20].words()));  // allocated on its own, freed on its own
  planes[5].set(17);
  EXPECT_FALSE(planes[4].test(17));  // blocks do not overlap
  EXPECT_FALSE(planes[6].test(17));
  // Assignment between an arena plane and a plain one copies, so each frees its own.
  FlatBitset plain(bits);
  plain = planes[5];
  EXPECT_TRUE(plain.test(17));
  EXPECT_FALSE(arena.Owns(plain.words()));
  planes[7] = std::move(plain);
  EXPECT_TRUE(planes[7].test(17));
  EXPECT_TRUE(arena.Owns(planes[7].words()));
}

}  // namespace
}  // namespace membrane
