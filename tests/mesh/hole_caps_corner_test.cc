// The caps' crease at a concave corner (core/mesh/hole_caps.h, corner_angle): a hole over the
// inner edge where a box stands on a slab, with the membrane left as a shelf over the edge
// (its plates could not enter the corner), is capped close to the edge, where a smooth cap
// from the rim spans it as a fillet outside it.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "absl/status/statusor.h"
#include "core/mesh/hole_caps.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/smooth_surface.h"
#include "gtest/gtest.h"
#include "tests/mesh/box_cloud.h"
#include "tests/mesh/cloud_surface.h"
#include "tests/mesh/surface_expectations.h"

namespace membrane {
namespace corner_test {
namespace {

constexpr double kVoxel = 0.05;

// The box on the slab (testing::BoxOnSlab); the data miss everything within kHoleRadius
// (12 voxels) of its inner edge's point kCorner.
const Vec3d kCorner = testing::kSlabCorner;
constexpr double kHoleRadius = 0.6;
// The shelf over the edge in the surface nets' cloud (the membrane left outside the corner).
constexpr testing::Shelf kShelf{0.5, 0.7};

struct Corner {
  double max_error = 0, mean_error = 0;  // voxels, over the vertices within 0.8 hole radii
  int vertices = 0;
  HoleCapStats caps;
  MeshReport check;
};

// The caps over the shelf's surface nets, given the cloud with the hole.
Corner Cap(const TriangleMesh& nets, const PointCloud& holed, double corner_angle) {
  TriangleMesh mesh = nets;
  HoleCapOptions options;
  options.corner_angle = corner_angle;
  Corner corner;
  EXPECT_TRUE(CapHoles(mesh, kVoxel, holed.points, options, &corner.caps).ok());
  for (const Point3f& q : mesh.vertices) {
    const Vec3d p = ToVec3d(q);
    if (SquaredNorm(p - kCorner) >= 0.64 * kHoleRadius * kHoleRadius) continue;
    const double e = testing::SlabCornerDistance(p) / kVoxel;
    corner.max_error = std::max(corner.max_error, e);
    corner.mean_error += e;
    ++corner.vertices;
  }
  if (corner.vertices > 0) corner.mean_error /= corner.vertices;
  corner.check = CheckMesh(mesh);
  return corner;
}

TEST(HoleCapCorners, HoleOverAConcaveEdgeUnderAShelfIsCappedAlongBothFaces) {
  absl::StatusOr<testing::ShelvedHole> shelved =
      testing::ShelvedHoleOverTheEdge(kShelf, kHoleRadius, kVoxel);
  ASSERT_TRUE(shelved.ok()) << shelved.status();
  const PointCloud& holed = shelved->holed;
  const Corner creased = Cap(shelved->nets, holed, HoleCapOptions{}.corner_angle);
  const Corner fillet = Cap(shelved->nets, holed, 181.0);
  ASSERT_GT(creased.vertices, 100);
  std::printf("box on a slab, its inner edge under a shelf: mean / max distance to the solid, "
              "voxels: creased %.2f / %.2f (%d caps creased, %d vertices), the smooth cap "
              "%.2f / %.2f\n",
              creased.mean_error, creased.max_error, static_cast<int>(creased.caps.creased),
              static_cast<int>(creased.caps.creased_vertices), fillet.mean_error,
              fillet.max_error);
  // Measured: 0.96 / 1.63 voxels creased (one cap, 210 vertices moved), 1.36 / 2.87 the
  // smooth cap (a fillet across the edge).
  EXPECT_GE(creased.caps.creased, 1);
  EXPECT_LT(creased.max_error, 2.0);
  EXPECT_EQ(fillet.caps.creased, 0);
  EXPECT_LT(creased.max_error, 0.6 * fillet.max_error);
  EXPECT_LT(creased.mean_error, fillet.mean_error);
  testing::ExpectValidReport(creased.check, 1, {0});
  testing::ExpectValidReport(fillet.check, 1, {0});
}

}  // namespace
}  // namespace corner_test
}  // namespace membrane
