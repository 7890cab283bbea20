// A point cloud in Draco parts: the parts decode to the points one cloud decodes to, they are
// slabs of nearly equal counts, and bad part tables or parts are refused naming the part.
#include "core/io/draco_parts.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "draco/compression/encode.h"
#include "draco/point_cloud/point_cloud.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::Octahedron;
using ::membrane::testing::SampleCloud;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::UnorderedElementsAreArray;

// 14-bit positions on an explicit box around SampleCloud's [-scale, scale] cube.
DracoOptions BoxOptions() {
  return {.position_quantization_bits = 14,
          .compression_level = 7,
          .box = PositionBox{{-10.5f, -10.5f, -10.5f}, 21.0f}};
}

std::vector<Point3f> Sorted(std::vector<Point3f> points) {
  std::sort(points.begin(), points.end());
  return points;
}

TEST(DracoParts, PartsOnOneBoxDecodeToTheSamePointsAsOneCloud) {
  const PointCloud cloud = SampleCloud(20000);
  absl::StatusOr<DracoEncoding> one = EncodeDracoPointCloud(cloud, BoxOptions());
  ASSERT_TRUE(one.ok()) << one.status();
  absl::StatusOr<DecodedDracoCloud> as_one = DecodeDracoPointCloud(one->bytes);
  ASSERT_TRUE(as_one.ok()) << as_one.status();
  for (int threads : {1, 3}) {
    absl::StatusOr<DracoParts> parts =
        EncodeDracoPointCloudParts(cloud.points, BoxOptions(), 5, threads);
    ASSERT_TRUE(parts.ok()) << parts.status();
    ASSERT_EQ(parts->part_bytes.size(), 5u);
    uint64_t sum = 0;
    for (uint64_t size : parts->part_bytes) sum += size;
    EXPECT_EQ(sum, parts->bytes.size());
    EXPECT_EQ(parts->max_position_error, one->max_position_error);
    for (int decode_threads : {1, 2, 4}) {
      absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloudParts(
          parts->bytes, parts->part_bytes, DracoMeshPolicy::kRejectMesh, decode_threads);
      ASSERT_TRUE(decoded.ok()) << decoded.status();
      EXPECT_EQ(decoded->attributes, as_one->attributes);
      // Bit for bit the same float32 points, in another order.
      EXPECT_EQ(Sorted(decoded->cloud.points), Sorted(as_one->cloud.points))
          << threads << " encode threads, " << decode_threads << " decode threads";
    }
  }
}

TEST(DracoParts, DecodedPartByPartTheyJoinToTheDecodedCloud) {
  const PointCloud cloud = SampleCloud(9000);
  absl::StatusOr<DracoParts> parts = EncodeDracoPointCloudParts(cloud.points, BoxOptions(), 4, 2);
  ASSERT_TRUE(parts.ok()) << parts.status();
  absl::StatusOr<DecodedDracoCloud> joined = DecodeDracoPointCloudParts(
      parts->bytes, parts->part_bytes, DracoMeshPolicy::kRejectMesh, 2);
  ASSERT_TRUE(joined.ok()) << joined.status();
  absl::StatusOr<std::vector<DecodedDracoCloud>> each =
      DecodeDracoParts(parts->bytes, parts->part_bytes, DracoMeshPolicy::kRejectMesh, 3);
  ASSERT_TRUE(each.ok()) << each.status();
  ASSERT_EQ(each->size(), 4u);
  std::vector<Point3f> in_order;
  for (const DecodedDracoCloud& part : *each) {
    EXPECT_EQ(part.attributes, joined->attributes);
    in_order.insert(in_order.end(), part.cloud.points.begin(), part.cloud.points.end());
  }
  EXPECT_EQ(in_order, joined->cloud.points);
  // No part table: the bytes are one cloud, one part.
  absl::StatusOr<DracoEncoding> one = EncodeDracoPointCloud(cloud, BoxOptions());
  ASSERT_TRUE(one.ok()) << one.status();
  absl::StatusOr<std::vector<DecodedDracoCloud>> whole =
      DecodeDracoParts(one->bytes, {}, DracoMeshPolicy::kRejectMesh, 2);
  ASSERT_TRUE(whole.ok()) << whole.status();
  ASSERT_EQ(whole->size(), 1u);
  EXPECT_EQ(Sorted(whole->front().cloud.points), Sorted(joined->cloud.points));
  // A part's error names it, as the joined decode's does.
  std::string broken = parts->bytes;
  broken[parts->part_bytes[0] + 3] ^= 0x55;
  absl::StatusOr<std::vector<DecodedDracoCloud>> bad =
      DecodeDracoParts(broken, parts->part_bytes, DracoMeshPolicy::kRejectMesh, 2);
  EXPECT_FALSE(bad.ok());
  EXPECT_THAT(bad.status().message(), HasSubstr("part 2 of 4"));
}

