// The checks made before Draco decodes a point cloud: the metadata walk must agree with Draco's
// own reading of real files, and impossible counts and sizes are refused without allocating.
#include "core/io/draco_header.h"

#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

#include "absl/strings/escaping.h"
#include "core/io/draco_codec.h"
#include "draco/compression/encode.h"
#include "draco/metadata/geometry_metadata.h"
#include "draco/point_cloud/point_cloud.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::HasSubstr;

constexpr int kPoints = 1237;

// A Draco point cloud of kPoints points with metadata on its position attribute and on the
// file, nested three levels deep, encoded by Draco itself at `speed` (10: the sequential
// coder; 6: the kd-tree).
std::string PointCloudWithMetadata(int speed) {
  draco::PointCloud pc;
  pc.set_num_points(kPoints);
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false,
                3 * sizeof(float), 0);
  const int id = pc.AddAttribute(position, /*identity_mapping=*/true, kPoints);
  for (int i = 0; i < kPoints; ++i) {
    const float p[3] = {float(i % 11), float(i % 13), float(i % 17) + 0.25f};
    pc.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(i), p);
  }
  auto file = std::make_unique<draco::GeometryMetadata>();
  file->AddEntryString("scanner", "station 4, turntable");
  file->AddEntryDoubleArray("transform", std::vector<double>(16, 0.5));
  auto sub = std::make_unique<draco::Metadata>();
  sub->AddEntryInt("pass", 3);
  auto subsub = std::make_unique<draco::Metadata>();
  subsub->AddEntryString("operator", std::string(300, 'x'));  // a value longer than 127 bytes
  sub->AddSubMetadata("details", std::move(subsub));
  file->AddSubMetadata("session", std::move(sub));
  file->AddSubMetadata("empty", std::make_unique<draco::Metadata>());
  pc.AddMetadata(std::move(file));
  auto attribute = std::make_unique<draco::AttributeMetadata>();
  attribute->AddEntryString("units", "mm");
  pc.AddAttributeMetadata(id, std::move(attribute));
  draco::Encoder encoder;
  encoder.SetSpeedOptions(speed, speed);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  draco::EncoderBuffer buffer;
  EXPECT_TRUE(encoder.EncodePointCloudToBuffer(pc, &buffer).ok());
  return std::string(buffer.data(), buffer.size());
}

// The offset of the point count: the first place the int32 kPoints occurs (the metadata
// before it holds no such bytes; the coded points after it may).
size_t CountOffset(const std::string& bytes) {
  int32_t count = kPoints;
  const size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&count), 4));
  EXPECT_NE(at, std::string::npos);
  return at;
}

TEST(DracoHeader, MetadataWrittenByDracoIsWalkedToThePointCount) {
  for (int speed : {10, 6}) {
    const std::string bytes = PointCloudWithMetadata(speed);
    EXPECT_TRUE(CheckDracoPointCloudHeader(bytes).ok()) << CheckDracoPointCloudHeader(bytes);
    absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloud(bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_EQ(decoded->cloud.points.size(), static_cast<size_t>(kPoints));
    // The same file claiming 2^30 points is refused before Draco sees it.
    std::string lying = bytes;
    const int32_t huge = 1 << 30;
    std::memcpy(&lying[CountOffset(bytes)], &huge, 4);
    const absl::Status status = CheckDracoPointCloudHeader(lying);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << speed;
    EXPECT_THAT(status.message(), HasSubstr("declares 1073741824 points"));
    EXPECT_EQ(DecodeDracoPointCloud(lying).status().code(), absl::StatusCode::kInvalidArgument);
  }
}

TEST(DracoHeader, FuzzedCountBehindEmptyMetadataIsRefused) {
  // Found by fuzz_io_drc: 119 bytes whose metadata flag hides the count from a check of the
  // fixed offset; Draco 1.5.5 then allocated 2.4 GB for 151 million points.
  std::string bytes("DRACO\x02\x03\x00\x00\xff\xff\x00\x00\x00\x06\x00\x00\x09", 18);
  bytes += std::string(101, '\xff');
  const absl::Status status = CheckDracoPointCloudHeader(bytes);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("declares 150994950 points"));
}

TEST(DracoHeader, FuzzedAttributesOutgrowingTheCountAreRefused) {
  // Found by fuzz_io_drc: 67 bytes declaring 67080 points (within 1024 per byte) whose
  // attributes take 27 bytes each; Draco 1.5.5 then took 51 s and 19 GB to give up.
  const std::string bytes = absl::HexStringToBytes(
      "445241434f02020001000008060100020402010402010401020004030404030405020104010200040304"
      "04030403020101000901434f02000000000000020402010400");
  const absl::Status status = CheckDracoPointCloudHeader(bytes);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("67080 points of 27 bytes each"));
}

TEST(DracoHeader, MetadataEntryLargerThanTheDataIsRefused) {
  // One file entry "k" declaring 2^31 - 1 bytes of value (varint ff ff ff ff 07): Draco 1.5.5
  // would allocate them before noticing the data ends.
  std::string bytes("DRACO\x02\x02\x00\x00\x00\x80", 11);
  bytes += std::string("\x00\x01\x01k\xff\xff\xff\xff\x07", 9);
  bytes += std::string(64, '\x01');
  const absl::Status status = CheckDracoPointCloudHeader(bytes);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("metadata"));
}

TEST(DracoHeader, DataEndingBeforeTheCountIsLeftToDraco) {
  EXPECT_TRUE(CheckDracoPointCloudHeader(std::string("DRACO\x02\x02\x00\x00\x00\x00\x05", 12)).ok());
  EXPECT_TRUE(CheckDracoPointCloudHeader("DRA").ok());
}

}  // namespace
}  // namespace membrane
