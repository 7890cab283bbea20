#include "core/mesh/polygon_split.h"

namespace membrane {
namespace {

double CosineBetween(const Vec3d& a, const Vec3d& b) {
  const double n = Norm(a) * Norm(b);
  return n > 0 ? Dot(a, b) / n : -1.0;
}

}  // namespace

void SplitQuadFlatter(const std::array<int32_t, 4>& q, const Vec3d* p,
                      std::vector<std::array<int32_t, 3>>& triangles) {
  const Vec3d& a = p[q[0]];
  const Vec3d& b = p[q[1]];
  const Vec3d& c = p[q[2]];
  const Vec3d& d = p[q[3]];
  const double along_ac = CosineBetween(TriangleNormal(a, b, c), TriangleNormal(a, c, d));
  const double along_bd = CosineBetween(TriangleNormal(a, b, d), TriangleNormal(b, c, d));
  if (along_ac >= along_bd) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  } else {
    triangles.push_back({q[0], q[1], q[3]});
    triangles.push_back({q[1], q[2], q[3]});
  }
}

void SplitPolygonFan(const std::vector<int32_t>& polygon, int apex,
                     std::vector<std::array<int32_t, 3>>& triangles) {
  const int n = static_cast<int>(polygon.size());
  for (int k = 1; k + 1 < n; ++k)
    triangles.push_back({polygon[apex], polygon[(apex + k) % n], polygon[(apex + k + 1) % n]});
}

}  // namespace membrane
