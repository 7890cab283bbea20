// Draco codecs: option validation, lossless exactness, honest quantization error bounds,
// and what happens with meshes where point clouds are expected.
#include "core/io/draco_codec.h"

#include <cmath>
#include <limits>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/support/io_test_util.h"

namespace membrane {
namespace {

using ::membrane::testing::CanonicalTriangles;
using ::membrane::testing::MaxNearestChebyshev;
using ::membrane::testing::Octahedron;
using ::membrane::testing::SampleCloud;
using ::membrane::testing::SphereMesh;
using ::testing::HasSubstr;
using ::testing::UnorderedElementsAreArray;

TEST(DracoOptions, QuantizationBitsOutsideZeroToThirtyNameTheField) {
  for (int bits : {-1, 31}) {
    const absl::Status status = ValidateDracoOptions({.position_quantization_bits = bits});
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(status.ToString(), HasSubstr("position_quantization_bits"));
    EXPECT_THAT(status.ToString(), HasSubstr("1..30"));
  }
  EXPECT_TRUE(ValidateDracoOptions({.position_quantization_bits = 0}).ok());
  EXPECT_TRUE(ValidateDracoOptions({.position_quantization_bits = 30}).ok());
}

TEST(DracoOptions, CompressionLevelOutsideZeroToTenNamesTheField) {
  for (int level : {-1, 11}) {
    const absl::Status status = ValidateDracoOptions({.compression_level = level});
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
    EXPECT_THAT(status.ToString(), HasSubstr("compression_level"));
    EXPECT_THAT(status.ToString(), HasSubstr("0..10"));
  }
  EXPECT_FALSE(EncodeDracoPointCloud(SampleCloud(10), {.compression_level = 11}).ok());
}

TEST(DracoCodec, LosslessPointCloudDecodesToExactlyTheSamePoints) {
  const PointCloud cloud = SampleCloud(500);
  for (int level : {0, 7, 10}) {
    absl::StatusOr<DracoEncoding> encoded =
        EncodeDracoPointCloud(cloud, {.position_quantization_bits = 0, .compression_level = level});
    ASSERT_TRUE(encoded.ok()) << encoded.status();
    EXPECT_EQ(encoded->max_position_error, 0);
    absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloud(encoded->bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    EXPECT_EQ(decoded->geometry, DracoGeometry::kPointCloud);
    // Draco may reorder points (kd-tree coding); the multiset must be identical.
    EXPECT_THAT(decoded->cloud.points, UnorderedElementsAreArray(cloud.points))
        << "level " << level;
  }
}

TEST(DracoCodec, QuantizedPointCloudStaysWithinTheReportedError) {
  const PointCloud cloud = SampleCloud(400, 50.0f);
  for (int bits : {4, 8, 11, 16, 30}) {
    absl::StatusOr<DracoEncoding> encoded =
        EncodeDracoPointCloud(cloud, {.position_quantization_bits = bits, .compression_level = 7});
    ASSERT_TRUE(encoded.ok()) << encoded.status();
    // Half a grid step over the 100-unit range, plus float rounding slack.
    const double half_step = 100.0 / (std::ldexp(1.0, bits) - 1) / 2;
    EXPECT_GE(encoded->max_position_error, half_step * 0.9) << bits;
    EXPECT_LE(encoded->max_position_error, half_step * 1.1 + 1e-4) << bits;
    absl::StatusOr<DecodedDracoCloud> decoded = DecodeDracoPointCloud(encoded->bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.status();
    ASSERT_EQ(decoded->cloud.points.size(), cloud.points.size());
    EXPECT_LE(MaxNearestChebyshev(decoded->cloud.points, cloud.points), encoded->max_position_error)
        << bits << " bits";
  }
}

TEST(DracoCodec, QuantizedMeshKeepsTrianglesWithinTheReportedError) {
  const TriangleMesh mesh = SphereMesh(12, 16);
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoMesh(mesh, {.position_quantization_bits = 10});
  ASSERT_TRUE(encoded.ok()) << encoded.status();
  absl::StatusOr<TriangleMesh> decoded = DecodeDracoMesh(encoded->bytes);
  ASSERT_TRUE(decoded.ok()) << decoded.status();
  EXPECT_EQ(decoded->faces.size(), mesh.faces.size());
  EXPECT_LE(MaxNearestChebyshev(decoded->vertices, mesh.vertices), encoded->max_position_error);
  EXPECT_LE(MaxNearestChebyshev(mesh.vertices, decoded->vertices), encoded->max_position_error);
}

TEST(DracoCodec, LosslessMeshKeepsEveryTriangleAndItsOrientation) {
  for (const TriangleMesh& mesh : {Octahedron(), SphereMesh(6, 9)}) {
    for (int level : {0, 10}) {
      absl::StatusOr<DracoEncoding> encoded =
          EncodeDracoMesh(mesh, {.position_quantization_bits = 0, .compression_level = level});
      ASSERT_TRUE(encoded.ok()) << encoded.status();
      absl::StatusOr<TriangleMesh> decoded = DecodeDracoMesh(encoded->bytes);
      ASSERT_TRUE(decoded.ok()) << decoded.status();
      EXPECT_EQ(CanonicalTriangles(*decoded), CanonicalTriangles(mesh)) << "level " << level;
    }
  }
}

TEST(DracoCodec, MeshReadAsPointCloudGivesItsVerticesUnlessRejected) {
  const TriangleMesh mesh = Octahedron();
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoMesh(mesh, {.position_quantization_bits = 0});
  ASSERT_TRUE(encoded.ok()) << encoded.status();
  absl::StatusOr<DecodedDracoCloud> cloud = DecodeDracoPointCloud(encoded->bytes);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  EXPECT_EQ(cloud->geometry, DracoGeometry::kMesh);
  EXPECT_THAT(cloud->cloud.points, UnorderedElementsAreArray(mesh.vertices));

  absl::StatusOr<DecodedDracoCloud> rejected =
      DecodeDracoPointCloud(encoded->bytes, DracoMeshPolicy::kRejectMesh);
  EXPECT_EQ(rejected.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(rejected.status().ToString(), HasSubstr("holds a mesh"));
}

TEST(DracoCodec, PointCloudIsNotAMesh) {
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoPointCloud(SampleCloud(20), {});
  ASSERT_TRUE(encoded.ok()) << encoded.status();
  absl::StatusOr<TriangleMesh> mesh = DecodeDracoMesh(encoded->bytes);
  EXPECT_EQ(mesh.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(mesh.status().ToString(), HasSubstr("point cloud, not a mesh"));
}

TEST(DracoCodec, GarbageBytesAreInvalidArgument) {
  for (const std::string& bytes : {std::string(), std::string("DRACO"), std::string(64, '\xff'),
                                   std::string("DRACO\x02\x02\x01\x01\x00\x00", 11)}) {
    EXPECT_EQ(DecodeDracoPointCloud(bytes).status().code(), absl::StatusCode::kInvalidArgument);
    EXPECT_EQ(DecodeDracoMesh(bytes).status().code(), absl::StatusCode::kInvalidArgument);
  }
}

TEST(DracoCodec, EmptyOrNonFiniteInputIsNotEncoded) {
  EXPECT_EQ(EncodeDracoPointCloud(PointCloud{}, {}).status().code(),
            absl::StatusCode::kInvalidArgument);
  PointCloud bad = SampleCloud(5);
  bad.points[2][1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(EncodeDracoPointCloud(bad, {}).status().code(), absl::StatusCode::kInvalidArgument);
  TriangleMesh no_faces = Octahedron();
  no_faces.faces.clear();
  EXPECT_EQ(EncodeDracoMesh(no_faces, {}).status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace membrane
