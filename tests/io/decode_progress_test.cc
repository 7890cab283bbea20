// The fraction of a Draco decode in a child process: the decoder's share by its CPU time, then
// the points read back by their bytes, never going back and ending at the points' end.
#include <unistd.h>

#include <cstdint>
#include <optional>

#include <gtest/gtest.h>

#include "core/base/progress_meter.h"
#include "core/io/decode_progress.h"

namespace membrane {
namespace {

TEST(DecodeProgress, ProcessCpuTicksReadsALiveProcess) {
  EXPECT_GE(ProcessCpuTicks(getpid()), 0);
  EXPECT_EQ(ProcessCpuTicks(-1), -1);
}

TEST(DecodeProgress, TheDecoderShareHoldsBelowThePointsUntilTheyCome) {
  // This process stands in for the child: its CPU time so far counts, and past 1 byte's
  // expected time (one tick) it holds at the decoder's share. The loop spends the tick.
  while (ProcessCpuTicks(getpid()) < 1) {
  }
  ProgressMeter meter;
  DecodeProgress progress(ProgressRange(&meter), 1, getpid());
  ASSERT_TRUE(meter.fraction().has_value());
  EXPECT_EQ(*meter.fraction(), 0);
  progress.Update(0, std::nullopt);
  EXPECT_EQ(*meter.fraction(), kDecoderShare);
  // Part of a count is no count yet.
  progress.Update(3, std::nullopt);
  EXPECT_EQ(*meter.fraction(), kDecoderShare);
}

TEST(DecodeProgress, ThePointsReadBackTakeTheRestToOne) {
  ProgressMeter meter;
  DecodeProgress progress(ProgressRange(&meter), 1 << 20, getpid());
  const uint64_t points = 1000;
  const size_t total = 8 + 12 * points;
  double last = *meter.fraction();
  for (size_t bytes : {size_t{8}, total / 2, total - 1, total}) {
    progress.Update(bytes, points);
    const double f = *meter.fraction();
    EXPECT_GE(f, kDecoderShare) << bytes;
    EXPECT_GE(f, last) << bytes;
    last = f;
  }
  EXPECT_EQ(*meter.fraction(), 1.0);
}

}  // namespace
}  // namespace membrane
