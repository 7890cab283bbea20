#include "tests/support/survey_cloud.h"

#include "core/engine/voxelization.h"
#include "core/io/point_cloud_io.h"
#include "gtest/gtest.h"

namespace membrane::testing {

void WriteSurveyCopy(const std::string& in, const std::string& out) {
  absl::StatusOr<PointCloud> cloud = ReadPointCloud(in);
  ASSERT_TRUE(cloud.ok()) << cloud.status();
  ASSERT_EQ(cloud->origin, (Origin3d{0, 0, 0})) << in;
  // The writer puts position + origin in the file, in double.
  cloud->origin = kSurveyOffset;
  const absl::Status written = WritePointCloud(*cloud, out);
  ASSERT_TRUE(written.ok()) << written;
}

std::array<double, 3> FileBoxCentre(const TriangleMesh& mesh) {
  absl::StatusOr<Box3d> box = CheckedBounds(mesh.vertices);
  EXPECT_TRUE(box.ok()) << box.status();
  if (!box.ok()) return {0, 0, 0};
  std::array<double, 3> centre;
  for (int k = 0; k < 3; ++k) centre[k] = (box->min[k] + box->max[k]) / 2 + mesh.origin[k];
  return centre;
}

}  // namespace membrane::testing
