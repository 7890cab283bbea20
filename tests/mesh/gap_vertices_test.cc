// The hole caps' gap search (core/mesh/gap_vertices.h) and the caps built on it: the same
// flags, counts, remote points and caps on any thread count, and on a dense cloud.
#include "core/mesh/gap_vertices.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/mesh/hole_caps.h"
#include "core/mesh/point_row_grid.h"
#include "core/mesh/smooth_surface.h"
#include "gtest/gtest.h"
#include "tests/mesh/cloud_surface.h"
#include "tests/support/shrink_fixture.h"

namespace membrane {
namespace {

// Points uniformly on the unit sphere but none within 0.5 of the pole (0, 0, 1), and `buried`
// points on a sphere of radius 0.3 inside it: no membrane vertex comes near those.
PointCloud SphereWithHoleAndBuriedPoints(int n, int buried) {
  PointCloud cloud = testing::SphereWithHole(n, 0.5, 5);
  std::mt19937_64 rng(6);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < buried; ++i)
    cloud.points.push_back(
        ToPoint3f(0.3 * Normalized(Vec3d{gauss(rng), gauss(rng), gauss(rng)})));
  return cloud;
}

struct NetsOfCloud {
  TriangleMesh mesh;
  double voxel_size = 0;
};

// The surface nets of the cloud's membrane (no caps, no fit): a crater sunk into the hole.
NetsOfCloud Nets(const PointCloud& cloud) {
  NetsOfCloud out;
  auto run = testing::ShrinkCloud(cloud, 1.0);
  EXPECT_TRUE(run.ok()) << run.status();
  if (!run.ok()) return out;
  SmoothSurfaceOptions options;
  options.fit = false;
  absl::StatusOr<TriangleMesh> mesh = SmoothSurface(run->voxels.grid, cloud.points, options);
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  if (mesh.ok()) out.mesh = *std::move(mesh);
  out.voxel_size = run->voxels.grid.voxel_size();
  return out;
}

TEST(GapVertices, TheSameOnAnyThreadCount) {
  const PointCloud cloud = SphereWithHoleAndBuriedPoints(20000, 300);
  const NetsOfCloud nets = Nets(cloud);
  // Several blocks of vertices, so that the threads share them.
  ASSERT_GT(nets.mesh.vertices.size(), 12000u);
  const double radius = 2 * nets.voxel_size;
  absl::StatusOr<GapVertices> one =
      FindGapVertices(nets.mesh, cloud.points, radius, 5, true, 1, 1, CancelToken::Never());
  ASSERT_TRUE(one.ok()) << one.status();
  // The crater's vertices are gaps, and the buried points are remote.
  EXPECT_GT(one->count, 100);
  EXPECT_GE(one->remote.size(), 300u);
  int64_t counted = one->count;
  for (const int64_t h : one->histogram) counted += h;
  EXPECT_EQ(counted, static_cast<int64_t>(nets.mesh.vertices.size()));
  // Fewer gaps than the caller's minimum: no remote points are listed.
  absl::StatusOr<GapVertices> few = FindGapVertices(nets.mesh, cloud.points, radius, 5, true,
                                                    one->count + 1, 2, CancelToken::Never());
  ASSERT_TRUE(few.ok()) << few.status();
  EXPECT_EQ(few->gap, one->gap);
  EXPECT_TRUE(few->remote.empty());
  for (const int threads : {2, 3}) {
    absl::StatusOr<GapVertices> many =
        FindGapVertices(nets.mesh, cloud.points, radius, 5, true, 1, threads, CancelToken::Never());
    ASSERT_TRUE(many.ok()) << many.status();
    EXPECT_EQ(many->gap, one->gap) << threads;
    EXPECT_EQ(many->count, one->count) << threads;
    EXPECT_EQ(many->histogram, one->histogram) << threads;
    EXPECT_EQ(many->remote, one->remote) << threads;
  }
}

TEST(GapVertices, ADenseCloudGivesWhatEveryPointAgainstEveryBallGives) {
  // Ten times the points the membrane was made from (16 a vertex): the search skips the
  // points a vertex need not read (its count past the last bin, points already covered), so
  // it is held against a count of every point in every vertex's ball.
  const NetsOfCloud nets = Nets(SphereWithHoleAndBuriedPoints(20000, 300));
  const PointCloud dense = SphereWithHoleAndBuriedPoints(200000, 3000);
  const double radius = 2 * nets.voxel_size;
  const int last_bin = 6;
  const PointRowGrid grid(dense.points, radius);
  std::vector<char> covered(grid.num_points(), 0), gap;
  std::vector<int64_t> histogram(last_bin + 1, 0);
  int64_t count = 0;
  for (const Point3f& v : nets.mesh.vertices) {
    int near = 0;
    const Vec3d c = ToVec3d(v);
    grid.ForEachRun(c, radius, [&](uint32_t begin, uint32_t end) {
      for (uint32_t i = begin; i < end; ++i) {
        const double dx = grid.xs()[i] - c[0], dy = grid.ys()[i] - c[1],
                     dz = grid.zs()[i] - c[2];
        if (dx * dx + dy * dy + dz * dz <= radius * radius) {
          ++near;
          covered[i] = 1;
        }
      }
    });
    gap.push_back(near == 0);
    count += near == 0;
    if (near > 0) ++histogram[std::min(near, last_bin)];
  }
  std::vector<Point3f> remote;
  for (size_t i = 0; i < grid.num_points(); ++i)
    if (!covered[i]) remote.push_back({grid.xs()[i], grid.ys()[i], grid.zs()[i]});
  EXPECT_GE(remote.size(), 3000u);
  for (const int threads : {1, 3}) {
    absl::StatusOr<GapVertices> found = FindGapVertices(nets.mesh, dense.points, radius, last_bin,
                                                        true, 1, threads, CancelToken::Never());
    ASSERT_TRUE(found.ok()) << found.status();
    EXPECT_EQ(found->gap, gap) << threads;
    EXPECT_EQ(found->count, count) << threads;
    EXPECT_EQ(found->histogram, histogram) << threads;
    EXPECT_EQ(found->remote, remote) << threads;
  }
}

TEST(GapVertices, CancelledIsCancelled) {
  const PointCloud cloud = SphereWithHoleAndBuriedPoints(20000, 0);
  const NetsOfCloud nets = Nets(cloud);
  CancelToken cancel;
  cancel.Cancel();
  for (const int threads : {1, 2})
    EXPECT_EQ(FindGapVertices(nets.mesh, cloud.points, 2 * nets.voxel_size, 5, false, 1,
                              threads, cancel)
                  .status()
                  .code(),
              absl::StatusCode::kCancelled);
}

TEST(HoleCapsThreads, TheCapsAreTheSameOnAnyThreadCount) {
  const PointCloud cloud = SphereWithHoleAndBuriedPoints(20000, 300);
  const NetsOfCloud nets = Nets(cloud);
  TriangleMesh one = nets.mesh;
  HoleCapStats one_stats;
  ASSERT_TRUE(CapHoles(one, nets.voxel_size, cloud.points, {}, &one_stats).ok());
  EXPECT_EQ(one_stats.regions, 1);
  EXPECT_NE(one.vertices, nets.mesh.vertices);
  // Every solve split into ranges too (split_solve_vertices 1): its sums stay in order.
  HoleCapOptions split;
  split.split_solve_vertices = 1;
  for (const int threads : {2, 3}) {
    TriangleMesh many = nets.mesh;
    HoleCapStats stats;
    ASSERT_TRUE(CapHoles(many, nets.voxel_size, cloud.points, split, &stats,
                         CancelToken::Never(), threads)
                    .ok());
    EXPECT_EQ(many.vertices, one.vertices) << threads;
    EXPECT_EQ(stats.regions, one_stats.regions) << threads;
    EXPECT_EQ(stats.vertices, one_stats.vertices) << threads;
    EXPECT_EQ(stats.anchors, one_stats.anchors) << threads;
  }
}

}  // namespace
}  // namespace membrane
