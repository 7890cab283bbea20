#include "server/shared_bytes.h"

#include <cstdlib>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/base/malloc_policy.h"
#include "gtest/gtest.h"
#include "tests/server/every_mapping.h"

namespace membrane::server {
namespace {

TEST(SharedBytes, ACopyOfTheBytesLiesInAMappingOfItsOwn) {
  const std::string bytes(100000, 'b');
  const SharedBytes shared = SharedBytes::Copy(bytes);
  EXPECT_TRUE(shared.mapped());
  EXPECT_EQ(shared.size(), bytes.size());
  EXPECT_TRUE(shared.view() == bytes);
  EXPECT_NE(shared.view().data(), bytes.data());
}

TEST(SharedBytes, EmptyBytesAllocateNothing) {
  const SharedBytes none;
  EXPECT_TRUE(none.empty());
  EXPECT_FALSE(none.mapped());
  const SharedBytes copied = SharedBytes::Copy("");
  EXPECT_TRUE(copied.empty());
  EXPECT_FALSE(copied.mapped());
  EXPECT_TRUE(copied.view().empty());
}

TEST(SharedBytes, CopiesShareOneBufferThatOutlivesTheFirstOwner) {
  std::vector<SharedBytes> owners;
  {
    SharedBytes first = SharedBytes::Copy("a job's mesh");
    for (int i = 0; i < 8; ++i) owners.push_back(first);
    SharedBytes moved = std::move(first);
    EXPECT_TRUE(first.empty());  // NOLINT(bugprone-use-after-move): a moved-from one is empty
    owners.push_back(moved);
  }
  for (const SharedBytes& owner : owners) {
    EXPECT_EQ(owner.view().data(), owners[0].view().data());
    EXPECT_EQ(owner.view(), "a job's mesh");
  }
  SharedBytes assigned = SharedBytes::Copy("other");
  assigned = owners.back();
  owners.clear();
  EXPECT_EQ(assigned.view(), "a job's mesh");
  assigned = assigned;  // self-assignment keeps the bytes
  EXPECT_EQ(assigned.view(), "a job's mesh");
}

// Owners made and dropped on several threads at once leave the bytes intact for the last.
TEST(SharedBytes, OwnersOnManyThreadsCountRight) {
  const SharedBytes kept = SharedBytes::Copy(std::string(5000, 'k'));
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&kept] {
      for (int i = 0; i < 20000; ++i) {
        SharedBytes copy = kept;
        SharedBytes moved = std::move(copy);
        if (moved.size() != 5000) std::abort();
      }
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(kept.view(), std::string(5000, 'k'));
}

// In a child process: takes every mapping the kernel allows (vm.max_map_count), then copies
// bytes. Exits 0 when the copy holds them in the heap, 1 when it is mapped, 2 when the
// contents differ, 3 when the limit was not reached.
[[noreturn]] void CopyWithNoMappingLeftAndExit() {
  if (!TakeEveryMappingLeft()) std::_Exit(3);
  const std::string bytes(20000, 'h');
  SharedBytes copy = SharedBytes::Copy(bytes);
  if (copy.mapped()) std::_Exit(1);
  SharedBytes second = copy;
  copy = SharedBytes();
  std::_Exit(second.view() == bytes ? 0 : 2);
}

TEST(SharedBytes, WithNoMappingLeftTheCopyIsInTheHeap) {
  if (!kGlibcMalloc) GTEST_SKIP() << "the sanitizers' allocators need mappings of their own";
  EXPECT_EXIT(CopyWithNoMappingLeftAndExit(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace membrane::server
