// OBJ reading: "v" lines for clouds; "f" lines in all reference forms for meshes.
#include <string>

#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(ObjReader, PointCloudTakesVLinesAndIgnoresEverythingElse) {
  const std::string obj =
      "# comment\n"
      "mtllib x.mtl\n"
      "o thing\n"
      "v 1 2 3\n"
      "vn 0 0 1\n"
      "vt 0.5 0.5\n"
      "v -1 -2 -3 1.0 0.5 0.5 0.5\n"
      "f 1 2 1\n"
      "usemtl red\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(obj, FileFormat::kObj);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{1, 2, 3}, Point3f{-1, -2, -3}));
}

TEST(ObjReader, FaceReferencesWithTextureAndNormalIndicesUseTheVertexIndex) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vt 0 0\nvn 0 0 1\n"
      "f 1/1/1 2/1/1 3/1/1\n"
      "f 1//1 3//1 4//1\n"
      "f 4/1 3/1 2/1\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(obj, FileFormat::kObj);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->vertices.size(), 4u);
  using Face = std::array<int32_t, 3>;
  EXPECT_THAT(mesh->faces, ElementsAre(Face{0, 1, 2}, Face{0, 2, 3}, Face{3, 2, 1}));
}

TEST(ObjReader, PolygonsAreFanTriangulatedAndNegativeIndicesAreRelative) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\n"
      "f -5 -4 -3 -2 -1\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(obj, FileFormat::kObj);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  using Face = std::array<int32_t, 3>;
  EXPECT_THAT(mesh->faces, ElementsAre(Face{0, 1, 2}, Face{0, 2, 3}, Face{0, 3, 4}));
}

TEST(ObjReader, FaceIndexZeroIsRejectedWithLineNumber) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(obj, FileFormat::kObj, "zero.obj");
  EXPECT_EQ(mesh.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(mesh.status().ToString(), HasSubstr("zero.obj: line 4"));
}

TEST(ObjReader, FaceIndexBeyondTheVerticesIsRejected) {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(obj, FileFormat::kObj, "far.obj");
  EXPECT_EQ(mesh.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(mesh.status().ToString(), HasSubstr("refers to vertex 3"));
}

TEST(ObjReader, VLineWithTwoCoordinatesNamesLineAndByte) {
  const std::string obj = "v 0 0 0\nv 1 2\n";
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(obj, FileFormat::kObj, "short.obj");
  EXPECT_EQ(cloud.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(cloud.status().ToString(), HasSubstr("short.obj: line 2 (byte 13)"));
}

}  // namespace
}  // namespace membrane
