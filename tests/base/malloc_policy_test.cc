#include "core/base/malloc_policy.h"

#include <malloc.h>
#include <stdlib.h>

#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

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

TEST(MallocPolicyTest, TunableNamesAreTheNamesOfTheColonSeparatedPairs) {
  EXPECT_TRUE(TunableNames(nullptr).empty());
  EXPECT_TRUE(TunableNames("").empty());
  EXPECT_EQ(TunableNames("glibc.malloc.arena_max=2::glibc.rtld.nns=2:flag"),
            (std::vector<std::string>{"glibc.malloc.arena_max", "glibc.rtld.nns", "flag"}));
}

TEST(MallocPolicyTest, TheHugePageTunableIsAddedUnlessNamed) {
  EXPECT_EQ(TunablesWithHugePageHeap(nullptr), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(TunablesWithHugePageHeap(""), "glibc.malloc.hugetlb=1");
  EXPECT_EQ(TunablesWithHugePageHeap("glibc.rtld.optional_static_tls=4096"),
            "glibc.rtld.optional_static_tls=4096:glibc.malloc.hugetlb=1");
  // A longer name is another tunable.
  EXPECT_EQ(TunablesWithHugePageHeap("glibc.malloc.hugetlbx=0"),
            "glibc.malloc.hugetlbx=0:glibc.malloc.hugetlb=1");
  // The operator's choice, either way, stands (and a process started again stops there).
  EXPECT_EQ(TunablesWithHugePageHeap("glibc.malloc.hugetlb=0"), std::nullopt);
  EXPECT_EQ(TunablesWithHugePageHeap("glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1"),
            std::nullopt);
}

// In a child process: GLIBC_TUNABLES set to `tunables` (unset when null), then
// RestartWithHugePageHeap(executable, a shell script that exits 7 when GLIBC_TUNABLES is
// `expected` and 1 otherwise). Exits 8 when the restart returned with the environment as it
// was, 9 when it returned with another.
[[noreturn]] void RestartAndExit(const char* tunables, const char* executable,
                                 const std::string& expected) {
  if (tunables == nullptr) {
    unsetenv("GLIBC_TUNABLES");
  } else {
    setenv("GLIBC_TUNABLES", tunables, 1);
  }
  std::string script = "test \"$GLIBC_TUNABLES\" = '" + expected + "' && exit 7; exit 1";
  char* argv[] = {const_cast<char*>("sh"), const_cast<char*>("-c"), script.data(), nullptr};
  RestartWithHugePageHeap(executable, argv);
  const char* after = std::getenv("GLIBC_TUNABLES");
  const bool same = tunables == nullptr ? after == nullptr
                                        : after != nullptr && std::strcmp(after, tunables) == 0;
  std::_Exit(same ? 8 : 9);
}

TEST(MallocPolicyTest, TheProcessStartsAgainWithTheHugePageTunable) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  // Where the kernel would give the heap huge pages without advice, or none with it, the
  // process goes on as it is.
  const int restarted = KernelGivesHugePagesOnlyWhenAdvised() ? 7 : 8;
  EXPECT_EXIT(RestartAndExit(nullptr, "/bin/sh", "glibc.malloc.hugetlb=1"),
              ::testing::ExitedWithCode(restarted), "");
  EXPECT_EXIT(
      RestartAndExit("glibc.rtld.nns=2", "/bin/sh", "glibc.rtld.nns=2:glibc.malloc.hugetlb=1"),
      ::testing::ExitedWithCode(restarted), "");
  // Named already: no second start.
  EXPECT_EXIT(RestartAndExit("glibc.malloc.hugetlb=0", "/bin/sh", "glibc.malloc.hugetlb=0"),
              ::testing::ExitedWithCode(8), "");
}

TEST(MallocPolicyTest, AFailedRestartGoesOnWithTheEnvironmentAsItWas) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  EXPECT_EXIT(RestartAndExit(nullptr, "/nonexistent/membrane", ""), ::testing::ExitedWithCode(8),
              "");
  EXPECT_EXIT(RestartAndExit("glibc.rtld.nns=2", "/nonexistent/membrane", ""),
              ::testing::ExitedWithCode(8), "");
}

[[noreturn]] void RestartProbeAndExit() {
  unsetenv("GLIBC_TUNABLES");
  char* argv[] = {const_cast<char*>(HEAP_PAGE_PROBE), nullptr};
  RestartWithHugePageHeap(HEAP_PAGE_PROBE, argv);
  std::_Exit(4);
}

// The probe (heap_page_probe.cc) started again with the tunable has its heap on huge pages,
// and a trim gives a freed block's back.
TEST(MallocPolicyTest, ARestartedProcessHasItsHeapOnHugePages) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  if (!KernelGivesHugePagesOnlyWhenAdvised()) {
    GTEST_SKIP() << "the kernel's transparent huge pages are not in madvise mode";
  }
  EXPECT_EXIT(RestartProbeAndExit(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace membrane
