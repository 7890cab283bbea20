// PCD DATA binary_compressed: files the test compresses with liblzf as PCL does (fields in
// structure-of-arrays order, padding "_" left out), and every lie a corrupt one can tell.
#include <cstdint>
#include <string>
#include <vector>

#include "core/io/pcd_compressed.h"
#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "lzf.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::LittleEndianDouble;
using ::membrane::testing::LittleEndianFloat;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string Uint32Le(uint32_t value) {
  std::string bytes(4, '\0');
  for (int i = 0; i < 4; ++i) bytes[i] = static_cast<char>(value >> (8 * i));
  return bytes;
}

// `raw` compressed with liblzf, behind PCL's two sizes.
std::string CompressedBlock(const std::string& raw) {
  std::string lzf(raw.size() + raw.size() / 16 + 64, '\0');
  const unsigned int size = lzf_compress(raw.data(), raw.size(), lzf.data(), lzf.size());
  EXPECT_GT(size, 0u);
  lzf.resize(size);
  return Uint32Le(size) + Uint32Le(raw.size()) + lzf;
}

// Three points with x y z in float32 and a colour; the body holds each field's column.
constexpr char kXyzRgbHeader[] =
    "# .PCD v0.7 - Point Cloud Data file format\n"
    "VERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
    "WIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\nDATA binary_compressed\n";

std::string XyzRgbColumns() {
  const float xs[3] = {1.5f, -2, 0.25f}, ys[3] = {10, 20, 30}, zs[3] = {-1, -1, 7};
  std::string raw;
  for (float x : xs) raw += LittleEndianFloat(x);
  for (float y : ys) raw += LittleEndianFloat(y);
  for (float z : zs) raw += LittleEndianFloat(z);
  for (int i = 0; i < 3; ++i) raw += Uint32Le(0xff00ff00u + i);
  return raw;
}

absl::StatusOr<PointCloud> Read(const std::string& pcd) {
  return ReadPointCloudFromBuffer(pcd, FileFormat::kPcd, "c.pcd");
}

TEST(PcdCompressed, ReadsTheColumnsOfEachField) {
  absl::StatusOr<PointCloud> cloud = Read(kXyzRgbHeader + CompressedBlock(XyzRgbColumns()));
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1.5f, 10, -1}, Point3f{-2, 20, -1},
                                         Point3f{0.25f, 30, 7}));
}

TEST(PcdCompressed, PaddingFieldsAreLeftOutAndDoublesAndCountsAreRead) {
  // PCL's layout for "normal(3) _ z x y": the padding field takes no bytes in the column data.
  const std::string header =
      "FIELDS normal _ z x y\nSIZE 4 1 8 8 8\nTYPE F U F F F\nCOUNT 3 5 1 1 1\n"
      "WIDTH 1\nHEIGHT 2\nDATA binary_compressed\n";
  std::string raw;
  for (int i = 0; i < 6; ++i) raw += LittleEndianFloat(0.5f);  // normals of both points
  raw += LittleEndianDouble(3) + LittleEndianDouble(6);        // z
  raw += LittleEndianDouble(1) + LittleEndianDouble(4);        // x
  raw += LittleEndianDouble(2) + LittleEndianDouble(5);        // y
  absl::StatusOr<PointCloud> cloud = Read(header + CompressedBlock(raw));
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1, 2, 3}, Point3f{4, 5, 6}));
}

TEST(PcdCompressed, ManyPointsRoundTripThroughRealCompression) {
  // Repetitive columns, so that LZF makes back references as well as literal runs.
  const std::string header =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 100\nHEIGHT 50\nDATA binary_compressed\n";
  std::string raw;
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < 5000; ++i) raw += LittleEndianFloat(static_cast<float>((i % 100) * axis));
  }
  const std::string block = CompressedBlock(raw);
  EXPECT_LT(block.size(), raw.size() / 2);
  absl::StatusOr<PointCloud> cloud = Read(header + block);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ASSERT_EQ(cloud->points.size(), 5000u);
  EXPECT_EQ(cloud->points[4321], (Point3f{0, 21, 42}));
}

// Open3D 0.16's writer, beside PCL's the other common source of binary_compressed files:
// the same 100 points (with normals and colours) saved compressed and uncompressed.
TEST(PcdCompressed, ReadsWhatOpen3dWrites) {
  const std::string dir = MEMBRANE_IO_TEST_DATA;
  absl::StatusOr<PointCloud> compressed = ReadPointCloud(dir + "/open3d_binary_compressed.pcd");
  ASSERT_TRUE(compressed.ok()) << compressed.status();
  absl::StatusOr<PointCloud> plain = ReadPointCloud(dir + "/open3d_binary.pcd");
  ASSERT_TRUE(plain.ok()) << plain.status();
  ASSERT_EQ(compressed->points.size(), 100u);
  EXPECT_EQ(compressed->points, plain->points);
}

