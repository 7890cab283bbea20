// Folded caps are untangled (core/mesh/hole_caps.h, untangle_rounds): a hole over the inner
// edge where a box stands on a slab, with the surface nets a shelf over the edge, as under
// spot's belly. The cap creased into the edge draws the shelf's vertices together and folds
// over itself; sent back toward the surface nets, the folded vertices would hang the cap
// toward the shelf, outside the solid.
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
namespace fold_test {
namespace {

constexpr double kVoxel = 0.05;

// The box on the slab (testing::BoxOnSlab); the data miss everything within kHoleRadius
// (12 voxels) of its inner edge's point kCorner.
const Vec3d kCorner = testing::kSlabCorner;
constexpr double kHoleRadius = 0.6;
// The shelf over the edge in the surface nets' cloud.
constexpr testing::Shelf kShelf{0.6, 0.8};

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
      testing::BoxOnSlab(3000, &kShelf, [](const Vec3d&) { return true; }), surface, kVoxel);
  ASSERT_TRUE(shelved.ok()) << shelved.status();
  const PointCloud holed = testing::BoxOnSlab(3000, nullptr, [](const Vec3d& p) {
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
      const double e = testing::SlabCornerDistance(p) / kVoxel;
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
