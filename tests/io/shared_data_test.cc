// The real scans and reference meshes in ../shared/data: they read whole. Skipped when
// the directory is absent (CI).
#include "tests/support/scratch_dir.h"
#include "tests/support/shared_data.h"

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/io/mesh_io.h"
#include "core/io/point_cloud_io.h"
#include "gtest/gtest.h"

namespace membrane {
namespace {

// Reading speed is measured in tests/bench (no timed unit tests on shared machines); here,
// that every scan cloud reads whole.
TEST(SharedDataReading, EveryScanCloudReadsWithAllItsPoints) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  int clouds = 0;
  for (const auto& entry : std::filesystem::directory_iterator(data_dir + "/clouds")) {
    if (entry.path().extension() != ".ply") continue;
    ++clouds;
    absl::StatusOr<PointCloud> cloud = ReadPointCloud(entry.path().string());
    ASSERT_TRUE(cloud.ok()) << cloud.status();
    const bool scan = entry.path().stem().string().ends_with("-scan");
    EXPECT_EQ(cloud->points.size(), scan ? 150000u : 100000u) << entry.path();
  }
  EXPECT_GE(clouds, 1);
}

TEST(SharedDataReading, EveryReferenceModelReadsAsAMeshWithValidFaces) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  int models = 0;
  for (const auto& entry : std::filesystem::directory_iterator(data_dir + "/models")) {
    if (entry.path().extension() != ".obj") continue;
    ++models;
    absl::StatusOr<TriangleMesh> mesh = ReadMesh(entry.path().string());
    ASSERT_TRUE(mesh.ok()) << mesh.status();
    EXPECT_GT(mesh->faces.size(), 1000u) << entry.path();
    // ReadMesh has already checked every index against the vertex count.
  }
  EXPECT_GE(models, 1);
}

TEST(SharedDataReading, SpotModelWithSlashedFaceReferencesHasItsDocumentedFaceCount) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const std::string path = data_dir + "/models/spot.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  absl::StatusOr<TriangleMesh> mesh = ReadMesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status();
  EXPECT_EQ(mesh->faces.size(), 5856u);  // data/README.md
}

TEST(SharedDataReading, ScanSurvivesDracoRoundTripThroughAFile) {
  MEMBRANE_REQUIRE_SHARED_DATA(data_dir);
  const std::string path = data_dir + "/clouds/spot-scan.ply";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(path);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  const testing::ScratchDir scratch;
  const std::string out = scratch.File("spot_scan.drc");
  ASSERT_TRUE(WritePointCloud(*cloud, out, {.position_quantization_bits = 0}).ok());
  absl::StatusOr<PointCloud> back = ReadPointCloud(out);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->points.size(), cloud->points.size());
}

}  // namespace
}  // namespace membrane
