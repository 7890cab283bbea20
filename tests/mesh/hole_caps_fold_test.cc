// Folded caps are untangled (core/mesh/hole_caps.h, untangle_rounds): a hole over the inner
// edge where a box stands on a slab, with the surface nets a shelf over the edge, as under
// spot's belly. The cap creased into the edge draws the shelf's vertices together and folds
// over itself; sent back toward the surface nets, the folded vertices would hang the cap
// toward the shelf, outside the solid.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "absl/status/statusor.h"
#include "core/mesh/hole_caps.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/smooth_surface.h"
#include "gtest/gtest.h"
#include "tests/mesh/box_cloud.h"
#include "tests/mesh/cloud_surface.h"
#include "tests/mesh/surface_expectations.h"

namespace membrane {
namespace fold_test {
namespace {

constexpr double kVoxel = 0.05;

// A slab [-2, 2] x [-0.5, 0] x [-2, 2] with a box [-1, 1] x [0, 1.5] x [-1, 1] standing on
// it; its inner edge between the box's face x = 1 and the slab's top runs along z through
// kCorner. The data miss everything within kHoleRadius (12 voxels) of kCorner.
const Vec3d kCorner{1, 0, 0};
constexpr double kHoleRadius = 0.6;
// The shelf over the edge in the surface nets' cloud: a prism, its slope from (1 + kShelf, 0)
// to (1, kShelf) across x and y, for |z| <= kShelfLength.
constexpr double kShelf = 0.6;
constexpr double kShelfLength = 0.8;

bool InBox(const Vec3d& p, const Vec3d& lo, const Vec3d& hi) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < lo[k] || p[k] > hi[k]) return false;
  return true;
}

bool InShelf(const Vec3d& p) {
  return std::abs(p[2]) <= kShelfLength && p[0] >= 1 && p[1] >= 0 &&
         (p[0] - 1) + p[1] <= kShelf;
}

// Points on the surface of the box on the slab, `keep` deciding which stay; with the shelf,
// on the surface of their union with it.
PointCloud BoxOnSlab(int per_unit_area, bool shelf,
                     const std::function<bool(const Vec3d&)>& keep) {
  const Vec3d slab_lo{-2, -0.5, -2}, slab_hi{2, 0, 2};
  const Vec3d box_lo{-1, 0, -1}, box_hi{1, 1.5, 1};
  auto outside_shelf = [&](const Vec3d& p) { return !shelf || !InShelf(p); };
  std::mt19937_64 rng(11);
  PointCloud cloud =
      testing::BoxFacePoints(slab_lo, slab_hi, per_unit_area, rng, [&](const Vec3d& p) {
        return keep(p) && outside_shelf(p) && !(p[1] >= 0 && InBox(p, box_lo, box_hi));
      });
  const PointCloud box =
      testing::BoxFacePoints(box_lo, box_hi, per_unit_area, rng, [&](const Vec3d& p) {
        return keep(p) && outside_shelf(p) && !(p[1] <= 0 && InBox(p, slab_lo, slab_hi));
      });
  cloud.points.insert(cloud.points.end(), box.points.begin(), box.points.end());
  if (!shelf) return cloud;
  std::uniform_real_distribution<double> u(0, 1);
  const int slope = static_cast<int>(per_unit_area * kShelf * std::sqrt(2.0) * 2 * kShelfLength);
  for (int i = 0; i < slope; ++i) {
    const double s = kShelf * u(rng), z = kShelfLength * (2 * u(rng) - 1);
    cloud.points.push_back(ToPoint3f(Vec3d{1 + kShelf - s, s, z}));
  }
  const int end = static_cast<int>(per_unit_area * kShelf * kShelf / 2);
  for (double z : {-kShelfLength, kShelfLength})
    for (int i = 0; i < end;) {
      const double a = kShelf * u(rng), b = kShelf * u(rng);
      if (a + b > kShelf) continue;
      cloud.points.push_back(ToPoint3f(Vec3d{1 + a, b, z}));
      ++i;
    }
  return cloud;
}

// Distance to the solid's surface near the inner edge: the slab's top (x >= 1, y = 0) and the
// box's face (x = 1, y >= 0), across the edge.
double CornerDistance(const Vec3d& p) {
  const double dx = p[0] - kCorner[0], dy = p[1] - kCorner[1];
  const double top = dx >= 0 ? std::abs(dy) : std::hypot(dx, dy);
  const double face = dy >= 0 ? std::abs(dx) : std::hypot(dx, dy);
  return std::min(top, face);
}

struct Cap {
  double mean_error = 0, max_error = 0;  // voxels, over the vertices the caps moved
  int moved = 0;
  HoleCapStats caps;
  MeshReport check;
};

TEST(HoleCapFolds, AFoldedCapIsUntangledInsteadOfSentBack) {
  SmoothSurfaceOptions surface;
  surface.fit = false;  // the surface nets, uncapped
  absl::StatusOr<testing::CloudSurface> shelved = testing::SmoothSurfaceOfCloud(
      BoxOnSlab(3000, true, [](const Vec3d&) { return true; }), surface, kVoxel);
  ASSERT_TRUE(shelved.ok()) << shelved.status();
  const PointCloud holed = BoxOnSlab(3000, false, [](const Vec3d& p) {
    return SquaredNorm(p - kCorner) >= kHoleRadius * kHoleRadius;
  });
  auto cap = [&](int untangle_rounds) {
    TriangleMesh mesh = shelved->mesh;
    HoleCapOptions options;
    options.untangle_rounds = untangle_rounds;
    Cap cap;
    EXPECT_TRUE(CapHoles(mesh, kVoxel, holed.points, options, &cap.caps).ok());
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
      const Vec3d p = ToVec3d(mesh.vertices[v]);
      if (mesh.vertices[v] == shelved->mesh.vertices[v] ||
          SquaredNorm(p - kCorner) >= kHoleRadius * kHoleRadius)
        continue;
      const double e = CornerDistance(p) / kVoxel;
      cap.max_error = std::max(cap.max_error, e);
      cap.mean_error += e;
      ++cap.moved;
    }
    if (cap.moved > 0) cap.mean_error /= cap.moved;
    cap.check = CheckMesh(mesh);
    return cap;
  };
  const Cap untangled = cap(HoleCapOptions{}.untangle_rounds);
  const Cap backed = cap(0);
  ASSERT_GT(untangled.moved, 100);
  std::printf("box on a slab, a fold of the creased cap: mean / max distance to the solid of "
              "the moved vertices, voxels: untangled %.2f / %.2f (%d untangled, %d backed off), "
              "sent back %.2f / %.2f (%d backed off)\n",
              untangled.mean_error, untangled.max_error,
              static_cast<int>(untangled.caps.untangled),
              static_cast<int>(untangled.caps.backed_off), backed.mean_error, backed.max_error,
              static_cast<int>(backed.caps.backed_off));
  EXPECT_GE(untangled.caps.creased, 1);
  EXPECT_GT(backed.caps.backed_off, 0);
  EXPECT_GT(untangled.caps.untangled, 0);
  EXPECT_EQ(untangled.caps.backed_off, 0);
  EXPECT_LT(untangled.mean_error, backed.mean_error);
  testing::ExpectValidReport(untangled.check, 1, {0});
  testing::ExpectValidReport(backed.check, 1, {0});
}

TEST(HoleCapFolds, RefusesUntangleOptionsOutOfRange) {
  TriangleMesh mesh;
  for (int case_index = 0; case_index < 3; ++case_index) {
    HoleCapOptions options;
    if (case_index == 0) options.untangle_rounds = -1;
    if (case_index == 1) options.untangle_rings = -1;
    if (case_index == 2) options.untangle_iterations = 0;
    EXPECT_EQ(CapHoles(mesh, 1.0, {}, options).code(), absl::StatusCode::kInvalidArgument)
        << case_index;
  }
}

}  // namespace
}  // namespace fold_test
}  // namespace membrane
