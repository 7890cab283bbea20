// Points with NaN or infinite coordinates, as organized scans mark missing returns: refused
// with their count by default, dropped on request with the others kept in order.
#include <cmath>
#include <limits>
#include <string>

#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::LittleEndianFloat;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A 3 x 2 organized PCD (binary) whose points 1 and 4 have no return.
std::string OrganizedPcd() {
  std::string pcd =
      "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 3\nHEIGHT 2\nPOINTS 6\n"
      "DATA binary\n";
  for (int i = 0; i < 6; ++i) {
    const float x = i == 1 || i == 4 ? kNaN : static_cast<float>(i);
    pcd += LittleEndianFloat(x) + LittleEndianFloat(x) + LittleEndianFloat(i == 4 ? kNaN : 1);
  }
  return pcd;
}

TEST(InvalidPoints, AreRefusedWithTheirCountByDefault) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer(OrganizedPcd(), FileFormat::kPcd, "scan.pcd");
  ASSERT_FALSE(cloud.ok());
  EXPECT_TRUE(absl::IsInvalidArgument(cloud.status()));
  EXPECT_THAT(cloud.status().message(),
              HasSubstr("scan.pcd: 2 points have NaN or infinite coordinates"));
}

TEST(InvalidPoints, AreDroppedOnRequestAndCounted) {
  size_t dropped = 99;
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(
      OrganizedPcd(), FileFormat::kPcd, "scan.pcd", InvalidPoints::kDrop, &dropped);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(dropped, 2u);
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{0, 0, 1}, Point3f{2, 2, 1}, Point3f{3, 3, 1},
                                         Point3f{5, 5, 1}));
}

TEST(InvalidPoints, PlyInfinityAndAsciiNanAreDroppedToo) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  for (float v : {1.0f, 2.0f, 3.0f, kInf, 0.0f, 0.0f, 4.0f, 5.0f, 6.0f}) {
    ply += LittleEndianFloat(v);
  }
  size_t dropped = 0;
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer(ply, FileFormat::kPly, "s.ply", InvalidPoints::kDrop, &dropped);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(dropped, 1u);
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1, 2, 3}, Point3f{4, 5, 6}));

  const std::string pcd =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 2\nDATA ascii\n"
      "nan nan nan\n1 2 3\nnan nan nan\n4 5 6\n";
  cloud = ReadPointCloudFromBuffer(pcd, FileFormat::kPcd, "a.pcd", InvalidPoints::kDrop, &dropped);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(dropped, 2u);
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1, 2, 3}, Point3f{4, 5, 6}));
}

TEST(InvalidPoints, AFiniteCloudDropsNothing) {
  size_t dropped = 99;
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(
      "1 2 3\n4 5 6\n", FileFormat::kXyz, "c.xyz", InvalidPoints::kDrop, &dropped);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(dropped, 0u);
  EXPECT_EQ(cloud->points.size(), 2u);
}

}  // namespace
}  // namespace membrane
