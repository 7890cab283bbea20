// Uploads in Draco parts (UploadHeader.upload_part_bytes): the job's mesh is the one-part
// upload's, bad part tables and bad parts end the call or the job INVALID_ARGUMENT naming the
// part, and the server keeps serving after each.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/draco_codec.h"
#include "core/io/draco_parts.h"
#include "core/synth/synthesize.h"
#include "tests/server/service_fixture.h"
#include "tests/support/shared_data.h"

namespace membrane::testing {
namespace {

// 14-bit positions on one box around the synthetic shapes (inside [-1.5, 1.5]).
DracoOptions OnOneBox() {
  return {.position_quantization_bits = 14,
          .compression_level = 7,
          .box = PositionBox{{-1.5f, -1.5f, -1.5f}, 3.0f}};
}

std::vector<Point3f> Shape(const std::string& shape, int points) {
  SynthOptions synth;
  synth.shape = shape;
  synth.points = points;
  absl::StatusOr<PointCloud> cloud = SynthesizeShape(synth);
  EXPECT_TRUE(cloud.ok()) << cloud.status();
  return cloud.ok() ? cloud->points : std::vector<Point3f>();
}

class UploadPartsTest : public ServiceTest {
 protected:
  void SetUp() override { StartServer(); }

  // Uploads `points` encoded with `options` as one Draco cloud without a part table (the
  // old-style upload), then in `parts` parts; expects both jobs to succeed with one mesh.
  void ExpectTheMeshOfOnePart(const std::vector<Point3f>& points, const DracoOptions& options,
                              int parts) {
    absl::StatusOr<DracoEncoding> one = EncodeDracoPointCloud(PointCloud{points}, options);
    ASSERT_TRUE(one.ok()) << one.status();
    absl::StatusOr<DracoParts> in_parts = EncodeDracoPointCloudParts(points, options, parts, 2);
    ASSERT_TRUE(in_parts.ok()) << in_parts.status();
    ASSERT_EQ(in_parts->part_bytes.size(), static_cast<size_t>(parts));
    const CallResult as_one = Reconstruct(one->bytes, {});
    ASSERT_TRUE(as_one.status.ok()) << as_one.status.error_message();
    UploadTweaks tweaks;
    tweaks.part_bytes = in_parts->part_bytes;
    const CallResult as_parts = Reconstruct(in_parts->bytes, {}, tweaks);
    ASSERT_TRUE(as_parts.status.ok()) << as_parts.status.error_message();
    EXPECT_FALSE(as_one.Mesh().empty());
    EXPECT_EQ(as_parts.Mesh(), as_one.Mesh())
        << parts << " parts, bits " << options.position_quantization_bits;
  }

  // Uploads `bytes` in parts of `part_bytes`; expects the call (or the job) to end with
  // INVALID_ARGUMENT, its message holding every one of `words`; then that the server serves.
  void ExpectInvalid(const std::string& bytes, std::vector<uint64_t> part_bytes,
                     const std::vector<std::string>& words) {
    UploadTweaks tweaks;
    tweaks.part_bytes = std::move(part_bytes);
    const CallResult r = Reconstruct(bytes, {}, tweaks, 30);
    EXPECT_EQ(r.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT)
        << r.status.error_message();
    for (const std::string& w : words) {
      EXPECT_NE(r.status.error_message().find(w), std::string::npos) << r.status.error_message();
    }
    EXPECT_EQ(Health(), "SERVING");
    EXPECT_TRUE(Reconstruct(DracoCloud("sphere", 1000), {}).status.ok()) << "server broken";
  }
};

TEST_F(UploadPartsTest, PartsGiveTheMeshOfOnePart) {
  const std::vector<Point3f> torus = Shape("torus", 30000);
  ExpectTheMeshOfOnePart(torus, OnOneBox(), 4);
  ExpectTheMeshOfOnePart(torus, {.position_quantization_bits = 0}, 4);
}

TEST_F(UploadPartsTest, AScanInPartsGivesTheMeshOfOnePart) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  absl::StatusOr<PointCloud> scan = ReadSharedCloud(data_dir, "stanford-bunny-scan");
  ASSERT_TRUE(scan.ok()) << scan.status();
  // The client's way: the positions on one grid over the cloud, 14 bits.
  DracoOptions options;
  options.position_quantization_bits = 14;
  options.box = BoundingGrid(scan->points, 14).box;
  ExpectTheMeshOfOnePart(scan->points, options, 3);
}

TEST_F(UploadPartsTest, SizesThatDoNotSumToTheUploadAreRefused) {
  const std::string cloud = DracoCloud("sphere", 2000);
  ExpectInvalid(cloud, {cloud.size() - 10}, {"sum to", "not the upload's"});
  ExpectInvalid(cloud, {cloud.size() - 10, 20}, {"at part 2 of 2"});
  ExpectInvalid(cloud, {cloud.size(), 0}, {"part 2 of 2 is empty"});
}

TEST_F(UploadPartsTest, TooManyPartsAreRefused) {
  const std::string cloud = DracoCloud("sphere", 2000);
  std::vector<uint64_t> sizes(kMaxDracoParts + 1, 1);
  sizes.back() = cloud.size() - kMaxDracoParts;
  ExpectInvalid(cloud, sizes, {"65 parts, over the limit of 64"});
}

TEST_F(UploadPartsTest, APartThatIsNotDracoIsNamed) {
  const std::string cloud = DracoCloud("sphere", 2000);
  ExpectInvalid(cloud + std::string(300, 'x'), {cloud.size(), 300},
                {"the upload could not be decoded", "part 2 of 2", "not valid Draco data"});
}

TEST_F(UploadPartsTest, AMeshPartIsNamed) {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  absl::StatusOr<DracoEncoding> encoded = EncodeDracoMesh(mesh, DracoOptions{});
  ASSERT_TRUE(encoded.ok());
  const std::string cloud = DracoCloud("sphere", 2000);
  ExpectInvalid(cloud + encoded->bytes, {cloud.size(), encoded->bytes.size()},
                {"part 2 of 2", "mesh"});
}

TEST_F(UploadPartsTest, PartsWithOtherQuantizationsAreStillOneCloud) {
  // The contract leaves quantization to the client: parts on their own boxes are accepted
  // (their points are where each part's grid puts them).
  const std::vector<Point3f> points = Shape("sphere", 4000);
  const size_t half = points.size() / 2;
  absl::StatusOr<DracoEncoding> a = EncodeDracoPointCloud(
      PointCloud{std::vector<Point3f>(points.begin(), points.begin() + half)}, {});
  absl::StatusOr<DracoEncoding> b = EncodeDracoPointCloud(
      PointCloud{std::vector<Point3f>(points.begin() + half, points.end())}, {});
  ASSERT_TRUE(a.ok() && b.ok());
  UploadTweaks tweaks;
  tweaks.part_bytes = {a->bytes.size(), b->bytes.size()};
  const CallResult r = Reconstruct(a->bytes + b->bytes, {}, tweaks);
  EXPECT_TRUE(r.status.ok()) << r.status.error_message();
}

}  // namespace
}  // namespace membrane::testing
