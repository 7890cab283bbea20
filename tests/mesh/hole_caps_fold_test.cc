// Folded caps are untangled (core/mesh/hole_caps.h, untangle_rounds): a hole over the inner
// edge where a box stands on a slab, with the surface nets a shelf over the edge, as under
// spot's belly. The cap creased into the edge draws the shelf's vertices together and folds
// over itself; sent back toward the surface nets, the folded vertices would hang the cap
// toward the shelf, outside the solid. With no untangling every crossing backs off, and each
// backed-off vertex stops where its own crossings let it, beside neighbours still on the cap:
// the steps to the neighbours' mean that follow (settle_rounds) must smooth that crease, keep
// the mesh embedded and leave the backed-off vertices that hold points where they are.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
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
  absl::StatusOr<testing::ShelvedHole> shelved =
      testing::ShelvedHoleOverTheEdge(kShelf, kHoleRadius, kVoxel);
  ASSERT_TRUE(shelved.ok()) << shelved.status();
  const PointCloud& holed = shelved->holed;
  auto cap = [&](int untangle_rounds) {
    TriangleMesh mesh = shelved->nets;
    HoleCapOptions options;
    options.untangle_rounds = untangle_rounds;
    Cap cap;
    EXPECT_TRUE(CapHoles(mesh, kVoxel, holed.points, options, &cap.caps).ok());
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
      const Vec3d p = ToVec3d(mesh.vertices[v]);
      if (mesh.vertices[v] == shelved->nets.vertices[v] ||
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

struct Capped {
  TriangleMesh mesh;
  HoleCapStats caps;
};

// Mean distance, in voxels, of the vertices the caps moved from their neighbours' mean: a
// ragged crease has vertices far from it, a smooth cap none.
double Roughness(const TriangleMesh& mesh, const TriangleMesh& nets) {
  std::vector<std::vector<int32_t>> nb(mesh.vertices.size());
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      nb[f[k]].push_back(f[(k + 1) % 3]);
      nb[f[(k + 1) % 3]].push_back(f[k]);
    }
  double sum = 0;
  int count = 0;
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (mesh.vertices[v] == nets.vertices[v]) continue;
    std::sort(nb[v].begin(), nb[v].end());
    nb[v].erase(std::unique(nb[v].begin(), nb[v].end()), nb[v].end());
    Vec3d mean{0, 0, 0};
    for (int32_t u : nb[v]) mean = mean + ToVec3d(mesh.vertices[u]);
    mean = (1.0 / nb[v].size()) * mean;
    sum += std::sqrt(SquaredNorm(ToVec3d(mesh.vertices[v]) - mean)) / kVoxel;
    ++count;
  }
  return count > 0 ? sum / count : 0;
}

TEST(HoleCapSettle, TheBackOffsCreaseIsSmoothedWhereNoPointsAreHeld) {
  absl::StatusOr<testing::ShelvedHole> shelved =
      testing::ShelvedHoleOverTheEdge(kShelf, kHoleRadius, kVoxel);
  ASSERT_TRUE(shelved.ok()) << shelved.status();
  const PointCloud& holed = shelved->holed;
  auto cap = [&](int settle_rounds, int threads,
                 int64_t split = HoleCapOptions{}.split_solve_vertices) {
    Capped c{shelved->nets, {}};
    HoleCapOptions options;
    options.untangle_rounds = 0;  // every crossing backs off
    options.settle_rounds = settle_rounds;
    options.split_solve_vertices = split;
    EXPECT_TRUE(CapHoles(c.mesh, kVoxel, holed.points, options, &c.caps, CancelToken::Never(),
                         threads)
                    .ok());
    return c;
  };
  const Capped ragged = cap(0, 1);
  const Capped settled = cap(HoleCapOptions{}.settle_rounds, 1);
  // The settling's searches run on the caps' threads: the same mesh on any count, with every
  // solve split into ranges too.
  EXPECT_EQ(cap(HoleCapOptions{}.settle_rounds, 3).mesh.vertices, settled.mesh.vertices);
  EXPECT_EQ(cap(HoleCapOptions{}.settle_rounds, 3, 1).mesh.vertices, settled.mesh.vertices);
  const double ragged_roughness = Roughness(ragged.mesh, shelved->nets);
  const double settled_roughness = Roughness(settled.mesh, shelved->nets);
  std::printf("box on a slab, every crossing backed off (%d vertices): roughness of the moved "
              "vertices %.3f voxel, settled %.3f (%d vertices moved on)\n",
              static_cast<int>(settled.caps.backed_off), ragged_roughness, settled_roughness,
              static_cast<int>(settled.caps.settled));
  ASSERT_GT(ragged.caps.backed_off, 100);
  EXPECT_EQ(ragged.caps.settled, 0);
  EXPECT_EQ(settled.caps.backed_off, ragged.caps.backed_off);
  EXPECT_GT(settled.caps.settled, settled.caps.backed_off / 4);
  EXPECT_LE(settled.caps.settled, settled.caps.backed_off);
  EXPECT_LT(settled_roughness, 0.8 * ragged_roughness);
  // A backed-off vertex with points within the gap radius holds the surface to them: it stays.
  const double near = HoleCapOptions{}.gap_radius * kVoxel;
  int moved = 0;
  for (size_t v = 0; v < settled.mesh.vertices.size(); ++v) {
    if (settled.mesh.vertices[v] == ragged.mesh.vertices[v]) continue;
    ++moved;
    for (const Point3f& p : holed.points)
      ASSERT_GT(SquaredNorm(ToVec3d(p) - ToVec3d(ragged.mesh.vertices[v])), near * near) << v;
  }
  EXPECT_EQ(moved, settled.caps.settled);
  testing::ExpectValidReport(CheckMesh(ragged.mesh), 1, {0});
  testing::ExpectValidReport(CheckMesh(settled.mesh), 1, {0});
}

TEST(HoleCapSettle, RefusesSettleOptionsOutOfRange) {
  TriangleMesh mesh;
  for (int case_index = 0; case_index < 4; ++case_index) {
    HoleCapOptions options;
    if (case_index == 0) options.settle_rounds = -1;
    if (case_index == 1) options.settle_rounds = 1001;
    if (case_index == 2) options.settle_min_step = -0.1;
    if (case_index == 3) options.settle_min_step = std::nan("");
    const absl::Status status = CapHoles(mesh, 1.0, {}, options);
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << case_index;
    EXPECT_NE(status.message().find("settle_"), std::string::npos) << status.message();
  }
}

}  // namespace
}  // namespace fold_test
}  // namespace membrane
