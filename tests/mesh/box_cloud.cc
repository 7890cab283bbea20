#include "tests/mesh/box_cloud.h"

namespace membrane::testing {

PointCloud BoxFacePoints(const Vec3d& lo, const Vec3d& hi, int per_unit_area,
                         std::mt19937_64& rng, const std::function<bool(const Vec3d&)>& keep) {
  std::uniform_real_distribution<double> u(0, 1);
  PointCloud cloud;
  for (int axis : {1, 0, 2})
    for (double at : {hi[axis], lo[axis]}) {
      // The face's two other axes, in the order their coordinates are drawn.
      const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
      const int n =
          static_cast<int>(per_unit_area * (hi[a1] - lo[a1]) * (hi[a2] - lo[a2]));
      for (int i = 0; i < n; ++i) {
        Vec3d p;
        p[axis] = at;
        p[a1] = lo[a1] + (hi[a1] - lo[a1]) * u(rng);
        p[a2] = lo[a2] + (hi[a2] - lo[a2]) * u(rng);
        if (keep(p)) cloud.points.push_back(ToPoint3f(p));
      }
    }
  return cloud;
}

}  // namespace membrane::testing
