// The caps on several threads (core/mesh/hole_caps.h, `threads`): every solve split into
// ranges (split_solve_vertices 1) and every crossing search on 2 or 3 threads give the mesh
// the calling thread alone gives, bit for bit: a thin tube in a wrapped cap solved apart, and
// a cap creased into an edge under a shelf whose crossings back off and settle (a sphere's
// spline cap: gap_vertices_test.cc).
#include <random>
#include <vector>

#include "absl/status/statusor.h"
#include "core/base/cancel_token.h"
#include "core/mesh/hole_caps.h"
#include "core/mesh/surface_nets.h"
#include "gtest/gtest.h"
#include "tests/mesh/box_cloud.h"
#include "tests/mesh/cloud_surface.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

struct Capped {
  TriangleMesh mesh;
  HoleCapStats caps;
};

// `nets` capped over the holes of `points` with `options` on `threads`, each solve split when
// it has at least `split` vertices.
Capped Cap(const TriangleMesh& nets, double voxel_size, const std::vector<Point3f>& points,
           HoleCapOptions options, int threads, int64_t split) {
  Capped c{nets, {}};
  options.split_solve_vertices = split;
  EXPECT_TRUE(
      CapHoles(c.mesh, voxel_size, points, options, &c.caps, CancelToken::Never(), threads).ok());
  return c;
}

// The serial caps, then split on 1 to 3 threads: the same.
Capped ExpectTheSameOnAnyCount(const TriangleMesh& nets, double voxel_size,
                               const std::vector<Point3f>& points,
                               const HoleCapOptions& options = {}) {
  const Capped serial =
      Cap(nets, voxel_size, points, options, 1, HoleCapOptions{}.split_solve_vertices);
  EXPECT_GE(serial.caps.regions, 1);
  EXPECT_GT(serial.caps.iterations, 0);
  for (int threads : {1, 2, 3}) {
    const Capped split = Cap(nets, voxel_size, points, options, threads, 1);
    EXPECT_EQ(split.caps.iterations, serial.caps.iterations) << threads << " threads";
    EXPECT_EQ(split.caps.backed_off, serial.caps.backed_off) << threads << " threads";
    EXPECT_TRUE(split.mesh.vertices == serial.mesh.vertices) << threads << " threads";
  }
  return serial;
}

TEST(HoleCapThreads, AWrappedCapsTubeIsTheSameOnAnyCount) {
  // A box over a one-voxel tunnel from its unscanned base to its top (hole_caps_tube_test.cc).
  VoxelGrid grid = testing::OutsideGrid(52);
  testing::MarkSolid(grid, [](int x, int y, int z) {
    return x >= 8 && x < 40 && z >= 8 && z < 40 && y >= 8 && y < 28 && !(x == 24 && z == 24);
  });
  const TriangleMesh nets = SurfaceNets(grid);
  Vec3d lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (const Point3f& p : nets.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min<double>(lo[k], p[k]);
      hi[k] = std::max<double>(hi[k], p[k]);
    }
  std::mt19937_64 rng(3);
  const PointCloud cloud = testing::BoxFacePoints(lo, hi, 40, rng, [&](const Vec3d& p) {
    const double dx = p[0] - 0.5 * (lo[0] + hi[0]), dz = p[2] - 0.5 * (lo[2] + hi[2]);
    return p[1] > lo[1] + 1e-9 || dx * dx + dz * dz >= 16 * 16;
  });
  EXPECT_GT(ExpectTheSameOnAnyCount(nets, 1.0, cloud.points).caps.tube_vertices, 0);
}

TEST(HoleCapThreads, ABackedOffCapIsTheSameOnAnyCount) {
  absl::StatusOr<testing::ShelvedHole> shelved =
      testing::ShelvedHoleOverTheEdge(testing::Shelf{0.6, 0.8}, 0.6, 0.05);
  ASSERT_TRUE(shelved.ok()) << shelved.status();
  HoleCapOptions options;
  options.untangle_rounds = 0;  // every crossing backs off, then settles
  const Capped serial =
      ExpectTheSameOnAnyCount(shelved->nets, 0.05, shelved->holed.points, options);
  EXPECT_GT(serial.caps.backed_off, 100);
  EXPECT_GT(serial.caps.settled, 0);
}

TEST(HoleCapThreads, RefusesASplitBelowOneVertex) {
  TriangleMesh mesh;
  const std::vector<Point3f> points{{0, 0, 0}};
  HoleCapOptions options;
  options.split_solve_vertices = 0;
  const absl::Status status = CapHoles(mesh, 1.0, points, options);
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(status.message().find("split_solve_vertices 0"), std::string::npos) << status;
}

}  // namespace
}  // namespace membrane
