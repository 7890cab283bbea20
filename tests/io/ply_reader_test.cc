// PLY reading: the three encodings, property types, and skipping what is not x/y/z.
#include <string>

#include "absl/strings/str_cat.h"
#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::BigEndianDouble;
using ::membrane::testing::BigEndianFloat;
using ::membrane::testing::LittleEndianDouble;
using ::membrane::testing::LittleEndianFloat;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

MATCHER_P3(IsPoint, x, y, z, "") { return arg == Point3f{x, y, z}; }

TEST(PlyReader, AsciiWithFacesNormalsAndColoursReadsOnlyPositions) {
  const std::string ply =
      "ply\n"
      "format ascii 1.0\n"
      "comment made by hand\n"
      "element vertex 3\n"
      "property float x\n"
      "property float y\n"
      "property float z\n"
      "property float nx\n"
      "property float ny\n"
      "property float nz\n"
      "property uchar red\n"
      "property uchar green\n"
      "property uchar blue\n"
      "element face 1\n"
      "property list uchar int vertex_indices\n"
      "end_header\n"
      "0 0 0 0 0 1 255 0 0\n"
      "1.5 0 -2e1 0 0 1 0 255 0\n"
      "+0.25 1 0 0 0 1 0 0 255\n"
      "3 0 1 2\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(IsPoint(0.f, 0.f, 0.f), IsPoint(1.5f, 0.f, -20.f),
                                         IsPoint(0.25f, 1.f, 0.f)));
}

TEST(PlyReader, BinaryLittleEndianDoublesWithExtraPropertiesBetweenCoordinates) {
  std::string ply =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "element vertex 2\n"
      "property double x\n"
      "property uchar flags\n"
      "property double y\n"
      "property list uchar float extra\n"
      "property double z\n"
      "end_header\n";
  for (int i = 0; i < 2; ++i) {
    ply += LittleEndianDouble(0.1 * (i + 1)) + std::string(1, '\x07') +
           LittleEndianDouble(-2.0 * i) + std::string(1, '\x02') + LittleEndianFloat(9.f) +
           LittleEndianFloat(8.f) + LittleEndianDouble(1e3);
  }
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(IsPoint(0.1f, 0.f, 1000.f), IsPoint(0.2f, -2.f, 1000.f)));
}

TEST(PlyReader, BinaryBigEndianFloatsAndDoubles) {
  std::string ply =
      "ply\n"
      "format binary_big_endian 1.0\n"
      "element vertex 2\n"
      "property float x\n"
      "property double y\n"
      "property float z\n"
      "property ushort intensity\n"
      "end_header\n";
  ply += BigEndianFloat(1.25f) + BigEndianDouble(-3.5) + BigEndianFloat(7.f) + "\x01\x02";
  ply += BigEndianFloat(-0.5f) + BigEndianDouble(1e-3) + BigEndianFloat(0.f) + "\x03\x04";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(IsPoint(1.25f, -3.5f, 7.f), IsPoint(-0.5f, 1e-3f, 0.f)));
}

TEST(PlyReader, FaceElementBeforeVertexElementIsSkipped) {
  std::string ply =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "element face 2\n"
      "property list uchar int vertex_indices\n"
      "property uchar material\n"
      "element vertex 3\n"
      "property float x\n"
      "property float y\n"
      "property float z\n"
      "element edge 1\n"
      "property int vertex1\n"
      "property int vertex2\n"
      "end_header\n";
  const auto int32 = [](int v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  ply += std::string(1, '\x03') + int32(0) + int32(1) + int32(2) + std::string(1, '\x09');
  ply +=
      std::string(1, '\x04') + int32(0) + int32(1) + int32(2) + int32(0) + std::string(1, '\x09');
  for (int i = 0; i < 3; ++i) {
    ply += LittleEndianFloat(i) + LittleEndianFloat(2 * i) + LittleEndianFloat(3 * i);
  }
  ply += int32(0) + int32(1);
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points,
              ElementsAre(IsPoint(0.f, 0.f, 0.f), IsPoint(1.f, 2.f, 3.f), IsPoint(2.f, 4.f, 6.f)));

  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(ply, FileFormat::kPly);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  // The quad is fan-triangulated into two triangles.
  EXPECT_EQ(mesh->faces.size(), 3u);
}

TEST(PlyReader, CrlfHeaderAndSizedTypeNamesAreAccepted) {
  std::string ply =
      "ply\r\n"
      "format binary_little_endian 1.0\r\n"
      "element vertex 1\r\n"
      "property float32 x\r\n"
      "property float32 y\r\n"
      "property float32 z\r\n"
      "end_header\r\n";
  ply += LittleEndianFloat(1) + LittleEndianFloat(2) + LittleEndianFloat(3);
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(IsPoint(1.f, 2.f, 3.f)));
}

TEST(PlyReader, MissingZPropertyIsInvalidArgument) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "end_header\n1 2\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly, "two_d.ply");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("two_d.ply"));
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("'z'"));
}

TEST(PlyReader, UnknownPropertyTypeNamesTheHeaderLine) {
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly, "q.ply");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("q.ply: line 4"));
}

TEST(PlyReader, FaceIndexOutOfRangeIsRejectedForMeshes) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(ply, FileFormat::kPly, "bad.ply");
  EXPECT_EQ(mesh.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(mesh.status().ToString(), HasSubstr("vertex index 3"));
  // As a point cloud the faces are only skipped, so the file is fine.
  EXPECT_TRUE(ReadPointCloudFromBuffer(ply, FileFormat::kPly).ok());
}

TEST(PlyReader, ZeroVerticesIsAnEmptyCloud) {
  const std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(ply, FileFormat::kPly);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_TRUE(cloud->points.empty());
}

}  // namespace
}  // namespace membrane
