// Vertex normals in PLY and OBJ mesh output: read back from the bytes the writers make, unit
// length and pointing outward on a sphere, and files our readers (and others) still read.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "core/geometry/vec3.h"
#include "core/io/mesh_io.h"
#include "core/io/vertex_normals.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::CanonicalTriangles;
using ::membrane::testing::Octahedron;
using ::membrane::testing::SphereMesh;
using ::testing::HasSubstr;

// The unit sphere about the origin, counter-clockwise seen from outside.
TriangleMesh UnitSphere() { return SphereMesh(24, 48); }

// Every normal has unit length and lies within 5 degrees of the outward radius from `centre`
// (the sphere's faces are at most 7.5 degrees wide).
void ExpectUnitAndOutward(const std::vector<Point3f>& positions,
                          const std::vector<Point3f>& normals, const Vec3d& centre) {
  ASSERT_EQ(normals.size(), positions.size());
  for (size_t i = 0; i < normals.size(); ++i) {
    const Vec3d normal = ToVec3d(normals[i]);
    EXPECT_NEAR(Norm(normal), 1.0, 1e-6) << "vertex " << i;
    const Vec3d radial = Normalized(ToVec3d(positions[i]) - centre);
    EXPECT_GT(Dot(normal, radial), std::cos(5 * std::acos(-1.0) / 180)) << "vertex " << i;
  }
}

// The float nx ny nz of each vertex of a binary PLY mesh whose vertex element is x y z
// (`position_bytes` each) followed by nx ny nz.
std::vector<Point3f> PlyNormals(const std::string& ply, size_t vertices, size_t position_bytes) {
  const size_t body = ply.find("end_header\n") + std::strlen("end_header\n");
  const size_t row = 3 * position_bytes + 3 * sizeof(float);
  std::vector<Point3f> normals(vertices);
  for (size_t i = 0; i < vertices; ++i) {
    std::memcpy(normals[i].data(), ply.data() + body + i * row + 3 * position_bytes,
                3 * sizeof(float));
  }
  return normals;
}

TEST(VertexNormals, AreTheAreaWeightedMeanOfTheFaces) {
  // Octahedron vertex 0 = (1, 0, 0) touches four faces of equal area whose normals are
  // (1, +-1, +-1) / sqrt(3): their mean is +x.
  const std::vector<Point3f> normals = AreaWeightedVertexNormals(Octahedron());
  EXPECT_NEAR(normals[0][0], 1, 1e-7);
  EXPECT_NEAR(normals[0][1], 0, 1e-7);
  EXPECT_NEAR(normals[0][2], 0, 1e-7);
  // A large face counts for more than a small one: a vertex shared by a big triangle in the
  // z = 0 plane and a small one in the x = 0 plane leans to +z.
  TriangleMesh wedge;
  wedge.vertices = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 1}, {0, -1, 0}};
  wedge.faces = {{0, 1, 2}, {0, 3, 4}};
  const Vec3d leaning = ToVec3d(AreaWeightedVertexNormals(wedge)[0]);
  EXPECT_NEAR(leaning[2], 100 / std::sqrt(100.0 * 100 + 1), 1e-6);
  EXPECT_NEAR(leaning[0], 1 / std::sqrt(100.0 * 100 + 1), 1e-6);
}

TEST(VertexNormals, AVertexWithoutAreaGetsTheZeroVector) {
  TriangleMesh mesh = Octahedron();
  mesh.vertices.push_back({5, 5, 5});  // in no face
  EXPECT_EQ(AreaWeightedVertexNormals(mesh).back(), (Point3f{0, 0, 0}));
}

TEST(VertexNormals, PlyHasUnitOutwardNormalsAfterThePositions) {
  const TriangleMesh sphere = UnitSphere();
  absl::StatusOr<std::string> ply = WriteMeshToBuffer(sphere, FileFormat::kPly);
  ASSERT_TRUE(ply.ok()) << ply.status();
  EXPECT_THAT(*ply, HasSubstr("property float z\nproperty float nx\nproperty float ny\n"
                              "property float nz\nelement face"));
  ExpectUnitAndOutward(sphere.vertices, PlyNormals(*ply, sphere.vertices.size(), 4),
                       Vec3d{0, 0, 0});
  // Our reader skips the normals and gets the same mesh back.
  absl::StatusOr<TriangleMesh> back = ReadMeshFromBuffer(*ply, FileFormat::kPly);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->vertices, sphere.vertices);
  EXPECT_EQ(back->faces, sphere.faces);
}

TEST(VertexNormals, PlyWithAnOriginHasDoublePositionsAndFloatNormals) {
  TriangleMesh sphere = UnitSphere();
  sphere.origin = {500000, 4000000, 0};
  absl::StatusOr<std::string> ply = WriteMeshToBuffer(sphere, FileFormat::kPly);
  ASSERT_TRUE(ply.ok()) << ply.status();
  EXPECT_THAT(*ply, HasSubstr("property double z\nproperty float nx\n"));
  ExpectUnitAndOutward(sphere.vertices, PlyNormals(*ply, sphere.vertices.size(), 8),
                       Vec3d{0, 0, 0});
  absl::StatusOr<TriangleMesh> back = ReadMeshFromBuffer(*ply, FileFormat::kPly);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->origin, sphere.origin);
  EXPECT_EQ(back->faces, sphere.faces);
}

TEST(VertexNormals, ObjHasOneVnPerVertexAndFacesNameThem) {
  TriangleMesh sphere = UnitSphere();
  // Off the origin, so that outward is about the sphere's centre, not about 0.
  const Vec3d centre{3, -2, 7};
  for (Point3f& p : sphere.vertices) p = ToPoint3f(ToVec3d(p) + centre);
  absl::StatusOr<std::string> obj = WriteMeshToBuffer(sphere, FileFormat::kObj);
  ASSERT_TRUE(obj.ok()) << obj.status();
  std::vector<Point3f> normals;
  size_t faces = 0;
  for (absl::string_view line : absl::StrSplit(*obj, '\n')) {
    std::vector<absl::string_view> words = absl::StrSplit(line, ' ');
    if (words[0] == "vn") {
      ASSERT_EQ(words.size(), 4u) << line;
      Point3f n;
      for (int axis = 0; axis < 3; ++axis) ASSERT_TRUE(absl::SimpleAtof(words[axis + 1], &n[axis]));
      normals.push_back(n);
    } else if (words[0] == "f") {
      ASSERT_EQ(words.size(), 4u) << line;
      for (int corner = 0; corner < 3; ++corner) {
        const std::vector<absl::string_view> refs = absl::StrSplit(words[corner + 1], "//");
        ASSERT_EQ(refs.size(), 2u) << line;
        EXPECT_EQ(refs[0], refs[1]) << line;
        int64_t index = 0;
        ASSERT_TRUE(absl::SimpleAtoi(refs[0], &index));
        EXPECT_EQ(index, sphere.faces[faces][corner] + 1) << line;
      }
      ++faces;
    }
  }
  EXPECT_EQ(faces, sphere.faces.size());
  ExpectUnitAndOutward(sphere.vertices, normals, centre);
  absl::StatusOr<TriangleMesh> back = ReadMeshFromBuffer(*obj, FileFormat::kObj);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(CanonicalTriangles(*back), CanonicalTriangles(sphere));
}

}  // namespace
}  // namespace membrane
