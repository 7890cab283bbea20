// OFF reading: the header and its counts, comments, colour columns, polygons fanned, and the
// lies a hostile file can tell (counts, indices) refused with the line that tells them.
#include <string>

#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr char kSquare[] =
    "OFF\n"
    "# a unit square as one quad\n"
    "4 1 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
    "4 0 1 2 3\n";

TEST(OffReader, PointCloudTakesTheVertices) {
  absl::StatusOr<PointCloud> cloud = ReadPointCloudFromBuffer(kSquare, FileFormat::kOff);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_THAT(cloud->points, ElementsAre(Point3f{0, 0, 0}, Point3f{1, 0, 0}, Point3f{1, 1, 0},
                                         Point3f{0, 1, 0}));
}

TEST(OffReader, PolygonsAreFanTriangulated) {
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(kSquare, FileFormat::kOff);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  ASSERT_EQ(mesh->faces.size(), 2u);
  EXPECT_EQ(mesh->faces[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh->faces[1], (std::array<int32_t, 3>{0, 2, 3}));
}

TEST(OffReader, CountsOnTheHeaderLineAndColourColumnsAreRead) {
  const std::string coff =
      "COFF 3 1 3\n"
      "0 0 0 255 0 0 255\n1 0 0 0 255 0 255  # colours after x y z\n\n0 1 0 0 0 255 255\n"
      "3 0 1 2 0.5 0.5 0.5\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(coff, FileFormat::kOff);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->vertices.size(), 3u);
  EXPECT_EQ(mesh->faces.size(), 1u);
}

TEST(OffReader, MissingKeywordNamesWhatWasFound) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer("PLY 3 0 0\n0 0 0\n", FileFormat::kOff, "x.off");
  ASSERT_FALSE(cloud.ok());
  EXPECT_TRUE(absl::IsInvalidArgument(cloud.status()));
  EXPECT_THAT(cloud.status().message(), HasSubstr("expected the keyword OFF, found 'PLY'"));
}

TEST(OffReader, CountPastWhatTheFileCanHoldIsRefusedBeforeAllocating) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer("OFF\n2000000000000 0 0\n0 0 0\n", FileFormat::kOff, "big.off");
  ASSERT_FALSE(cloud.ok());
  EXPECT_THAT(cloud.status().message(), HasSubstr("vertex count '2000000000000'"));
}

TEST(OffReader, FewerVerticesThanAnnouncedIsAnError) {
  absl::StatusOr<PointCloud> cloud =
      ReadPointCloudFromBuffer("OFF\n3 0 0\n0 0 0\n1 0 0\n", FileFormat::kOff, "short.off");
  ASSERT_FALSE(cloud.ok());
  EXPECT_THAT(cloud.status().message(),
              HasSubstr("the header announces 3 vertices but the file holds 2"));
}

TEST(OffReader, FaceIndexOutsideTheVerticesIsRefused) {
  absl::StatusOr<TriangleMesh> mesh =
      ReadMeshFromBuffer("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", FileFormat::kOff, "f.off");
  ASSERT_FALSE(mesh.ok());
  EXPECT_THAT(mesh.status().message(), HasSubstr("vertex index '7' is not in [0, 3)"));
}

TEST(OffReader, OffIsReadNotWritten) {
  EXPECT_TRUE(FormatFromPath("scan.off", FileUse::kReadPointCloud).ok());
  EXPECT_TRUE(FormatFromPath("scan.OFF", FileUse::kReadMesh).ok());
  EXPECT_FALSE(FormatFromPath("out.off", FileUse::kWriteMesh).ok());
  EXPECT_FALSE(FormatFromPath("out.off", FileUse::kWritePointCloud).ok());
}

}  // namespace
}  // namespace membrane
