// XYZ/TXT/PTS reading: extra columns, comments, separators, the .pts count line.
#include <string>

#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(XyzReader, ExtraColumnsAndCommentsAreIgnored) {
  const std::string xyz =
      "# x y z r g b\n"
      "// exported by a scanner\n"
      "\n"
      "1 2 3 255 0 0\n"
      "  4.5\t5.5  6.5 0.1 0.2 0.3 label\r\n"
      "-1e-2 0 +7\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(xyz, FileFormat::kXyz);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points,
              ElementsAre(Point3f{1, 2, 3}, Point3f{4.5f, 5.5f, 6.5f}, Point3f{-1e-2f, 0, 7}));
}

TEST(XyzReader, CommaAndSemicolonSeparatedColumnsAreAccepted) {
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer("1,2,3\n4;5;6;7\n", FileFormat::kXyz);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1, 2, 3}, Point3f{4, 5, 6}));
}

TEST(XyzReader, PtsCountLineIsSkippedWhenItMatches) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer("2\n1 2 3 -100 255 0 0\n4 5 6 -120 0 255 0\n", FileFormat::kXyz);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1, 2, 3}, Point3f{4, 5, 6}));
}

TEST(XyzReader, PtsCountLineThatDisagreesIsInvalidArgument) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer("3\n1 2 3\n4 5 6\n", FileFormat::kXyz, "short.pts");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(
      cloud.status().ToString(),
      HasSubstr(
          "short.pts: at byte 14: the data ends after 2 points but the count line declares 3"));
}

TEST(XyzReader, LineWithTwoNumbersNamesLineAndByte) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer("1 2 3\n4 5\n", FileFormat::kXyz, "two.xyz");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("two.xyz: line 2 (byte 9)"));
}

TEST(XyzReader, NonNumericTokenIsNamed) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer("1 2 3\n4 five 6\n", FileFormat::kXyz, "word.xyz");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("'five' is not a number"));
}

}  // namespace
}  // namespace membrane
