// The memory budget's shares: a job's reservation grows stage by stage (to the largest stage's
// estimate, through its MemoryBudgetGate), waits while others hold the memory, and gives up
// when every holder waits (no share would ever shrink).
#include <algorithm>
#include <atomic>
#include <optional>
#include <string>
#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "absl/strings/str_format.h"
#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "core/pipeline/memory_estimate.h"
#include "server/memory_budget.h"
#include "server/memory_budget_gate.h"

namespace membrane::server {
namespace {

TEST(MemoryBudget, ShareOverTheWholeBudgetIsRefusedAtOnce) {
  MemoryBudget budget(100);
  const CancelToken cancel;
  MemoryBudget::Share share(budget);
  ASSERT_TRUE(share.Add(60, cancel).ok());
  const absl::Status s = share.Add(41, cancel);
  EXPECT_EQ(s.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(s.message().find("needs about 101 bytes"), std::string::npos) << s.message();
  EXPECT_EQ(share.bytes(), 60);
}

// A download's conversion takes what is free now or is refused at once: it never waits
// behind the jobs, and its refusal names what it needed and what the jobs hold.
TEST(MemoryBudget, TryAddTakesWhatIsFreeNowAndNeverWaits) {
  MemoryBudget budget(100);
  const CancelToken cancel;
  MemoryBudget::Share job(budget);
  ASSERT_TRUE(job.Add(70, cancel).ok());
  {
    MemoryBudget::Share download(budget);
    const absl::Status busy = download.TryAdd(40, "converting");
    EXPECT_EQ(busy.code(), absl::StatusCode::kResourceExhausted);
    EXPECT_NE(busy.message().find("converting needs about 40 bytes while the running jobs hold "
                                  "70 of the server's memory budget of 100 bytes; retry later"),
              std::string::npos)
        << busy.message();
    const absl::Status over = download.TryAdd(101, "converting");
    EXPECT_NE(over.message().find("over the server's memory budget of 100 bytes"),
              std::string::npos)
        << over.message();
    ASSERT_TRUE(download.TryAdd(30, "converting").ok());
    EXPECT_EQ(budget.reserved(), 100);
  }
  EXPECT_EQ(budget.reserved(), 70);  // given back with the share
}

TEST(MemoryBudget, GrowthWaitsUntilAnotherJobEnds) {
  MemoryBudget budget(100);
  const CancelToken cancel;
  MemoryBudget::Share grower(budget);
  ASSERT_TRUE(grower.Add(50, cancel).ok());
  auto other = std::make_optional<MemoryBudget::Share>(budget);
  ASSERT_TRUE(other->Add(40, cancel).ok());
  std::atomic<bool> granted{false};
  std::thread t([&] {
    EXPECT_TRUE(grower.Add(30, cancel).ok());
    granted = true;
  });
  // 50 + 40 + 30 > 100: waits while the other job runs.
  while (budget.waiting() == 0 && !granted) std::this_thread::yield();
  EXPECT_FALSE(granted);
  EXPECT_EQ(budget.waiting(), 1);
  other.reset();          // the other job ends
  t.join();
  EXPECT_TRUE(granted);
  EXPECT_EQ(grower.bytes(), 80);
}

TEST(MemoryBudget, WhenEveryHolderWaitsOneGivesUpAndTheOtherProceeds) {
  MemoryBudget budget(100);
  const CancelToken cancel;
  std::optional<MemoryBudget::Share> a(std::in_place, budget), b(std::in_place, budget);
  ASSERT_TRUE(a->Add(50, cancel).ok());
  ASSERT_TRUE(b->Add(40, cancel).ok());
  absl::Status status_a, status_b;
  absl::Notification a_done, b_done;
  // Each job ends (its share goes back) once its own Add has answered, as a job does.
  std::thread ta([&] {
    status_a = a->Add(30, cancel);
    if (!status_a.ok()) a.reset();
    a_done.Notify();
  });
  std::thread tb([&] {
    status_b = b->Add(30, cancel);
    if (!status_b.ok()) b.reset();
    b_done.Notify();
  });
  ASSERT_TRUE(a_done.WaitForNotificationWithTimeout(absl::Seconds(10)));
  ASSERT_TRUE(b_done.WaitForNotificationWithTimeout(absl::Seconds(10)));
  ta.join();
  tb.join();
  // Both waited for the other: exactly one gave up, so the other could grow.
  EXPECT_NE(status_a.ok(), status_b.ok()) << status_a << " / " << status_b;
  const absl::Status& refused = status_a.ok() ? status_b : status_a;
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(refused.message().find("every running job waits"), std::string::npos)
      << refused.message();
}

TEST(MemoryBudget, WaitingEndsWhenTheJobIsCancelled) {
  MemoryBudget budget(100);
  CancelToken cancel;
  MemoryBudget::Share holder(budget);
  ASSERT_TRUE(holder.Add(90, CancelToken()).ok());
  MemoryBudget::Share newcomer(budget);  // holds nothing yet: it waits, it is not stuck
  std::thread t([&] { cancel.Cancel(); });
  const absl::Status s = newcomer.Add(20, cancel);
  t.join();
  EXPECT_EQ(s.code(), absl::StatusCode::kCancelled);
  EXPECT_EQ(newcomer.bytes(), 0);
}

TEST(MemoryBudget, NoBudgetGrantsEverything) {
  MemoryBudget budget(0);
  MemoryBudget::Share share(budget);
  EXPECT_TRUE(share.Add(int64_t{1} << 50, CancelToken()).ok());
}

// A job holds the larger of its grid's and its surface's estimates, not their sum: the surface's
// counts the grid it is built beside.
TEST(MemoryBudgetGate, TheShareGrowsToTheSurfacesPeakNotByIt) {
  MemoryBudget budget(int64_t{1} << 40);
  MemoryBudgetGate gate(budget, 0);
  PlannedGrid grid;
  grid.voxels = 100'000'000;
  grid.points = 1'000'000;
  grid.bytes = GridBytesEstimate(grid.voxels, grid.points);
  ASSERT_TRUE(gate.AdmitGrid(grid, grid.points, CancelToken()).ok());
  EXPECT_EQ(budget.reserved(), grid.bytes);
  MembraneCounts small;  // a surface within the grid's share takes nothing more
  small.hard_voxels = 1000;
  ASSERT_LE(SurfaceBytesEstimate(grid, small), grid.bytes);
  ASSERT_TRUE(gate.AdmitSurface(small, CancelToken()).ok());
  EXPECT_EQ(budget.reserved(), grid.bytes);
}

TEST(MemoryBudgetGate, ALargeSurfaceTakesItsPeak) {
  MemoryBudget budget(int64_t{1} << 40);
  MemoryBudgetGate gate(budget, 0);
  PlannedGrid grid;
  grid.voxels = 1'000'000;
  grid.points = 100'000;
  grid.bytes = GridBytesEstimate(grid.voxels, grid.points);
  ASSERT_TRUE(gate.AdmitGrid(grid, grid.points, CancelToken()).ok());
  MembraneCounts foam;
  foam.soft_voxels = 900'000;
  ASSERT_TRUE(gate.AdmitSurface(foam, CancelToken()).ok());
  EXPECT_EQ(budget.reserved(), SurfaceBytesEstimate(grid, foam));
}

// A grid over the whole budget is told the voxel_size whose grid fits it; one over what other
// jobs leave free waits instead (MemoryBudget's tests).
TEST(MemoryBudgetGate, AGridOverTheWholeBudgetNamesTheVoxelSizeThatFits) {
  PlannedGrid grid;
  grid.bounds = Box3d{{0, 0, 0}, {1, 1, 1}};
  grid.voxel_size = 0.001;
  grid.voxels = PlannedVoxelCount(grid.bounds, grid.voxel_size);
  grid.points = 1'000'000;
  grid.bytes = GridBytesEstimate(grid.voxels, grid.points);
  const int64_t total = int64_t{1} << 30;
  ASSERT_GT(grid.bytes, total);
  MemoryBudget budget(total);
  MemoryBudgetGate gate(budget, 0);
  const absl::Status refused = gate.AdmitGrid(grid, grid.points, CancelToken());
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted);
  const double fits = SmallestVoxelSizeWithin(grid, total);
  ASSERT_GT(fits, grid.voxel_size);
  EXPECT_THAT(std::string(refused.message()),
              ::testing::AllOf(::testing::HasSubstr("over the server's memory budget"),
                               ::testing::EndsWith(absl::StrFormat(
                                   "; use a larger voxel_size: %.3g or larger fits", fits))));
  EXPECT_EQ(budget.reserved(), 0);
}

TEST(MemoryBudgetGate, ASurfaceOverTheBudgetNamesTheMembrane) {
  PlannedGrid grid;
  grid.voxels = 1'000'000;
  grid.points = 100'000;
  grid.bytes = GridBytesEstimate(grid.voxels, grid.points);
  MemoryBudget budget(grid.bytes + 1000);
  MemoryBudgetGate gate(budget, 0);
  ASSERT_TRUE(gate.AdmitGrid(grid, grid.points, CancelToken()).ok());
  MembraneCounts foam;
  foam.soft_voxels = 900'000;
  const absl::Status refused = gate.AdmitSurface(foam, CancelToken());
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_NE(refused.message().find("the surface of a membrane of 900000 voxels"),
            std::string::npos)
      << refused.message();
}

// Draco's encoder holds tables of 2^bits entries whatever the mesh (3.56 GB more at 30 bits
// than at 11 on a 1M-point torus): a job's surface share counts them beside the surface.
TEST(MemoryBudgetGate, TheSurfaceShareCountsTheEncodersTables) {
  EXPECT_EQ(DracoTableBytes(0), 0);
  EXPECT_EQ(DracoTableBytes(11), 4 << 11);
  EXPECT_GE(DracoTableBytes(30), int64_t{3'560'000'000});
  PlannedGrid grid;
  grid.voxels = 1'000'000;
  grid.points = 100'000;
  grid.bytes = GridBytesEstimate(grid.voxels, grid.points);
  MembraneCounts membrane;
  membrane.soft_voxels = 10'000;
  MemoryBudget budget(int64_t{1} << 40);
  MemoryBudgetGate gate(budget, 30);
  ASSERT_TRUE(gate.AdmitGrid(grid, grid.points, CancelToken()).ok());
  ASSERT_TRUE(gate.AdmitSurface(membrane, CancelToken()).ok());
  EXPECT_EQ(budget.reserved(),
            std::max(SurfaceBytesEstimate(grid, membrane), grid.bytes) + DracoTableBytes(30));
}

TEST(DefaultMemoryBudget, IsThreeQuartersOfTheTotalOrNoLimitWhenUnknown) {
  EXPECT_EQ(DefaultMemoryBudget(int64_t{16} << 30), int64_t{12} << 30);
  EXPECT_EQ(DefaultMemoryBudget(0), 0);
}

}  // namespace
}  // namespace membrane::server
