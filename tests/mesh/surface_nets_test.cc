#include "core/mesh/surface_nets.h"

#include <cmath>
#include <utility>
#include <vector>

#include "core/engine/voxel_topology.h"
#include "core/mesh/diagonal_bridging.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/smooth_surface.h"
#include "gtest/gtest.h"
#include "tests/mesh/surface_expectations.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

using namespace membrane::testing;

// The smooth surface, without the fit (the voxel-only part of recipe 3) or with it, fitted to
// points on the boundary voxels' centres, shifted a little so that every vertex moves.
TriangleMesh Smooth(const VoxelGrid& grid, bool fit, bool remove_loose_sheets) {
  std::vector<Point3f> points;
  for (int64_t i = 0; i < grid.size(); ++i)
    if (IsBoundary(grid.at(i))) {
      const auto c = grid.Center(grid.CoordOf(i));
      points.push_back({float(c[0] + 0.21), float(c[1] - 0.13), float(c[2] + 0.08)});
    }
  SmoothSurfaceOptions options;
  options.fit = fit;
  options.remove_loose_sheets = remove_loose_sheets;
  absl::StatusOr<TriangleMesh> mesh = SmoothSurface(grid, points, options);
  EXPECT_TRUE(mesh.ok()) << mesh.status();
  return mesh.ok() ? *std::move(mesh) : TriangleMesh{};
}

// Both surfaces keep every promise, with the given topology.
void ExpectValidSmoothSurfaces(const VoxelGrid& grid, int shells, std::vector<int> genus,
                               bool remove_loose_sheets = true) {
  {
    SCOPED_TRACE("unfitted");
    ExpectValidSurface(Smooth(grid, false, remove_loose_sheets), shells, genus);
  }
  {
    SCOPED_TRACE("fitted");
    ExpectValidSurface(Smooth(grid, true, remove_loose_sheets), shells, genus);
  }
}

TEST(SurfaceNets, OfBallIsClosedManifoldSphereBeforeAndAfterFitting) {
  ExpectValidSmoothSurfaces(BallGrid(24, 8.3), 1, {0});
}

TEST(SurfaceNets, OfSolidTorusHasGenusOne) {
  ExpectValidSmoothSurfaces(SolidTorusGrid(32, 9, 3.5), 1, {1});
}

// A membrane given up is cleaned in place and freed: the same mesh as from a copy, and the
// caller's grid is left empty (its bytes are not held through the caps and the fit).
TEST(SmoothSurface, FromAGivenUpGridIsTheCopysMeshAndFreesTheGrid) {
  const VoxelGrid torus = SolidTorusGrid(40, 12, 4);
  std::vector<Point3f> points;
  for (int64_t i = 0; i < torus.size(); ++i)
    if (IsBoundary(torus.at(i))) {
      const auto c = torus.Center(torus.CoordOf(i));
      points.push_back({float(c[0] + 0.21), float(c[1] - 0.13), float(c[2] + 0.08)});
    }
  absl::StatusOr<TriangleMesh> copied = SmoothSurface(torus, points);
  ASSERT_TRUE(copied.ok()) << copied.status();
  VoxelGrid given = torus;
  absl::StatusOr<TriangleMesh> moved = SmoothSurface(std::move(given), points);
  ASSERT_TRUE(moved.ok()) << moved.status();
  EXPECT_EQ(given.size(), 0);
  EXPECT_EQ(moved->vertices, copied->vertices);
  EXPECT_EQ(moved->faces, copied->faces);
  EXPECT_FALSE(copied->faces.empty());
}

TEST(SurfaceNets, SameMeshOnAnyThreadCount) {
  // The boundary scan runs layer by layer on the threads; the quads are numbered in index
  // order on the calling thread. Random solids hold every corner configuration (split fans,
  // edge midpoints) in many layers.
  for (uint32_t seed : {1u, 2u}) {
    const VoxelGrid grid = RandomSolidGrid(36, 0.35, seed);
    const UnrepairedSurfaceNets one = SurfaceNetsBeforeRepair(grid, 1);
    ASSERT_GT(one.mesh.faces.size(), 1000u);
    for (int threads : {2, 3}) {
      const UnrepairedSurfaceNets many = SurfaceNetsBeforeRepair(grid, threads);
      EXPECT_EQ(many.mesh.vertices, one.mesh.vertices) << threads << " threads, seed " << seed;
      EXPECT_EQ(many.mesh.faces, one.mesh.faces) << threads << " threads, seed " << seed;
      EXPECT_EQ(many.fallback, one.fallback) << threads << " threads, seed " << seed;
      EXPECT_EQ(many.corner_contacts, one.corner_contacts);
    }
  }
}

