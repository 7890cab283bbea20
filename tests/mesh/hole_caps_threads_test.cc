// The caps on several threads (core/mesh/hole_caps.h, `threads`): every solve split into
// ranges (split_solve_vertices 1) and every crossing search on 2 or 3 threads give the mesh
// the calling thread alone gives, bit for bit, and so do solves whose sums go by blocks
// (split_solve_vertices 64). The case: a box whose base the scanner did not
// see, with a one-voxel tunnel from the base up to the top face (hole_caps_tube_test.cc), so
// that the cap wraps, its tube is solved apart and its rim's crossings back off. The points
// are the box's outer surface-nets vertices off the base's hole: no shrink is needed, and the
// test runs in the ThreadSanitizer job.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/mesh/hole_caps.h"
#include "core/mesh/surface_nets.h"
#include "gtest/gtest.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

struct Capped {
  TriangleMesh mesh;
  HoleCapStats caps;
};

Capped Cap(const TriangleMesh& nets, const std::vector<Point3f>& points, int threads,
           int64_t split) {
  Capped c{nets, {}};
  HoleCapOptions options;
  options.split_solve_vertices = split;
  EXPECT_TRUE(CapHoles(c.mesh, 1.0, points, options, &c.caps, CancelToken::Never(), threads).ok());
  return c;
}

struct BoxCase {
  TriangleMesh nets;
  std::vector<Point3f> points;
};

// The box with its tunnel, and the points of its outer faces but a disc of the base.
BoxCase BoxWithUnseenBase() {
  VoxelGrid grid = testing::OutsideGrid(52);
  testing::MarkSolid(grid, [](int x, int y, int z) {
    return x >= 8 && x < 40 && z >= 8 && z < 40 && y >= 8 && y < 28 && !(x == 24 && z == 24);
  });
  BoxCase c{SurfaceNets(grid), {}};
  Vec3d lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (const Point3f& p : c.nets.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min<double>(lo[k], p[k]);
      hi[k] = std::max<double>(hi[k], p[k]);
    }
  // The tunnel's walls hold no outer vertex.
  for (const Point3f& p : c.nets.vertices) {
    bool outer = false;
    for (int k = 0; k < 3; ++k) outer |= p[k] <= lo[k] + 0.5 || p[k] >= hi[k] - 0.5;
    const double dx = p[0] - 0.5 * (lo[0] + hi[0]), dz = p[2] - 0.5 * (lo[2] + hi[2]);
    if (outer && !(p[1] <= lo[1] + 0.5 && dx * dx + dz * dz < 16 * 16)) c.points.push_back(p);
  }
  return c;
}

TEST(HoleCapThreads, AWrappedCapIsTheSameOnAnyThreadCount) {
  const auto [nets, points] = BoxWithUnseenBase();
  const Capped serial = Cap(nets, points, 1, HoleCapOptions{}.split_solve_vertices);
  ASSERT_EQ(serial.caps.regions, 1);
  EXPECT_EQ(serial.caps.wrapped, 1);
  EXPECT_GT(serial.caps.tube_vertices, 0);
  EXPECT_GT(serial.caps.iterations, 0);
  EXPECT_NE(serial.mesh.vertices, nets.vertices);
  for (int threads : {1, 2, 3}) {
    const Capped split = Cap(nets, points, threads, 1);
    EXPECT_EQ(split.caps.iterations, serial.caps.iterations) << threads << " threads";
    EXPECT_EQ(split.caps.backed_off, serial.caps.backed_off) << threads << " threads";
    EXPECT_TRUE(split.mesh.vertices == serial.mesh.vertices) << threads << " threads";
  }
}

// Split at 64 vertices, a solve's dot products are summed over blocks of 64 free vertices
// (then over the blocks in order), which the threads share: the same bits on any count.
TEST(HoleCapThreads, SumsOverBlocksAreTheSameOnAnyThreadCount) {
  const auto [nets, points] = BoxWithUnseenBase();
  const Capped one = Cap(nets, points, 1, 64);
  ASSERT_EQ(one.caps.regions, 1);
  EXPECT_GT(one.caps.vertices, 8 * 64);  // blocks enough for every thread
  EXPECT_GT(one.caps.iterations, 0);
  for (int threads : {2, 3}) {
    const Capped split = Cap(nets, points, threads, 64);
    EXPECT_EQ(split.caps.iterations, one.caps.iterations) << threads << " threads";
    EXPECT_TRUE(split.mesh.vertices == one.mesh.vertices) << threads << " threads";
  }
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
