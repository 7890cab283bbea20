#include "core/base/bucket_offsets.h"

#include <cstdint>
#include <vector>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// Items of three parts dealt into four buckets by their value, as the threaded passes deal
// theirs: every item lands in its bucket, each part's items after the earlier parts' in it.
TEST(PlaceBucketsByPart, EachPartPlacesItsItemsInItsOwnSlots) {
  const std::vector<std::vector<int>> parts = {{3, 0, 3, 1}, {}, {1, 3, 0, 0, 2}};
  std::vector<std::vector<uint32_t>> counts(parts.size(), std::vector<uint32_t>(4, 0));
  for (size_t p = 0; p < parts.size(); ++p)
    for (const int item : parts[p]) ++counts[p][item];
  const std::vector<uint32_t> start = PlaceBucketsByPart(counts);
  EXPECT_EQ(start, (std::vector<uint32_t>{0, 3, 5, 6, 9}));
  std::vector<int> grouped(9, -1), part_of(9, -1);
  for (size_t p = 0; p < parts.size(); ++p) {
    for (const int item : parts[p]) {
      const uint32_t slot = counts[p][item]++;
      ASSERT_EQ(grouped[slot], -1) << "slot " << slot << " taken twice";
      grouped[slot] = item;
      part_of[slot] = static_cast<int>(p);
    }
  }
  EXPECT_EQ(grouped, (std::vector<int>{0, 0, 0, 1, 1, 2, 3, 3, 3}));
  EXPECT_EQ(part_of, (std::vector<int>{0, 2, 2, 0, 2, 2, 0, 0, 2}));
}

TEST(PlaceBucketsByPart, NoPartsNoBuckets) {
  std::vector<std::vector<size_t>> none;
  EXPECT_EQ(PlaceBucketsByPart(none), (std::vector<size_t>{0}));
}

}  // namespace
}  // namespace membrane
