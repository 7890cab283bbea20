#include "server/memory_release.h"

#include <malloc.h>
#include <stdlib.h>

#include <cstdlib>
#include <cstring>

#include <vector>

#include "absl/strings/str_cat.h"
#include "core/base/malloc_policy.h"
#include "server/job.h"
#include "gtest/gtest.h"

namespace membrane::server {
namespace {

constexpr size_t kBytes = size_t{256} << 20;

// In a child process (malloc's settings are the whole process's), with `name` set to `value`
// in the environment unless name is null: a 256 MB block is allocated, written and freed.
// Exits 0 when the policy was set, the block came from the heap and stayed there once freed,
// and ReleaseFreedMemory then gave the heap's pages back; 10 when the policy was not set and
// the block was mapped on its own, as glibc's defaults do. Any other code names what differed.
[[noreturn]] void AllocateFreeAndExit(const char* name, const char* value) {
  unsetenv("MALLOC_ARENA_MAX");
  unsetenv("GLIBC_TUNABLES");
  if (name != nullptr) setenv(name, value, 1);
  const bool policy = UseMallocPolicyUnlessChosen();
  char* block = static_cast<char*>(std::malloc(kBytes));
  if (block == nullptr) std::_Exit(3);
  std::memset(block, 1, kBytes);
  const bool mapped = mallinfo2().hblks != 0;
  std::free(block);
  if (!policy) std::_Exit(mapped ? 10 : 11);
  if (mapped) std::_Exit(1);
  if (mallinfo2().arena < kBytes) std::_Exit(2);  // given back before the job's end
  ReleaseFreedMemory();
  std::_Exit(mallinfo2().arena < kBytes ? 0 : 4);
}

TEST(ServerMallocPolicy, AJobsFreedBlocksStayUntilReleased) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  EXPECT_EXIT(AllocateFreeAndExit(nullptr, nullptr), ::testing::ExitedWithCode(0), "");
  // Tunables of another part of glibc leave malloc to the policy.
  EXPECT_EXIT(AllocateFreeAndExit("GLIBC_TUNABLES", "glibc.rtld.optional_static_tls=4096"),
              ::testing::ExitedWithCode(0), "");
  // Nor does the huge pages' one, which the process sets itself (RestartWithHugePageHeap).
  EXPECT_EXIT(AllocateFreeAndExit("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1"),
              ::testing::ExitedWithCode(0), "");
}

TEST(ServerMallocPolicy, TheOperatorsSettingsStand) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  EXPECT_EXIT(AllocateFreeAndExit("MALLOC_ARENA_MAX", "2"), ::testing::ExitedWithCode(10), "");
  EXPECT_EXIT(AllocateFreeAndExit("GLIBC_TUNABLES", "glibc.malloc.arena_max=2"),
              ::testing::ExitedWithCode(10), "");
  EXPECT_EXIT(
      AllocateFreeAndExit("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1:glibc.malloc.mmap_max=0"),
      ::testing::ExitedWithCode(10), "");
}

// In a child process under the policy: a job's run frees a 256 MB array, then the job records
// the events of its late stages and ends with its statistics, mesh, preview and point sample.
// Exits 0 when the next 256 MB array takes the freed one's place (what the job keeps did not
// split it), 1 when it had to go elsewhere.
[[noreturn]] void KeepAJobsResultAfterAFreedArrayAndExit() {
  unsetenv("MALLOC_ARENA_MAX");
  unsetenv("GLIBC_TUNABLES");
  if (!UseMallocPolicyUnlessChosen()) std::_Exit(3);
  Job job("job-1", "peer", v1::Parameters(), std::string());
  if (!job.Start()) std::_Exit(5);
  // Made before the array is freed: the observer's messages and the run's result are
  // transient, what the job makes of them is what it keeps.
  std::vector<v1::JobEvent> events(2000);
  for (size_t i = 0; i < events.size(); ++i) {
    v1::StageProgress* p = events[i].mutable_progress();
    p->set_stage("surface");
    p->set_line(absl::StrCat("surface: ", i, " of ", events.size(), " parts fitted so far"));
  }
  const std::string statistics(3000, '{');
  const std::string mesh(16 << 20, 'm');
  const std::string preview(60000, 'p');
  const std::string sample(240000, 's');
  char* array = static_cast<char*>(std::malloc(kBytes));
  if (array == nullptr) std::_Exit(4);
  std::memset(array, 1, 4096);
  std::free(array);
  for (const v1::JobEvent& event : events) job.AddEvent(event);
  job.SetPointSample(sample);
  job.SetPreview(preview);
  job.Succeed(statistics, v1::MeshSummary(), mesh);
  char* next = static_cast<char*>(std::malloc(kBytes));
  if (job.Closing()->mesh.view() != mesh || job.Events().size() != events.size()) std::_Exit(6);
  std::_Exit(next == array ? 0 : 1);
}

TEST(ServerMallocPolicy, WhatAJobKeepsLeavesTheSpaceItsRunFreedWhole) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  EXPECT_EXIT(KeepAJobsResultAfterAFreedArrayAndExit(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace membrane::server
