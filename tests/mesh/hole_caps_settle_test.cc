// The back-off's crease is settled (core/mesh/hole_caps.h, settle_rounds): where every crossing
// of a cap backs off (the fold of hole_caps_fold_test.cc with no untangling), each backed-off
// vertex stops where its own crossings let it, beside neighbours still on the cap. The steps
// to the neighbours' mean that follow must smooth that crease, keep the mesh embedded and
// leave the backed-off vertices that hold points where they are.
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
namespace settle_test {
namespace {

constexpr double kVoxel = 0.05;
const Vec3d kCorner = testing::kSlabCorner;
constexpr double kHoleRadius = 0.6;
constexpr testing::Shelf kShelf{0.6, 0.8};

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
  SmoothSurfaceOptions surface;
  surface.fit = false;  // the surface nets, uncapped
  absl::StatusOr<testing::CloudSurface> shelved = testing::SmoothSurfaceOfCloud(
      testing::BoxOnSlab(3000, &kShelf, [](const Vec3d&) { return true; }), surface, kVoxel);
  ASSERT_TRUE(shelved.ok()) << shelved.status();
  const PointCloud holed = testing::BoxOnSlab(3000, nullptr, [](const Vec3d& p) {
    return SquaredNorm(p - kCorner) >= kHoleRadius * kHoleRadius;
  });
  auto cap = [&](int settle_rounds, int threads) {
    Capped c{shelved->mesh, {}};
    HoleCapOptions options;
    options.untangle_rounds = 0;  // every crossing backs off
    options.settle_rounds = settle_rounds;
    EXPECT_TRUE(CapHoles(c.mesh, kVoxel, holed.points, options, &c.caps, CancelToken::Never(),
                         threads)
                    .ok());
    return c;
  };
  const Capped ragged = cap(0, 1);
  const Capped settled = cap(HoleCapOptions{}.settle_rounds, 1);
  // The settling's searches run on the caps' threads: the same mesh on any count.
  EXPECT_EQ(cap(HoleCapOptions{}.settle_rounds, 3).mesh.vertices, settled.mesh.vertices);
  const double ragged_roughness = Roughness(ragged.mesh, shelved->mesh);
  const double settled_roughness = Roughness(settled.mesh, shelved->mesh);
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
}  // namespace settle_test
}  // namespace membrane
