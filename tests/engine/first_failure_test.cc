#include "core/engine/first_failure.h"

#include <cstdint>
#include <vector>

#include "core/base/cancel_token.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// Candidates 0 .. n-1 split into `spans` equal spans; the scan in order tests each and stops at
// the first failure: the answer FindFirstFailure must give for any thread and span count.
FirstFailure ScanInOrder(const std::vector<bool>& fails) {
  FirstFailure out;
  for (bool f : fails) {
    ++out.tested;
    if (f) {
      out.failed = true;
      break;
    }
  }
  return out;
}

FirstFailure Find(const std::vector<bool>& fails, int64_t spans, int threads,
                  const CancelToken& cancel = CancelToken::Never()) {
  const int64_t n = static_cast<int64_t>(fails.size());
  return FindFirstFailure(
      spans, threads, cancel,
      [&](int64_t span, auto visit) {
        for (int64_t i = n * span / spans; i < n * (span + 1) / spans; ++i) {
          if (!visit(i)) return;
        }
      },
      [&](int64_t i) { return static_cast<bool>(fails[static_cast<size_t>(i)]); });
}

TEST(FirstFailureTest, CountsTheTestsOfTheScanInOrder) {
  uint64_t state = 7;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial * 37 % 5000;
    std::vector<bool> fails(static_cast<size_t>(n), false);
    // Up to three failures anywhere, or none: the first one decides.
    const int failures = trial % 4;
    for (int k = 0; k < failures; ++k) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      fails[static_cast<size_t>((state >> 33) % static_cast<uint64_t>(n))] = true;
    }
    const FirstFailure expected = ScanInOrder(fails);
    for (int threads : {1, 2, 3}) {
      for (int64_t spans : {int64_t{1}, int64_t{2}, int64_t{7}, int64_t{64}, int64_t{n}}) {
        const FirstFailure got = Find(fails, spans, threads);
        EXPECT_FALSE(got.cancelled);
        EXPECT_EQ(got.failed, expected.failed) << n << " " << threads << " " << spans;
        EXPECT_EQ(got.tested, expected.tested) << n << " " << threads << " " << spans;
      }
    }
  }
}

TEST(FirstFailureTest, NoCandidatesTestNothing) {
  const FirstFailure got = Find({}, 1, 2);
  EXPECT_FALSE(got.failed);
  EXPECT_EQ(got.tested, 0);
}

TEST(FirstFailureTest, ACancelledScanSaysSo) {
  CancelToken cancel;
  cancel.Cancel();
  // Polled every 4096 tests of a worker: 100k candidates reach the poll on any split.
  const FirstFailure got = Find(std::vector<bool>(100000, false), 16, 2, cancel);
  EXPECT_TRUE(got.cancelled);
}

}  // namespace
}  // namespace membrane
