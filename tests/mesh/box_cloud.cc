#include "tests/mesh/box_cloud.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/mesh/smooth_surface.h"
#include "tests/mesh/cloud_surface.h"

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

namespace {

bool InBox(const Vec3d& p, const Vec3d& lo, const Vec3d& hi) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < lo[k] || p[k] > hi[k]) return false;
  return true;
}

bool InShelf(const Vec3d& p, const Shelf& shelf) {
  return std::abs(p[2]) <= shelf.length && p[0] >= 1 && p[1] >= 0 &&
         (p[0] - 1) + p[1] <= shelf.size;
}

}  // namespace

PointCloud BoxOnSlab(int per_unit_area, const Shelf* shelf,
                     const std::function<bool(const Vec3d&)>& keep) {
  const Vec3d slab_lo{-2, -0.5, -2}, slab_hi{2, 0, 2};
  const Vec3d box_lo{-1, 0, -1}, box_hi{1, 1.5, 1};
  auto outside_shelf = [&](const Vec3d& p) { return shelf == nullptr || !InShelf(p, *shelf); };
  std::mt19937_64 rng(11);
  PointCloud cloud = BoxFacePoints(slab_lo, slab_hi, per_unit_area, rng, [&](const Vec3d& p) {
    return keep(p) && outside_shelf(p) && !(p[1] >= 0 && InBox(p, box_lo, box_hi));
  });
  const PointCloud box = BoxFacePoints(box_lo, box_hi, per_unit_area, rng, [&](const Vec3d& p) {
    return keep(p) && outside_shelf(p) && !(p[1] <= 0 && InBox(p, slab_lo, slab_hi));
  });
  cloud.points.insert(cloud.points.end(), box.points.begin(), box.points.end());
  if (shelf == nullptr) return cloud;
  std::uniform_real_distribution<double> u(0, 1);
  // The slope, then the two triangular ends.
  const double size = shelf->size, length = shelf->length;
  const int slope = static_cast<int>(per_unit_area * size * std::sqrt(2.0) * 2 * length);
  for (int i = 0; i < slope; ++i) {
    const double s = size * u(rng), z = length * (2 * u(rng) - 1);
    cloud.points.push_back(ToPoint3f(Vec3d{1 + size - s, s, z}));
  }
  const int end = static_cast<int>(per_unit_area * size * size / 2);
  for (double z : {-length, length})
    for (int i = 0; i < end;) {
      const double a = size * u(rng), b = size * u(rng);
      if (a + b > size) continue;
      cloud.points.push_back(ToPoint3f(Vec3d{1 + a, b, z}));
      ++i;
    }
  return cloud;
}

double SlabCornerDistance(const Vec3d& p) {
  const double dx = p[0] - kSlabCorner[0], dy = p[1] - kSlabCorner[1];
  const double top = dx >= 0 ? std::abs(dy) : std::hypot(dx, dy);
  const double face = dy >= 0 ? std::abs(dx) : std::hypot(dx, dy);
  return std::min(top, face);
}

absl::StatusOr<ShelvedHole> ShelvedHoleOverTheEdge(const Shelf& shelf, double hole_radius,
                                                   double voxel_size) {
  SmoothSurfaceOptions surface;
  surface.fit = false;  // the surface nets, uncapped
  absl::StatusOr<CloudSurface> shelved = SmoothSurfaceOfCloud(
      BoxOnSlab(3000, &shelf, [](const Vec3d&) { return true; }), surface, voxel_size);
  if (!shelved.ok()) return shelved.status();
  return ShelvedHole{std::move(shelved->mesh), BoxOnSlab(3000, nullptr, [&](const Vec3d& p) {
                       return SquaredNorm(p - kSlabCorner) >= hole_radius * hole_radius;
                     })};
}

}  // namespace membrane::testing
