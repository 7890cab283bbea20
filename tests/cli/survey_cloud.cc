#include "tests/cli/survey_cloud.h"

#include <algorithm>

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
  std::array<double, 3> lo, hi;
  lo.fill(1e300);
  hi.fill(-1e300);
  for (const Point3f& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], v[k] + mesh.origin[k]);
      hi[k] = std::max(hi[k], v[k] + mesh.origin[k]);
    }
  return {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
}

}  // namespace membrane::testing
