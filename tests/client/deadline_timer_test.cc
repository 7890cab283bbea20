// DeadlineTimer on a clock the test moves: it cancels at the deadline, not before, and never
// once it is destroyed.
#include "client/deadline_timer.h"

#include <chrono>
#include <optional>

#include "core/base/cancel_token.h"
#include "gtest/gtest.h"
#include "tests/client/manual_timer_clock.h"

namespace membrane::client {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using testing::ManualTimerClock;

TEST(DeadlineTimer, CancelsTheTokenWhenTheClockReachesTheDeadline) {
  ManualTimerClock clock;
  CancelToken token;
  DeadlineTimer timer(2.0, &token, &clock);
  clock.AwaitWaiters(1);

  clock.Advance(milliseconds(1999));
  EXPECT_FALSE(token.cancelled());
  EXPECT_FALSE(timer.expired());
  EXPECT_EQ(clock.waiters(), 1);  // still waiting

  clock.Advance(milliseconds(1));
  EXPECT_TRUE(token.cancelled());
  EXPECT_TRUE(timer.expired());
  EXPECT_EQ(clock.waiters(), 0);  // done
}

TEST(DeadlineTimer, CancelsOnceTheClockIsPastTheDeadlineInOneStep) {
  ManualTimerClock clock;
  CancelToken token;
  DeadlineTimer timer(0.25, &token, &clock);
  clock.AwaitWaiters(1);
  clock.Advance(seconds(3600));
  EXPECT_TRUE(token.cancelled());
  EXPECT_TRUE(timer.expired());
}

TEST(DeadlineTimer, MeasuresFromItsConstructionNotFromTheClocksStart) {
  ManualTimerClock clock;
  clock.Advance(seconds(100));
  CancelToken token;
  DeadlineTimer timer(5.0, &token, &clock);
  clock.AwaitWaiters(1);
  clock.Advance(seconds(4));
  EXPECT_FALSE(token.cancelled());
  clock.Advance(seconds(1));
  EXPECT_TRUE(token.cancelled());
}

TEST(DeadlineTimer, DestroyedBeforeTheDeadlineNeverCancels) {
  ManualTimerClock clock;
  CancelToken token;
  std::optional<DeadlineTimer> timer;
  timer.emplace(2.0, &token, &clock);
  clock.AwaitWaiters(1);
  clock.Advance(seconds(1));
  timer.reset();  // the work finished in time
  EXPECT_EQ(clock.waiters(), 0);
  clock.Advance(seconds(10));
  EXPECT_FALSE(token.cancelled());
}

TEST(DeadlineTimer, NoDeadlineStartsNoThreadAndNeverCancels) {
  for (const double no_deadline : {0.0, -1.0}) {
    ManualTimerClock clock;
    CancelToken token;
    DeadlineTimer timer(no_deadline, &token, &clock);
    clock.Advance(seconds(1000000));
    EXPECT_EQ(clock.waiters(), 0) << no_deadline;
    EXPECT_FALSE(token.cancelled()) << no_deadline;
    EXPECT_FALSE(timer.expired()) << no_deadline;
  }
}

TEST(DeadlineTimer, TimersOnOneClockExpireInTheOrderOfTheirDeadlines) {
  ManualTimerClock clock;
  CancelToken early_token;
  CancelToken late_token;
  DeadlineTimer late(3.0, &late_token, &clock);
  DeadlineTimer early(1.0, &early_token, &clock);
  clock.AwaitWaiters(2);
  clock.Advance(seconds(1));
  EXPECT_TRUE(early_token.cancelled());
  EXPECT_FALSE(late_token.cancelled());
  clock.Advance(seconds(2));
  EXPECT_TRUE(late_token.cancelled());
}

// The steady clock with a deadline far away: the destructor stops the wait at once instead of
// waiting it out (a test that hung here would time out in ctest).
TEST(DeadlineTimer, OnTheSteadyClockDestructionEndsAFarWait) {
  CancelToken token;
  { DeadlineTimer timer(3600.0, &token); }
  EXPECT_FALSE(token.cancelled());
}

}  // namespace
}  // namespace membrane::client
