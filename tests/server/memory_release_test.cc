#include "server/memory_release.h"

#include <malloc.h>
#include <stdlib.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/blocking_counter.h"
#include "core/base/malloc_policy.h"
#include "gtest/gtest.h"
#include "server/job.h"
#include "server/job_scheduler.h"

namespace membrane::server {
namespace {

constexpr size_t kBytes = size_t{256} << 20;

// A run's array: kBytes allocated, a page of them written, then freed. Returns where it lay
// (exits 4 when it cannot be had).
uintptr_t AllocateAndFreeAnArray() {
  void* array = std::malloc(kBytes);
  if (array == nullptr) std::_Exit(4);
  std::memset(array, 1, 4096);
  // Read through a volatile before the free, so that no use of the pointer follows it.
  const volatile uintptr_t at = reinterpret_cast<uintptr_t>(array);
  std::free(array);
  return at;
}

// Whether an array of kBytes allocated at `next` took the place of one freed at `freed`: at
// the same address, or a little below where blocks freed beside it merged with it. Where the
// freed space was split, it lies above, at the heap's top.
bool TookTheFreedPlace(uintptr_t freed, const char* next) {
  const auto at = reinterpret_cast<uintptr_t>(next);
  return at <= freed && freed - at < (1 << 20);
}

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
// Exits 0 when the next 256 MB array takes the freed one's place (TookTheFreedPlace: what the
// job keeps did not split it), 1 when it had to go elsewhere.
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
  const uintptr_t freed = AllocateAndFreeAnArray();
  for (const v1::JobEvent& event : events) job.AddEvent(event);
  job.SetPointSample(sample);
  job.SetPreview(preview);
  job.Succeed(statistics, v1::MeshSummary(), mesh);
  char* next = static_cast<char*>(std::malloc(kBytes));
  if (job.Closing()->mesh.view() != mesh || job.Events().size() != events.size()) std::_Exit(6);
  std::_Exit(TookTheFreedPlace(freed, next) ? 0 : 1);
}

TEST(ServerMallocPolicy, WhatAJobKeepsLeavesTheSpaceItsRunFreedWhole) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  GTEST_FLAG_SET(death_test_style, "threadsafe");  // a child started afresh, as below
  EXPECT_EXIT(KeepAJobsResultAfterAFreedArrayAndExit(), ::testing::ExitedWithCode(0), "");
}

// In a child process under the policy: a job on the scheduler's one worker frees a 256 MB
// array, then allocates and frees small blocks of many sizes (they stay in its thread's cache
// of freed blocks, inside the array's freed space). Exits 0 when, the job ended, the next
// 256 MB array takes the freed one's place (TookTheFreedPlace), 1 when it had to go elsewhere.
[[noreturn]] void RunAJobThatFreesSmallBlocksAndExit() {
  unsetenv("MALLOC_ARENA_MAX");
  unsetenv("GLIBC_TUNABLES");
  if (!UseMallocPolicyUnlessChosen()) std::_Exit(3);
  uintptr_t freed = 0;
  absl::BlockingCounter ended(1);
  JobScheduler scheduler(1, 1, [&](const std::shared_ptr<Job>& job) {
    // First, as a job's runner does: it starts the job (the thread's first lock, which
    // allocates the thread's own data for the locks' library) and makes what the job keeps
    // (its status here), neither of which is what this test is about.
    if (!job->Start()) std::_Exit(6);
    const absl::Status failed = absl::InternalError("a test job");
    freed = AllocateAndFreeAnArray();
    std::vector<void*> blocks;
    for (size_t size = 144; size <= 1024; size += 16) blocks.push_back(std::malloc(size));
    for (void* block : blocks) std::free(block);
    job->Fail(failed);
    ended.DecrementCount();
  });
  if (!scheduler.Submit(std::make_shared<Job>("job-1", "peer", v1::Parameters(), "")).ok()) {
    std::_Exit(5);
  }
  ended.Wait();
  scheduler.Shutdown(absl::InfiniteDuration());  // the job's thread has ended
  char* next = static_cast<char*>(std::malloc(kBytes));
  std::_Exit(TookTheFreedPlace(freed, next) ? 0 : 1);
}

TEST(ServerMallocPolicy, AJobsThreadTakesTheBlocksItFreedAlongWhenItEnds) {
  if (!kGlibcMalloc) GTEST_SKIP() << "glibc's malloc is replaced under the sanitizers";
  // A child started afresh: one forked from a process whose earlier tests ran threads could
  // give the job's thread one of their arenas, where a 256 MB block is mapped on its own.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(RunAJobThatFreesSmallBlocksAndExit(), ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace membrane::server