TEST(DracoParts, LosslessPartsKeepEveryPoint) {
  const PointCloud cloud = SampleCloud(3000);
  absl::StatusOr<DracoParts> parts = EncodeDracoPointCloudParts(
      cloud.points, {.position_quantization_bits = 0}, 3, 2);
  ASSERT_TRUE(parts.ok()) << parts.status();
  EXPECT_EQ(parts->max_position_error, 0);
  absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloudParts(
      parts->bytes, parts->part_bytes, DracoMeshPolicy::kRejectMesh, 2);
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_THAT(decoded->cloud.points, UnorderedElementsAreArray(cloud.points));
}

TEST(DracoParts, PartsAreSlabsOfNearlyEqualCountsAcrossTheLongestSide) {
  // Twice as long along y: the slabs cut y.
  PointCloud cloud = SampleCloud(12000);
  for (Point3f& p : cloud.points) p[1] *= 2;
  DracoOptions options = BoxOptions();
  options.box = PositionBox{{-21, -21, -21}, 42};
  absl::StatusOr<DracoParts> parts = EncodeDracoPointCloudParts(cloud.points, options, 4, 2);
  ASSERT_TRUE(parts.ok()) << parts.status();
  ASSERT_EQ(parts->part_bytes.size(), 4u);
  float last_high = -1e9f;
  uint64_t begin = 0;
  for (uint64_t size : parts->part_bytes) {
    absl::StatusOr<DecodedDracoCloud> part =
        DecodeDracoPointCloud(absl::string_view(parts->bytes).substr(begin, size));
    begin += size;
    ASSERT_TRUE(part.ok()) << part.status();
    // A histogram bin (1/4096 of the side) of points from a quarter each.
    EXPECT_NEAR(part->cloud.points.size(), 3000.0, 100.0);
    float low = 1e9f, high = -1e9f;
    for (const Point3f& p : part->cloud.points) {
      low = std::min(low, p[1]);
      high = std::max(high, p[1]);
    }
    EXPECT_GE(low, last_high);
    last_high = high;
  }
}

TEST(DracoParts, OnePartIsOneDracoCloud) {
  const PointCloud cloud = SampleCloud(500);
  absl::StatusOr<DracoParts> parts = EncodeDracoPointCloudParts(cloud.points, BoxOptions(), 1, 2);
  absl::StatusOr<DracoEncoding> one = EncodeDracoPointCloud(cloud, BoxOptions());
  ASSERT_TRUE(parts.ok() && one.ok());
  EXPECT_EQ(parts->bytes, one->bytes);
  EXPECT_THAT(parts->part_bytes, ElementsAre(one->bytes.size()));
  // Points all in one slab: one part however many were asked for.
  absl::StatusOr<DracoParts> same = EncodeDracoPointCloudParts(
      std::vector<Point3f>(50, Point3f{1, 2, 3}), BoxOptions(), 4, 2);
  ASSERT_TRUE(same.ok()) << same.status();
  EXPECT_EQ(same->part_bytes.size(), 1u);
}

