// Backoff's delays: doubling from the initial delay up to the cap, or the server's RetryInfo
// delay when that is longer, with 0-20% jitter on top.
#include "client/backoff.h"

#include <algorithm>
#include <optional>
#include <vector>

#include "absl/time/time.h"
#include "gtest/gtest.h"

namespace membrane::client {
namespace {

constexpr double kMaxJitter = 1.2;

// The delays of `n` calls with no server hint.
std::vector<absl::Duration> Delays(absl::Duration initial, absl::Duration max, int n) {
  Backoff backoff(initial, max);
  std::vector<absl::Duration> delays;
  for (int i = 0; i < n; ++i) delays.push_back(backoff.Next(std::nullopt));
  return delays;
}

TEST(Backoff, DoublesFromTheInitialDelayWithinTheJitter) {
  const absl::Duration initial = absl::Milliseconds(100);
  const std::vector<absl::Duration> delays = Delays(initial, absl::Seconds(100), 8);
  absl::Duration base = initial;
  for (const absl::Duration delay : delays) {
    EXPECT_GE(delay, base);
    EXPECT_LE(delay, base * kMaxJitter);
    base *= 2;
  }
}

TEST(Backoff, GrowsStrictlyUntilTheCap) {
  // Doubling outgrows 20% jitter: each delay exceeds the one before.
  for (int run = 0; run < 50; ++run) {
    const std::vector<absl::Duration> delays =
        Delays(absl::Milliseconds(10), absl::Seconds(100), 12);
    for (size_t i = 1; i < delays.size(); ++i) EXPECT_GT(delays[i], delays[i - 1]) << i;
  }
}

TEST(Backoff, StaysAtTheCapWithinTheJitter) {
  const absl::Duration max = absl::Seconds(5);
  const std::vector<absl::Duration> delays = Delays(absl::Milliseconds(100), max, 30);
  // 100 ms doubled 6 times is 6.4 s: from the 7th delay on, the base is the cap.
  for (size_t i = 6; i < delays.size(); ++i) {
    EXPECT_GE(delays[i], max) << i;
    EXPECT_LE(delays[i], max * kMaxJitter) << i;
  }
}

TEST(Backoff, AnInitialDelayAboveTheCapIsUsedOnceThenCapped) {
  const std::vector<absl::Duration> delays =
      Delays(absl::Seconds(10), absl::Seconds(2), 3);
  EXPECT_GE(delays[0], absl::Seconds(10));
  EXPECT_LE(delays[0], absl::Seconds(10) * kMaxJitter);
  for (size_t i = 1; i < delays.size(); ++i) {
    EXPECT_GE(delays[i], absl::Seconds(2)) << i;
    EXPECT_LE(delays[i], absl::Seconds(2) * kMaxJitter) << i;
  }
}

TEST(Backoff, JitterSpreadsClientsRefusedTogether) {
  // 200 clients' first delays: uniform over [1, 1.2) times the initial delay, so some fall in
  // each end quarter (the chance that none does is 2 * 0.75^200, about 1e-25).
  const absl::Duration initial = absl::Seconds(1);
  absl::Duration lowest = absl::InfiniteDuration();
  absl::Duration highest = absl::ZeroDuration();
  for (int client = 0; client < 200; ++client) {
    const absl::Duration delay = Backoff(initial, absl::Seconds(60)).Next(std::nullopt);
    lowest = std::min(lowest, delay);
    highest = std::max(highest, delay);
  }
  EXPECT_LT(lowest, initial * 1.05);
  EXPECT_GT(highest, initial * 1.15);
}

TEST(Backoff, ALongerServerHintWinsWithinTheJitter) {
  Backoff backoff(absl::Milliseconds(100), absl::Seconds(1));
  const absl::Duration first = backoff.Next(absl::Seconds(3));
  EXPECT_GE(first, absl::Seconds(3));
  EXPECT_LE(first, absl::Seconds(3) * kMaxJitter);
  // Beyond the cap too: the server knows when it will have room.
  const absl::Duration second = backoff.Next(absl::Seconds(30));
  EXPECT_GE(second, absl::Seconds(30));
  EXPECT_LE(second, absl::Seconds(30) * kMaxJitter);
}

TEST(Backoff, JitterSpreadsClientsGivenTheSameServerHint) {
  // A full queue gives every client it refuses the same delay; the jitter parts them.
  absl::Duration lowest = absl::InfiniteDuration();
  absl::Duration highest = absl::ZeroDuration();
  for (int client = 0; client < 200; ++client) {
    const absl::Duration delay =
        Backoff(absl::Milliseconds(10), absl::Seconds(1)).Next(absl::Seconds(2));
    lowest = std::min(lowest, delay);
    highest = std::max(highest, delay);
  }
  EXPECT_LT(lowest, absl::Seconds(2) * 1.05);
  EXPECT_GT(highest, absl::Seconds(2) * 1.15);
}

TEST(Backoff, AShorterServerHintLeavesTheBackoff) {
  Backoff backoff(absl::Seconds(1), absl::Seconds(10));
  const absl::Duration first = backoff.Next(absl::Milliseconds(1));
  EXPECT_GE(first, absl::Seconds(1));
  EXPECT_LE(first, absl::Seconds(1) * kMaxJitter);
  // The hint does not reset the doubling.
  const absl::Duration second = backoff.Next(absl::ZeroDuration());
  EXPECT_GE(second, absl::Seconds(2));
  EXPECT_LE(second, absl::Seconds(2) * kMaxJitter);
}

}  // namespace
}  // namespace membrane::client
