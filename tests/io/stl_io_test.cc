// STL: binary writing and reading with shared vertices restored, ascii reading.
#include <string>

#include "core/io/mesh_io.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::CanonicalTriangles;
using ::membrane::testing::Octahedron;
using ::testing::HasSubstr;

TEST(StlIo, BinaryRoundTripWeldsCornersBackIntoSharedVertices) {
  const TriangleMesh mesh = Octahedron();
  absl::StatusOr<std::string> bytes = WriteMeshToBuffer(mesh, FileFormat::kStl);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  EXPECT_EQ(bytes->size(), 84u + 50u * mesh.faces.size());
  EXPECT_NE(bytes->substr(0, 5), "solid");
  absl::StatusOr<TriangleMesh> read = ReadMeshFromBuffer(*bytes, FileFormat::kStl);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->vertices.size(), mesh.vertices.size());
  EXPECT_EQ(CanonicalTriangles(*read), CanonicalTriangles(mesh));
}

TEST(StlIo, AsciiSolidIsRead) {
  const std::string stl =
      "solid tri\n"
      " facet normal 0 0 1\n"
      "  outer loop\n"
      "   vertex 0 0 0\n"
      "   vertex 1 0 0\n"
      "   vertex 0 1 0\n"
      "  endloop\n"
      " endfacet\n"
      " facet normal 0 0 1\n"
      "  outer loop\n"
      "   vertex 1 0 0\n"
      "   vertex 1 1 0\n"
      "   vertex 0 1 0\n"
      "  endloop\n"
      " endfacet\n"
      "endsolid tri\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(stl, FileFormat::kStl);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->vertices.size(), 4u);
  EXPECT_EQ(mesh->faces.size(), 2u);
}

TEST(StlIo, TruncatedBinaryNamesByteOffset) {
  absl::StatusOr<std::string> bytes = WriteMeshToBuffer(Octahedron(), FileFormat::kStl);
  ASSERT_TRUE(bytes.ok());
  bytes->resize(84 + 50 * 3 + 20);
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(*bytes, FileFormat::kStl, "cut.stl");
  EXPECT_EQ(mesh.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(mesh.status().ToString(),
              HasSubstr("cut.stl: at byte 234: the data ends inside triangle 3 of 8"));
}

TEST(StlIo, AsciiWithoutEndsolidIsInvalidArgument) {
  const std::string stl = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
  absl::StatusOr<TriangleMesh> mesh = ReadMeshFromBuffer(stl, FileFormat::kStl, "open.stl");
  EXPECT_EQ(mesh.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(mesh.status().ToString(), HasSubstr("endsolid"));
}

}  // namespace
}  // namespace membrane
