// A binary PLY file read in pieces (StreamPlyPointCloud) gives the cloud the whole-file reader
// gives, and any file it does not read so is left to that reader, errors included.
#include "core/io/ply_stream.h"

#include <cstdint>
#include <string>

#include "absl/strings/str_cat.h"
#include "core/io/file_bytes.h"
#include "core/io/point_cloud_io.h"
#include "core/io/ply_reader.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"
#include "tests/support/scratch_dir.h"

namespace membrane {
namespace {

using ::membrane::testing::BigEndianDouble;
using ::membrane::testing::LittleEndianFloat;

// A binary little-endian PLY of `n` vertices (float x, an uchar between, float y, z) after an
// element of two fixed rows, and a trailing element of fixed rows: what a scanner writes,
// with elements to skip on both sides.
std::string FloatPly(int n) {
  std::string ply = absl::StrCat(
      "ply\nformat binary_little_endian 1.0\ncomment scanner\n"
      "element camera 2\nproperty double t\n"
      "element vertex ", n, "\nproperty float x\nproperty uchar quality\nproperty float y\n"
      "property float z\nelement marker 1\nproperty int id\nend_header\n");
  ply += std::string(16, '\x7f');  // the cameras
  for (int i = 0; i < n; ++i) {
    ply += LittleEndianFloat(0.001f * static_cast<float>(i));
    ply += '\x05';
    ply += LittleEndianFloat(-0.5f * static_cast<float>(i % 97));
    ply += LittleEndianFloat(static_cast<float>(i % 13) + 0.25f);
  }
  ply += std::string(4, '\0');  // the marker
  return ply;
}

// Big-endian doubles far from 0: the points are moved by a CoordinateShift.
std::string GeoreferencedPly(int n) {
  std::string ply = absl::StrCat("ply\nformat binary_big_endian 1.0\nelement vertex ", n,
                                 "\nproperty double x\nproperty double y\nproperty double z\n"
                                 "end_header\n");
  for (int i = 0; i < n; ++i) {
    ply += BigEndianDouble(500000.125 + i);
    ply += BigEndianDouble(4100000.5 - 0.25 * i);
    ply += BigEndianDouble(120.0 + 0.01 * i);
  }
  return ply;
}

class PlyStreamTest : public ::testing::Test {
 protected:
  // Writes `bytes` to a file of the scratch directory and returns its path.
  std::string Write(const std::string& name, const std::string& bytes) {
    const std::string path = dir_.File(name);
    EXPECT_TRUE(WriteFileBytes(path, bytes).ok());
    return path;
  }
  testing::ScratchDir dir_;
};

void ExpectSameCloud(const PointCloud& streamed, const PointCloud& whole) {
  ASSERT_EQ(streamed.points.size(), whole.points.size());
  for (size_t i = 0; i < whole.points.size(); ++i) {
    ASSERT_EQ(streamed.points[i], whole.points[i]) << "point " << i;
  }
  EXPECT_EQ(streamed.origin, whole.origin);
}

TEST_F(PlyStreamTest, FloatsOverSeveralPiecesAreTheWholeFilesPoints) {
  // 13 bytes a row: 4 MB pieces end mid-way through no row, and 400k rows take two pieces.
  const std::string bytes = FloatPly(400'000);
  const std::string path = Write("scan.ply", bytes);
  std::optional<PointCloud> streamed = StreamPlyPointCloud(path);
  ASSERT_TRUE(streamed.has_value());
  absl::StatusOr<PointCloud> whole = ReadPlyPointCloud(bytes, path);
  ASSERT_TRUE(whole.ok()) << whole.status();
  ExpectSameCloud(*streamed, *whole);
}

TEST_F(PlyStreamTest, DoublesFarFromZeroAreMovedAsTheWholeFileReaderMovesThem) {
  const std::string bytes = GeoreferencedPly(1000);
  const std::string path = Write("geo.ply", bytes);
  std::optional<PointCloud> streamed = StreamPlyPointCloud(path);
  ASSERT_TRUE(streamed.has_value());
  absl::StatusOr<PointCloud> whole = ReadPlyPointCloud(bytes, path);
  ASSERT_TRUE(whole.ok()) << whole.status();
  EXPECT_NE(whole->origin[0], 0.0);
  ExpectSameCloud(*streamed, *whole);
}

TEST_F(PlyStreamTest, FilesItDoesNotStreamAreLeftToTheWholeFileReader) {
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  EXPECT_FALSE(StreamPlyPointCloud(Write("ascii.ply", ascii)).has_value());
  std::string with_faces = absl::StrCat(
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n");
  for (int i = 0; i < 9; ++i) with_faces += LittleEndianFloat(static_cast<float>(i));
  with_faces += std::string("\x03\0\0\0\0\1\0\0\0\2\0\0\0", 13);
  EXPECT_FALSE(StreamPlyPointCloud(Write("faces.ply", with_faces)).has_value());
  // ...whose cloud ReadPointCloudFile reads all the same.
  absl::StatusOr<PointCloud> faces =
      ReadPointCloudFile(dir_.File("faces.ply"), FileFormat::kPly, "faces.ply");
  ASSERT_TRUE(faces.ok()) << faces.status();
  EXPECT_EQ(faces->points.size(), 3u);
  EXPECT_FALSE(StreamPlyPointCloud(dir_.File("missing.ply")).has_value());
  EXPECT_FALSE(StreamPlyPointCloud(dir_.path()).has_value());  // a directory
  EXPECT_FALSE(StreamPlyPointCloud(Write("empty.ply", "")).has_value());
}

// A truncated file gets the whole-file reader's error, naming the file and the offset.
TEST_F(PlyStreamTest, ATruncatedFileGetsTheWholeFileReadersError) {
  const std::string bytes = FloatPly(1000);
  const std::string cut = bytes.substr(0, bytes.size() - 20);
  const std::string path = Write("cut.ply", cut);
  EXPECT_FALSE(StreamPlyPointCloud(path).has_value());
  const absl::StatusOr<PointCloud> from_file =
      ReadPointCloudFile(path, FileFormat::kPly, "cut.ply");
  const absl::StatusOr<PointCloud> from_buffer =
      ReadPointCloudFromBuffer(cut, FileFormat::kPly, "cut.ply");
  EXPECT_EQ(from_file.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(from_file.status(), from_buffer.status());
}

TEST_F(PlyStreamTest, NonFinitePointsAreRefusedOrDroppedAsFromABuffer) {
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  const float values[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  for (int i = 0; i < 15; ++i) {
    ply += i == 13 ? std::string("\0\0\xc0\x7f", 4) : LittleEndianFloat(values[i]);  // a NaN
  }
  const std::string path = Write("nan.ply", ply);
  const absl::StatusOr<PointCloud> refused = ReadPointCloudFile(path, FileFormat::kPly, "nan.ply");
  EXPECT_EQ(refused.status(), ReadPointCloudFromBuffer(ply, FileFormat::kPly, "nan.ply").status());
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kInvalidArgument);
  size_t dropped = 0;
  const absl::StatusOr<PointCloud> kept =
      ReadPointCloudFile(path, FileFormat::kPly, "nan.ply", InvalidPoints::kDrop, &dropped);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_EQ(kept->points.size(), 4u);
  EXPECT_EQ(dropped, 1u);
}

}  // namespace
}  // namespace membrane
