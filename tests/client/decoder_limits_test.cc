// The limits of the child that decodes a user's Draco file: a small (possibly hostile) file
// gets the base, a large real result gets time and memory in proportion to its size.
#include <string>

#include "client/input_files.h"
#include "gtest/gtest.h"

namespace membrane::client {
namespace {

TEST(DecoderLimits, ATinyFileGetsTheBaseTimeAndMemory) {
  const DecodeLimits limits = DecoderLimits(std::string(30, 'x'), "tiny.drc");
  EXPECT_NEAR(limits.timeout_seconds, 30.0, 0.01);
  EXPECT_EQ(limits.memory_bytes, (int64_t{1} << 30) + 32 * 30);
  EXPECT_EQ(limits.subject, "tiny.drc");
  ASSERT_EQ(limits.helper.size(), 2u);
  EXPECT_EQ(limits.helper[1], kDecodeHelperFlag);
}

TEST(DecoderLimits, TheMeshOfATenMillionPointCloudGetsTimeInProportion) {
  // 7 MiB: the size of a 15.3M-face .drc, which took over 30 s of wall on a loaded machine.
  const std::string bytes(7 << 20, 'x');
  const DecodeLimits limits = DecoderLimits(bytes, "scan.drc");
  EXPECT_NEAR(limits.timeout_seconds, 100.0, 0.01);
  EXPECT_EQ(limits.memory_bytes, (int64_t{1} << 30) + int64_t{32} * (7 << 20));
}

}  // namespace
}  // namespace membrane::client
