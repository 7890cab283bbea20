// The Draco decoder child (core/io/decode_subprocess.h) as membraned runs it: a decode counts
// its progress to the end.
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "core/base/progress_meter.h"
#include "core/io/decode_subprocess.h"
#include "tests/server/draco_upload.h"

namespace membrane::testing {
namespace {

TEST(DecodeSubprocess, ADecodedCloudEndsItsProgressAtOne) {
  const std::string upload = LosslessDracoCloud("sphere", 2000);
  ProgressMeter meter;
  DecodeLimits limits;
  limits.helper = {MEMBRANE_DECODE_BINARY};
  const absl::StatusOr<PointCloud> cloud =
      DecodeInSubprocess(upload, limits, CancelToken::Never(), ProgressRange(&meter));
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(cloud->points.size(), 2000u);
  EXPECT_EQ(meter.fraction(), std::optional<double>(1.0));
}

TEST(DecodeSubprocess, ARefusedUploadDoesNotEndItsProgress) {
  ProgressMeter meter;
  DecodeLimits limits;
  limits.helper = {MEMBRANE_DECODE_BINARY};
  const absl::StatusOr<PointCloud> cloud = DecodeInSubprocess(
      std::string(100, 'x'), limits, CancelToken::Never(), ProgressRange(&meter));
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument) << cloud.status();
  ASSERT_TRUE(meter.fraction().has_value());
  EXPECT_LE(*meter.fraction(), 0.9);
}

}  // namespace
}  // namespace membrane::testing
