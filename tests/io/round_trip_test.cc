// Every writer against its reader, through real files: what is written reads back.
#include <string>

#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"
#include "tests/support/scratch_dir.h"

namespace membrane {
namespace {

using ::membrane::testing::CanonicalTriangles;
using ::membrane::testing::MaxNearestChebyshev;
using ::membrane::testing::Octahedron;
using ::membrane::testing::SampleCloud;
using ::membrane::testing::ScratchDir;
using ::membrane::testing::SphereMesh;
using ::testing::ElementsAreArray;
using ::testing::UnorderedElementsAreArray;

class PointCloudRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(PointCloudRoundTrip, LosslessFormatsReadBackExactlyInOrder) {
  const ScratchDir scratch;
  const PointCloud cloud = SampleCloud(1000);
  const std::string path = scratch.File(std::string("cloud") + GetParam());
  ASSERT_TRUE(WritePointCloud(cloud, path, {.position_quantization_bits = 0}).ok());
  absl::StatusOr<PointCloud> read = ReadPointCloud(path);
  ASSERT_TRUE(read.ok()) << read.status();
  if (GetParam() == ".drc") {
    EXPECT_THAT(read->points, UnorderedElementsAreArray(cloud.points));  // kd-tree reorders
  } else {
    EXPECT_THAT(read->points, ElementsAreArray(cloud.points));
  }
}

INSTANTIATE_TEST_SUITE_P(EveryPointCloudWriter, PointCloudRoundTrip,
                         ::testing::Values(".ply", ".xyz", ".obj", ".drc", ".PLY"),
                         [](const auto& info) { return info.param.substr(1); });

TEST(PointCloudRoundTrip, QuantizedDracoFileIsWithinTheGridStep) {
  const ScratchDir scratch;
  const PointCloud cloud = SampleCloud(300, 1.0f);
  const std::string path = scratch.File("q.drc");
  ASSERT_TRUE(WritePointCloud(cloud, path, {.position_quantization_bits = 14}).ok());
  absl::StatusOr<PointCloud> read = ReadPointCloud(path);
  ASSERT_TRUE(read.ok()) << read.status();
  ASSERT_EQ(read->points.size(), cloud.points.size());
  // Range 2, 14 bits: half a step is 2 / 16383 / 2.
  EXPECT_LE(MaxNearestChebyshev(read->points, cloud.points), 2.0 / 16383 / 2 * 1.01);
}

class MeshRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshRoundTrip, TrianglesReadBackWithTheirOrientation) {
  const ScratchDir scratch;
  for (const TriangleMesh& mesh : {Octahedron(), SphereMesh(8, 12)}) {
    const std::string path = scratch.File(std::string("mesh") + GetParam());
    ASSERT_TRUE(WriteMesh(mesh, path, {.position_quantization_bits = 0}).ok());
    absl::StatusOr<TriangleMesh> read = ReadMesh(path);
    ASSERT_TRUE(read.ok()) << read.status();
    EXPECT_EQ(read->vertices.size(), mesh.vertices.size());
    EXPECT_EQ(CanonicalTriangles(*read), CanonicalTriangles(mesh));
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMeshWriter, MeshRoundTrip,
                         ::testing::Values(".ply", ".obj", ".stl", ".drc"),
                         [](const auto& info) { return info.param.substr(1); });

TEST(MeshRoundTrip, PlyAndObjKeepVertexAndFaceOrderExactly) {
  const ScratchDir scratch;
  const TriangleMesh mesh = SphereMesh(5, 7);
  for (const char* extension : {".ply", ".obj"}) {
    const std::string path = scratch.File(std::string("ordered") + extension);
    ASSERT_TRUE(WriteMesh(mesh, path).ok());
    absl::StatusOr<TriangleMesh> read = ReadMesh(path);
    ASSERT_TRUE(read.ok()) << read.status();
    EXPECT_EQ(read->vertices, mesh.vertices) << extension;
    EXPECT_EQ(read->faces, mesh.faces) << extension;
  }
}

TEST(MeshRoundTrip, WritingDanglingFaceIndicesFails) {
  const ScratchDir scratch;
  TriangleMesh mesh = Octahedron();
  mesh.faces[3][1] = 6;
  const absl::Status status = WriteMesh(mesh, scratch.File("bad.ply"));
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
}

TEST(MeshRoundTrip, PointCloudFileOfAWrittenMeshGivesItsVertices) {
  const ScratchDir scratch;
  const TriangleMesh mesh = Octahedron();
  const std::string path = scratch.File("as_cloud.ply");
  ASSERT_TRUE(WriteMesh(mesh, path).ok());
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(cloud->points, mesh.vertices);
}

}  // namespace
}  // namespace membrane
