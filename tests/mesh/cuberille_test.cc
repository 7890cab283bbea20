#include "core/mesh/cuberille.h"

#include "core/engine/voxel_topology.h"
#include "core/mesh/mesh_check.h"
#include "gtest/gtest.h"
#include "tests/mesh/surface_expectations.h"
#include "tests/mesh/test_grids.h"

namespace membrane {
namespace {

using namespace membrane::testing;

TEST(Cuberille, OfBallIsClosedManifoldSphere) {
  ExpectValidSurface(Cuberille(BallGrid(24, 8.3)), 1, {0});
}

TEST(Cuberille, OfSolidTorusHasGenusOne) {
  ExpectValidSurface(Cuberille(SolidTorusGrid(32, 9, 3.5)), 1, {1});
}

TEST(Cuberille, OfTwoBallsHasTwoShells) {
  ExpectValidSurface(Cuberille(TwoBallsGrid(32, 6, 3)), 2, {0, 0});
}

TEST(Cuberille, OfEdgeContactIsClosedManifoldOneShell) {
  ExpectValidSurface(Cuberille(EdgeContactGrid()), 1, {0});
}

TEST(Cuberille, OfCornerContactIsClosedManifoldOneShell) {
  ExpectValidSurface(Cuberille(CornerContactGrid()), 1, {0});
}

TEST(Cuberille, OfThickEdgeContactIsOneShell) {
  ExpectValidSurface(Cuberille(ThickEdgeContactGrid()), 1, {0});
}

TEST(Cuberille, OfThickCornerContactIsOneShell) {
  ExpectValidSurface(Cuberille(ThickCornerContactGrid()), 1, {0});
}

TEST(Cuberille, OfPinholeBoxIsOneSphere) {
  ExpectValidSurface(Cuberille(PinholeBoxGrid(16, 3)), 1, {0});
}

TEST(Cuberille, UsesModelUnits) {
  VoxelGrid g({7, 7, 7}, {10, 20, 30}, 0.5, OutsideState(0));
  g.set(Coord{3, 3, 3}, kBoundaryHard);
  const TriangleMesh m = Cuberille(g);
  ASSERT_EQ(m.vertices.size(), 8u);
  for (const auto& v : m.vertices) {
    EXPECT_TRUE(v[0] == 11.5f || v[0] == 12.0f);
    EXPECT_TRUE(v[1] == 21.5f || v[1] == 22.0f);
    EXPECT_TRUE(v[2] == 31.5f || v[2] == 32.0f);
  }
  EXPECT_NEAR(CheckMesh(m).volume, 0.125, 1e-6);
}

TEST(Cuberille, OfEmptyGridIsEmpty) { EXPECT_TRUE(Cuberille(OutsideGrid(6)).faces.empty()); }

TEST(Cuberille, MatchesVoxelTopologyOnRandomSolids) {
  // Random solids hold every local configuration: edge and corner contacts, checkerboards,
  // handles and many shells.
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    for (double p : {0.15, 0.35, 0.55, 0.75}) {
      const VoxelGrid g = RandomSolidGrid(12, p, seed);
      const VoxelTopology topo = ComputeVoxelTopology(g);
      SCOPED_TRACE(::testing::Message() << "seed " << seed << " p " << p);
      ExpectValidSurface(Cuberille(g), topo.shells, topo.genus);
      if (HasFatalFailure() || HasNonfatalFailure()) return;
    }
  }
}

}  // namespace
}  // namespace membrane