TEST(DracoParts, QuantizedPartsWithoutABoxAreRefused) {
  absl::StatusOr<DracoParts> parts =
      EncodeDracoPointCloudParts(SampleCloud(100).points, {.position_quantization_bits = 11}, 2, 1);
  EXPECT_EQ(parts.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(parts.status().message(), HasSubstr("explicit quantization box"));
}

TEST(DracoParts, NonFiniteCoordinatesAreRefusedBeforeTheSlabs) {
  std::vector<Point3f> points = SampleCloud(100).points;
  points[40][2] = std::numeric_limits<float>::quiet_NaN();
  absl::StatusOr<DracoParts> parts = EncodeDracoPointCloudParts(points, BoxOptions(), 3, 1);
  EXPECT_EQ(parts.status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(DracoParts, PartCountFollowsThePoints) {
  EXPECT_EQ(DracoPartCount(100'000), 1);
  EXPECT_EQ(DracoPartCount(500'000), 1);
  EXPECT_EQ(DracoPartCount(1'000'000), 3);
  EXPECT_EQ(DracoPartCount(10'000'000), kMaxEncodedParts);
}

TEST(DracoPartBytes, SizesMustBePositiveFewAndSumToTheUpload) {
  EXPECT_TRUE(CheckDracoPartBytes({}, 100).ok());
  EXPECT_TRUE(CheckDracoPartBytes({60, 40}, 100).ok());
  const auto message = [](std::vector<uint64_t> sizes, uint64_t total) {
    const absl::Status s = CheckDracoPartBytes(sizes, total);
    EXPECT_EQ(s.code(), absl::StatusCode::kInvalidArgument);
    return std::string(s.message());
  };
  EXPECT_THAT(message({60, 30}, 100), HasSubstr("sum to 90 bytes, not the upload's 100"));
  EXPECT_THAT(message({60, 0, 40}, 100), HasSubstr("part 2 of 3 is empty"));
  EXPECT_THAT(message({60, 50}, 100), HasSubstr("at part 2 of 2"));
  EXPECT_THAT(message({1, UINT64_MAX}, 100), HasSubstr("at part 2 of 2"));
  EXPECT_THAT(message(std::vector<uint64_t>(kMaxDracoParts + 1, 1), kMaxDracoParts + 1),
              HasSubstr("65 parts, over the limit of 64"));
}

// The parts of `clouds`' Draco bytes, one after the other, and their sizes.
std::pair<std::string, std::vector<uint64_t>> Concatenated(const std::vector<std::string>& parts) {
  std::pair<std::string, std::vector<uint64_t>> result;
  for (const std::string& p : parts) {
    result.first += p;
    result.second.push_back(p.size());
  }
  return result;
}

std::string CloudBytes(int n) {
  absl::StatusOr<DracoEncoding> e = EncodeDracoPointCloud(SampleCloud(n), BoxOptions());
  EXPECT_TRUE(e.ok()) << e.status();
  return e.ok() ? e->bytes : std::string();
}

TEST(DracoParts, APartThatIsNotDracoIsNamed) {
  const auto [bytes, sizes] = Concatenated({CloudBytes(100), std::string(40, 'x')});
  absl::StatusOr<DecodedDracoCloud> decoded =
      DecodeDracoPointCloudParts(bytes, sizes, DracoMeshPolicy::kRejectMesh, 2);
  EXPECT_EQ(decoded.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(decoded.status().message(),
              HasSubstr(absl::StrCat("part 2 of 2 (bytes ", sizes[0], "..", bytes.size(),
                                     "): not valid Draco data")));
}

TEST(DracoParts, AMeshAmongCloudsIsNamed) {
  absl::StatusOr<DracoEncoding> mesh = EncodeDracoMesh(Octahedron(), BoxOptions());
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  const auto [bytes, sizes] = Concatenated({CloudBytes(100), CloudBytes(50), mesh->bytes});
  absl::StatusOr<DecodedDracoCloud> refused =
      DecodeDracoPointCloudParts(bytes, sizes, DracoMeshPolicy::kRejectMesh, 2);
  EXPECT_THAT(refused.status().message(), HasSubstr("part 3 of 3"));
  EXPECT_THAT(refused.status().message(), HasSubstr("a mesh where a point cloud is required"));
  absl::StatusOr<DecodedDracoCloud> mixed =
      DecodeDracoPointCloudParts(bytes, sizes, DracoMeshPolicy::kAcceptMeshVertices, 2);
  EXPECT_EQ(mixed.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(mixed.status().message(),
              HasSubstr("holds a mesh where part 1 holds a point cloud"));
}

TEST(DracoParts, APartWithOtherAttributesIsNamed) {
  // Part 2 carries normals beside its positions.
  draco::PointCloud pc;
  pc.set_num_points(3);
  for (auto type : {draco::GeometryAttribute::POSITION, draco::GeometryAttribute::NORMAL}) {
    draco::GeometryAttribute attribute;
    attribute.Init(type, nullptr, 3, draco::DT_FLOAT32, false, 12, 0);
    const int id = pc.AddAttribute(attribute, true, 3);
    const float values[9] = {0, 0, 1, 0, 1, 0, 1, 0, 0};
    pc.attribute(id)->buffer()->Write(0, values, sizeof values);
  }
  draco::Encoder encoder;
  draco::EncoderBuffer buffer;
  ASSERT_TRUE(encoder.EncodePointCloudToBuffer(pc, &buffer).ok());
  const auto [bytes, sizes] =
      Concatenated({CloudBytes(100), std::string(buffer.data(), buffer.size())});
  absl::StatusOr<DecodedDracoCloud> decoded =
      DecodeDracoPointCloudParts(bytes, sizes, DracoMeshPolicy::kRejectMesh, 1);
  EXPECT_EQ(decoded.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(decoded.status().message(),
              HasSubstr("has the attributes POSITION float32 x3, NORMAL float32 x3 where part 1 "
                        "has POSITION float32 x3"));
}

TEST(DracoParts, ABadPartTableIsRefusedBeforeDecoding) {
  const std::string bytes = CloudBytes(100);
  absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloudParts(
      bytes, {bytes.size() - 1}, DracoMeshPolicy::kRejectMesh, 1);
  EXPECT_EQ(decoded.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(decoded.status().message(), HasSubstr("sum to"));
}

}  // namespace
}  // namespace membrane