TEST(PcdCompressed, AnEmptyCloudIsRead) {
  const std::string pcd =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 0\nDATA binary_compressed\n" + Uint32Le(0) +
      Uint32Le(0);
  absl::StatusOr<PointCloud> cloud = Read(pcd);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_TRUE(cloud->points.empty());
}

void ExpectInvalid(const std::string& pcd, const std::string& message) {
  absl::StatusOr<PointCloud> cloud = Read(pcd);
  ASSERT_FALSE(cloud.ok());
  EXPECT_TRUE(absl::IsInvalidArgument(cloud.status())) << cloud.status();
  EXPECT_THAT(cloud.status().message(), HasSubstr(message));
  EXPECT_THAT(cloud.status().message(), HasSubstr("c.pcd: at byte "));
}

TEST(PcdCompressed, MissingSizeHeaderIsRefused) {
  ExpectInvalid(std::string(kXyzRgbHeader) + "\x10\0\0", "needs an 8-byte size header");
}

TEST(PcdCompressed, CompressedSizePastTheFileIsRefused) {
  std::string block = CompressedBlock(XyzRgbColumns());
  block.resize(block.size() - 1);
  ExpectInvalid(kXyzRgbHeader + block, "only " + std::to_string(block.size() - 8) + " follow");
}

TEST(PcdCompressed, UncompressedSizeThatDisagreesWithPointsIsRefused) {
  const std::string raw = XyzRgbColumns();
  ExpectInvalid(kXyzRgbHeader + CompressedBlock(raw + raw),
                "declares 96 uncompressed bytes, but POINTS 3 x 16 bytes per point");
}

TEST(PcdCompressed, PointsTooManyForA32BitSizeAreRefusedBeforeAllocating) {
  const std::string pcd =
      "FIELDS x y z\nSIZE 8 8 8\nTYPE F F F\nPOINTS 200000000000\nDATA binary_compressed\n" +
      Uint32Le(2) + Uint32Le(0xffffffffu) + std::string(2, '\0');
  ExpectInvalid(pcd, "more than a 32-bit size can hold");
}

TEST(PcdCompressed, ExpansionBeyondWhatLzfCanDoIsRefusedBeforeAllocating) {
  // 4 GB - 4 from 2 bytes: 1431655764 points of 12 bytes is what POINTS must say to match.
  const std::string pcd =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 357913941\nDATA binary_compressed\n" +
      Uint32Le(2) + Uint32Le(357913941u * 12) + std::string(2, '\0');
  ExpectInvalid(pcd, "more than LZF can expand to");
}

TEST(PcdCompressed, CorruptLzfDataIsRefused) {
  // A back reference (length 7+, offset 0x100) as the first token: before the output starts.
  ExpectInvalid(kXyzRgbHeader + Uint32Le(3) + Uint32Le(48) + std::string("\xe1\x00\x01", 3),
                "the LZF data is corrupt");
}

TEST(PcdCompressed, LzfDataLongerOrShorterThanDeclaredIsRefused) {
  const std::string raw = XyzRgbColumns();
  std::string longer = CompressedBlock(raw + "\x01\x02\x03\x04");
  // Keep the LZF data of 52 bytes but declare 48.
  longer.replace(4, 4, Uint32Le(48));
  ExpectInvalid(kXyzRgbHeader + longer, "decompresses to more than the 48 bytes");
  std::string shorter = CompressedBlock(raw.substr(0, 44));
  shorter.replace(4, 4, Uint32Le(48));
  ExpectInvalid(kXyzRgbHeader + shorter, "decompresses to 44 bytes, not the 48");
}

TEST(PcdCompressed, EveryTruncationAndByteOverwriteGivesAStatus) {
  const std::string good = kXyzRgbHeader + CompressedBlock(XyzRgbColumns());
  const size_t body = std::string(kXyzRgbHeader).size();
  for (size_t size = body; size < good.size(); ++size) {
    EXPECT_FALSE(Read(good.substr(0, size)).ok()) << size;
  }
  for (size_t i = body; i < good.size(); ++i) {
    for (int value : {0x00, 0x1f, 0x20, 0xe0, 0xff}) {
      std::string bad = good;
      bad[i] = static_cast<char>(value);
      absl::StatusOr<PointCloud> cloud = Read(bad);
      if (!cloud.ok()) {
        EXPECT_TRUE(absl::IsInvalidArgument(cloud.status())) << cloud.status();
      }
    }
  }
}

}  // namespace
}  // namespace membrane
