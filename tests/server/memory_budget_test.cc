// The memory budget's shares: a job's reservation grows stage by stage, waits while others
// hold the memory, and gives up when every holder waits (no share would ever shrink).
#include <atomic>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "server/memory_budget.h"

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

TEST(DefaultMemoryBudget, IsThreeQuartersOfTheTotalOrNoLimitWhenUnknown) {
  EXPECT_EQ(DefaultMemoryBudget(int64_t{16} << 30), int64_t{12} << 30);
  EXPECT_EQ(DefaultMemoryBudget(0), 0);
}

}  // namespace
}  // namespace membrane::server
