#include "core/engine/huge_page_allocator.h"

#include <cstdint>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

TEST(HugePageAllocator, LargeBlocksAreAlignedToAHugePage) {
  std::vector<uint64_t, HugePageAllocator<uint64_t>> plane(3 * kHugePageBytes / 8 + 5, 0);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(plane.data()) % kHugePageBytes, 0u);
  plane.back() = 7;
  EXPECT_EQ(plane.back(), 7u);
  EXPECT_EQ(plane.front(), 0u);
}

TEST(HugePageAllocator, SmallBlocksWorkLikeOrdinaryOnes) {
  std::vector<uint64_t, HugePageAllocator<uint64_t>> small(10, 3);
  small.push_back(4);
  EXPECT_EQ(small.size(), 11u);
  EXPECT_EQ(small[0] + small[10], 7u);
}

}  // namespace
}  // namespace membrane
