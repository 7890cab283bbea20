// PCD reading: ascii and binary DATA, fields skipped by SIZE and COUNT (binary_compressed:
// pcd_compressed_test.cc).
#include <cstdint>
#include <string>

#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::LittleEndianDouble;
using ::membrane::testing::LittleEndianFloat;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(PcdReader, AsciiWithRgbAndMultiCountFields) {
  const std::string pcd =
      "# .PCD v0.7 - Point Cloud Data file format\n"
      "VERSION 0.7\n"
      "FIELDS normal x y z rgb\n"
      "SIZE 4 4 4 4 4\n"
      "TYPE F F F F U\n"
      "COUNT 3 1 1 1 1\n"
      "WIDTH 2\n"
      "HEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\n"
      "POINTS 2\n"
      "DATA ascii\n"
      "0 0 1 1.5 2.5 3.5 4278190080\n"
      "0 1 0 -1 -2 -3 16711680\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1.5f, 2.5f, 3.5f}, Point3f{-1, -2, -3}));
}

TEST(PcdReader, BinaryWithDoubleCoordinatesAndPaddingFields) {
  std::string pcd =
      "VERSION .7\n"
      "FIELDS intensity x y z _ label\n"
      "SIZE 2 8 8 8 1 4\n"
      "TYPE U F F F U I\n"
      "COUNT 1 1 1 1 3 1\n"
      "WIDTH 2\n"
      "HEIGHT 1\n"
      "POINTS 2\n"
      "DATA binary\n";
  for (int i = 0; i < 2; ++i) {
    pcd += std::string(2, '\x11') + LittleEndianDouble(i + 0.5) + LittleEndianDouble(-i) +
           LittleEndianDouble(100.0 * i) + std::string(3, '\0') + std::string(4, '\x22');
  }
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{0.5f, 0, 0}, Point3f{1.5f, -1, 100}));
}

TEST(PcdReader, BinaryFloatWithoutCountLineDefaultsToOne) {
  std::string pcd = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nDATA binary\n";
  pcd += LittleEndianFloat(1) + LittleEndianFloat(2) + LittleEndianFloat(3);
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1, 2, 3}));
}

TEST(PcdReader, IntegerCoordinatesAreRejected) {
  const std::string pcd = "FIELDS x y z\nSIZE 4 4 4\nTYPE I I I\nPOINTS 1\nDATA ascii\n1 2 3\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd, "i.pcd");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("'x' must be TYPE F"));
}

TEST(PcdReader, TruncatedBinaryNamesByteOffset) {
  std::string pcd = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 3\nDATA binary\n";
  const size_t body = pcd.size();
  for (int i = 0; i < 3; ++i)
    pcd += LittleEndianFloat(1) + LittleEndianFloat(2) + LittleEndianFloat(3);
  pcd.resize(pcd.size() - 5);  // point 2 loses its last bytes
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd, "t.pcd");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("t.pcd: at byte " + std::to_string(body + 24) +
                                                   ": the data ends inside point 2 of 3"));
}

TEST(PcdReader, AsciiWithFewerLinesThanPointsIsInvalidArgument) {
  const std::string pcd =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 3\nDATA ascii\n1.000 2.000 3.000\n4.000 5.000 "
      "6.000\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd, "a.pcd");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("after 2 of 3 points"));
}

TEST(PcdReader, PointsDisagreeingWithWidthTimesHeightIsInvalidArgument) {
  const std::string pcd =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd);
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("disagrees"));
}

}  // namespace
}  // namespace membrane
