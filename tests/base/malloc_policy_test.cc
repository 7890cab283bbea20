#include "core/base/malloc_policy.h"

#include <malloc.h>

#include <cstdlib>
#include <cstring>

#include "gtest/gtest.h"

namespace membrane {
namespace {

// In a child process (the policy is the whole process's): a 256 MB block, written and freed,
// is neither mapped on its own nor trimmed away, so the next one reuses its pages. Exits 0
// when so; 1 when it was mapped on its own, 2 when the heap gave it back.
[[noreturn]] void AllocateFreeAndExit() {
  KeepFreedBlocksInOneHeap();
  constexpr size_t kBytes = size_t{256} << 20;
  char* block = static_cast<char*>(std::malloc(kBytes));
  if (block == nullptr) std::_Exit(3);
  std::memset(block, 1, kBytes);
  const int mapped = static_cast<int>(mallinfo2().hblks);
  std::free(block);
  const bool kept = mallinfo2().arena >= kBytes;
  std::_Exit(mapped != 0 ? 1 : (kept ? 0 : 2));
}

TEST(MallocPolicyTest, FreedBigBlocksStayInTheHeap) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  EXPECT_EXIT(AllocateFreeAndExit(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace membrane
