#include "server/point_sample.h"

#include <algorithm>
#include <cstring>

namespace membrane::server {

std::string SamplePoints(const PointCloud& cloud, size_t max_points) {
  const size_t n = cloud.points.size();
  const size_t kept = std::min(n, max_points);
  std::string out(kept * sizeof(Point3f), '\0');
  for (size_t i = 0; i < kept; ++i) {
    // Point i of the sample is point floor(i * n / kept) of the cloud: spread over all of it.
    const Point3f& p = cloud.points[i * n / kept];
    std::memcpy(out.data() + i * sizeof(Point3f), p.data(), sizeof(Point3f));
  }
  return out;
}

absl::StatusOr<PointCloud> SamplingSource::Read(const CancelToken& cancel, ProgressRange progress) {
  absl::StatusOr<PointCloud> cloud = inner_.Read(cancel, progress);
  if (cloud.ok()) job_.SetPointSample(SamplePoints(*cloud));
  return cloud;
}

}  // namespace membrane::server