TEST(SurfaceNets, SameMeshOnAnyThreadCountWithTheMortonSortSplit) {
  // Enough vertices that the Morton order sorts two halves on two threads and merges them.
  const VoxelGrid grid = RandomSolidGrid(72, 0.35, 3);
  const UnrepairedSurfaceNets one = SurfaceNetsBeforeRepair(grid, 1);
  ASSERT_GT(one.mesh.vertices.size(), size_t{1} << 17);
  for (int threads : {2, 3}) {
    const UnrepairedSurfaceNets many = SurfaceNetsBeforeRepair(grid, threads);
    EXPECT_EQ(many.mesh.vertices, one.mesh.vertices) << threads << " threads";
    EXPECT_EQ(many.mesh.faces, one.mesh.faces) << threads << " threads";
    EXPECT_EQ(many.fallback, one.fallback) << threads << " threads";
  }
}

TEST(SurfaceNets, OfTwoBallsHasTwoShells) {
  ExpectValidSmoothSurfaces(TwoBallsGrid(32, 6, 3), 2, {0, 0});
}

TEST(SurfaceNets, OfTwoBallsOneVoxelApartHasTwoShells) {
  // Nearest voxel centres two apart: a 1-voxel outside gap that pairing on the inside point
  // would have closed.
  ExpectValidSmoothSurfaces(TwoBallsGrid(32, 6, 1), 2, {0, 0});
}

TEST(SurfaceNets, OfEdgeContactIsClosedManifoldOneShell) {
  ExpectValidSmoothSurfaces(EdgeContactGrid(), 1, {0}, /*remove_loose_sheets=*/false);
}

TEST(SurfaceNets, OfCornerContactIsOneShellAfterBridging) {
  ExpectValidSmoothSurfaces(CornerContactGrid(), 1, {0}, /*remove_loose_sheets=*/false);
}

TEST(SurfaceNets, OfThickEdgeContactIsOneShell) {
  ExpectValidSmoothSurfaces(ThickEdgeContactGrid(), 1, {0});
}

TEST(SurfaceNets, OfThickCornerContactIsOneShell) {
  ExpectValidSmoothSurfaces(ThickCornerContactGrid(), 1, {0});
}

TEST(SurfaceNets, OfPinholeBoxIsOneSphere) {
  ExpectValidSmoothSurfaces(PinholeBoxGrid(16, 3), 1, {0});
}

TEST(SurfaceNets, WithoutBridgingSplitsACornerContact) {
  // Documents why bridging exists: the raw nets cannot join voxels meeting at a corner.
  ExpectValidSurface(SurfaceNets(CornerContactGrid()), 2, {0, 0});
}

TEST(SurfaceNets, VerticesLieInTheirCells) {
  const VoxelGrid g = BallGrid(20, 6.5);
  const TriangleMesh m = SurfaceNets(g);
  ASSERT_FALSE(m.vertices.empty());
  for (const Point3f& p : m.vertices) {
    // Every vertex lies in a cube of voxel centres: within 1/2 of a lattice corner per axis.
    for (int k = 0; k < 3; ++k) {
      const double frac = p[k] - std::round(p[k]);
      EXPECT_LE(std::fabs(frac), 0.5 + 1e-6);
    }
  }
}

TEST(SurfaceNets, MatchesVoxelTopologyOnRandomSolids) {
  int bridged_all = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    for (double p : {0.15, 0.35, 0.55, 0.75}) {
      VoxelGrid g = RandomSolidGrid(12, p, seed);
      const VoxelTopology before = ComputeVoxelTopology(g);
      const BridgingResult bridging = BridgeDiagonalContacts(g);
      const VoxelTopology after = ComputeVoxelTopology(g);
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " p " << p);
      ASSERT_EQ(after.shells, before.shells);
      ASSERT_EQ(after.genus, before.genus);
      const TriangleMesh m = SurfaceNets(g);
      if (bridging.remaining == 0) {
        ++bridged_all;
        ExpectValidSurface(m, after.shells, after.genus);
      } else {
        // Unbridged corner contacts split the shell; everything else still holds.
        const MeshReport r = CheckMesh(m);
        EXPECT_TRUE(r.closed && r.manifold && r.oriented && r.positive_volume)
            << MeshReportToJson(r);
        EXPECT_EQ(r.self_intersections, 0) << MeshReportToJson(r);
      }
      if (HasFailure()) return;
    }
  }
  EXPECT_GT(bridged_all, 100);
}

}  // namespace
}  // namespace membrane
